// The gains Lawson's sweeps test (core/lawson.h), computed with what successive tests share
// kept: each edge's cost per channel (a gain's "before" half is the cost of the edge and its
// four neighbours) and the vertices' coordinates (no division by the width). The formulas are
// glsl/sederberg.h's with the same operands in the same order, so every gain equals
// flipGainOf's bit for bit, and so do the flips.
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
    FlipGains(const Mesh& mesh, const CostField& field);

    // meshCost(mesh, field) for the mesh as it is now.
    double total() const;
    // flipGainOf(mesh, field, e) for the mesh as it is now.
    double gainOf(uint32_t e);
    // After flipEdge(mesh, e) right after gainOf(e): the five edges whose triangles changed
    // take the costs that gain computed.
    void flipped(uint32_t e);

private:
    struct Channel {
        const std::vector<float>& values;
        std::vector<double> costs;  // per edge; 0 on the hull
        double after[5];            // the last gain's new costs of its edges `changed_`
    };

    const Mesh& mesh_;
    DivideBy by_width_;
    std::vector<Channel> channels_;  // luma, then alpha if any
    uint32_t changed_[5] = {kNone};  // the last gain's edge e and its neighbours bl, la, ar, rb
};

}  // namespace ddt
