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
    AxisTaps apply_x_, apply_y_, transpose_x_, transpose_y_;
    uint32_t transpose_rows_;  // the most input rows one output row of Dᵀ along y gathers
};

}  // namespace ddt
