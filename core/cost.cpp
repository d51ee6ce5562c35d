#include "cost.h"

#include <cassert>
#include <limits>

namespace ddt {

namespace {

// Rec. 601 luma weights, as the paper's "standard conversion".
const double kLumaRed = 0.299, kLumaGreen = 0.587, kLumaBlue = 0.114;

float valueAt(const std::vector<float>& channel, uint32_t vertex) {
    return vertex == kNone ? 0.0f : channel[vertex];
}

StencilValues stencilValues(const std::vector<float>& channel, const FlipStencil& s) {
    return {valueAt(channel, s.a),      valueAt(channel, s.b),      valueAt(channel, s.l),
            valueAt(channel, s.r),      valueAt(channel, s.far_bl), valueAt(channel, s.far_la),
            valueAt(channel, s.far_ar), valueAt(channel, s.far_rb)};
}

double channelEdgeCost(const std::vector<float>& z, const EdgeVertices& v, uint32_t width) {
    Gradient left = planeGradient(v.a, v.b, v.l, z[v.a], z[v.b], z[v.l], width);
    Gradient right = planeGradient(v.b, v.a, v.r, z[v.b], z[v.a], z[v.r], width);
    return sederbergCost(left, right);
}

}  // namespace

CostField costFieldOf(const Image& image) {
    CostField field;
    field.width = image.width;
    field.height = image.height;
    const size_t count = size_t(image.width) * image.height;
    field.luma.resize(count);
    if (image.hasAlpha()) field.alpha.resize(count);
    const uint32_t c = image.channels;
    for (size_t i = 0; i < count; ++i) {
        const float* p = image.pixels.data() + i * c;
        field.luma[i] = c >= 3 ? float(kLumaRed * p[0] + kLumaGreen * p[1] + kLumaBlue * p[2]) : p[0];
        if (image.hasAlpha()) field.alpha[i] = p[c - 1];
    }
    return field;
}

double edgeCost(const Mesh& mesh, const CostField& field, uint32_t e) {
    const EdgeVertices& v = mesh.vertices[e];
    if (v.l == kNone || v.r == kNone) return 0.0;
    double cost = channelEdgeCost(field.luma, v, mesh.width);
    if (!field.alpha.empty()) cost += channelEdgeCost(field.alpha, v, mesh.width);
    return cost;
}

double meshCost(const Mesh& mesh, const CostField& field) {
    double total = 0.0;
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) total += edgeCost(mesh, field, e);
    return total;
}

double flipGainOf(const Mesh& mesh, const CostField& field, uint32_t e) {
    const FlipStencil s = flipStencil(mesh, e);
    if (!flipIsConvex(s, mesh.width)) return -std::numeric_limits<double>::infinity();
    double gain = flipGain(s, stencilValues(field.luma, s), mesh.width);
    if (!field.alpha.empty()) gain += flipGain(s, stencilValues(field.alpha, s), mesh.width);
    return gain;
}

}  // namespace ddt
