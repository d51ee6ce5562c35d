// The gains Lawson's sweeps test (core/image/lawson.h), computed with what successive tests share
// kept: for Sederberg's cost and face-SCF each edge's share per channel (a gain's "before"
// half is the share of the edge and its four neighbours), and for every cost the vertices'
// coordinates (on the grid no division by the width; or the explicit positions, read once
// per vertex). Variance's gain reads only e's two triangles and keeps nothing. The formulas are glsl/image/sederberg.h's and glsl/image/content_cost.h's with the same
// operands in the same order, so every gain equals flipGainOf's bit for bit, and so do the
// flips.
#pragma once

#include <cstdint>
#include <vector>

#include "cost.h"
#include "divide_by.h"
#include "mesh.h"

namespace ddt {

class FlipGains {
public:
    // The costs of every edge of `mesh` as it is now.
    FlipGains(const Mesh& mesh, const CostField& field, CostFunction cost = CostFunction::sederberg);

    // meshCost(mesh, field, cost) for the mesh as it is now.
    double total() const;
    // flipGainOf(mesh, field, e, cost) for the mesh as it is now.
    double gainOf(uint32_t e);
    // After flipEdge(mesh, e) right after gainOf(e): the five edges whose triangles changed
    // take the costs that gain computed. Returns gainOf(e) for the mesh as it is now, the gain
    // of flipping e back, bit for bit (+infinity for variance, which keeps no costs: unknown).
    double flipped(uint32_t e);

private:
    struct Channel {
        const std::vector<float>& values;
        std::vector<double> costs;  // per edge (empty for variance); 0 on the hull
        double after[5];            // the last gain's new costs of its edges `changed_`
    };

    // The constructor's costs, gainOf's two cases, for the mesh's places (positioned: explicit
    // positions; else the grid's pixel centres), each compiled apart.
    template <bool positioned>
    void keepCosts(bool face_weighted);
    template <bool positioned>
    double scfGainOf(uint32_t e);
    template <bool positioned>
    double varianceGainOf(uint32_t e) const;

    const Mesh& mesh_;
    const CostField& field_;
    CostFunction cost_;
    DivideBy by_width_;             // the grid's places: vertex id → pixel centre
    const Position* positions_;     // the explicit positions, or nullptr on the grid
    std::vector<Channel> channels_;  // luma, then alpha if any
    uint32_t changed_[5] = {kNone};  // the last gain's edge e and its neighbours bl, la, ar, rb
};

}  // namespace ddt
