// The reconstruction's degradation D (core/image/reconstruct.h) and its transpose between the
// supersampled grid (the input's size × kSupersampling per axis) and the input grid, on the CPU.
//
// Each of the four one-axis passes (D and Dᵀ, along x and along y) is a gather: every output
// sums weight · input over its own list of taps, from 0, in a fixed order. The lists are made
// once from the model; so each output is written by one task, and the sums (and so the
// results, bit for bit) do not depend on how rows are split across threads.
#pragma once

#include <cstdint>
#include <vector>

#include "reconstruct.h"

namespace ddt {

// One axis of a separable filter: output o sums weight[j] · input[index[j]] for j in
// [first[o], first[o + 1]), in that order.
struct AxisTaps {
    std::vector<uint32_t> first;
    std::vector<uint32_t> index;
    std::vector<float> weight;

    uint32_t outputs() const { return uint32_t(first.size() - 1); }
};

// Outputs of an AxisTaps along x that share one list of weights on consecutive inputs, at
// inputs and outputs in steps: output out_first + j · out_step gathers inputs
// in_first + j · in_step + t, t < weights.size() (D's interior has one such run, with
// in_step = kSupersampling; Dᵀ's one per phase of the supersamples, with out_step =
// kSupersampling). A run is summed as a filter over the row's floats, many outputs to a
// vector instruction, and each output keeps its terms in order, so its sum is the same.
struct TapRun {
    uint32_t out_first = 0, out_step = 1, in_first = 0, in_step = 1, count = 0;
    std::vector<float> weights;
};

// An AxisTaps along x split into its runs and the outputs in none (the clamped ends).
struct ColumnGather {
    AxisTaps taps;
    std::vector<TapRun> runs;
    std::vector<uint32_t> loose;  // outputs gathered one tap at a time, as taps lists them
};

class Degradation {
public:
    Degradation(uint32_t width, uint32_t height, uint32_t channels, const DegradationModel& model);

    uint32_t subWidth() const { return sub_w_; }
    uint32_t subHeight() const { return sub_h_; }

    // degraded (w × h × channels floats) = D(sub (sub_w × sub_h × channels)).
    void apply(const float* sub, float* degraded) const;
    // sub = Dᵀ(residual).
    void transpose(const float* residual, float* sub) const;

private:
    uint32_t w_, h_, c_, sub_w_, sub_h_;
    ColumnGather apply_x_, transpose_x_;
    AxisTaps apply_y_, transpose_y_;
    uint32_t transpose_rows_;  // the most input rows one output row of Dᵀ along y gathers
};

}  // namespace ddt
