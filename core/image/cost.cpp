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

// Sederberg's or face-SCF's share of an interior edge, for one channel.
double channelEdgeCost(const std::vector<float>& z, const EdgeVertices& v, Places places, bool face_weighted) {
    Gradient left = planeGradient(v.a, v.b, v.l, z[v.a], z[v.b], z[v.l], places);
    Gradient right = planeGradient(v.b, v.a, v.r, z[v.b], z[v.a], z[v.r], places);
    return pairCost(left, right, face_weighted);
}

// Variance's share of e, for one channel: the cost of the triangles it reports, left then right.
double channelVarianceShare(const std::vector<float>& z, const EdgeVertices& v, bool left, bool right,
                            Places places) {
    double share = 0.0;
    if (left) share += varianceCost(v.a, v.b, v.l, z[v.a], z[v.b], z[v.l], places);
    if (right) share += varianceCost(v.b, v.a, v.r, z[v.b], z[v.a], z[v.r], places);
    return share;
}

}  // namespace

const char* costFunctionName(CostFunction cost) {
    switch (cost) {
        case CostFunction::sederberg: return "sederberg";
        case CostFunction::variance: return "variance";
        case CostFunction::face_scf: return "face-scf";
    }
    return "?";
}

std::optional<CostFunction> parseCostFunction(const std::string& name) {
    for (CostFunction cost : {CostFunction::sederberg, CostFunction::variance, CostFunction::face_scf})
        if (name == costFunctionName(cost)) return cost;
    return std::nullopt;
}

int roiDegree(CostFunction cost) { return cost == CostFunction::variance ? 1 : 2; }

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

double edgeCost(const Mesh& mesh, const CostField& field, uint32_t e, CostFunction cost) {
    const EdgeVertices& v = mesh.vertices[e];
    const Places places = placesOf(mesh);
    if (cost == CostFunction::variance) {
        // The triangles e reports, as forEachTriangle: those of whose edges e has the lowest id.
        const EdgeNeighbours& n = mesh.neighbours[e];
        const bool left = v.l != kNone && e < n.bl && e < n.la, right = v.r != kNone && e < n.ar && e < n.rb;
        double share = channelVarianceShare(field.luma, v, left, right, places);
        if (!field.alpha.empty()) share += channelVarianceShare(field.alpha, v, left, right, places);
        return share;
    }
    if (v.l == kNone || v.r == kNone) return 0.0;
    const bool face_weighted = cost == CostFunction::face_scf;
    double share = channelEdgeCost(field.luma, v, places, face_weighted);
    if (!field.alpha.empty()) share += channelEdgeCost(field.alpha, v, places, face_weighted);
    return share;
}

double meshCost(const Mesh& mesh, const CostField& field, CostFunction cost) {
    double total = 0.0;
    for (uint32_t e = 0; e < mesh.edgeCount(); ++e) total += edgeCost(mesh, field, e, cost);
    return total;
}

double flipGainOf(const Mesh& mesh, const CostField& field, uint32_t e, CostFunction cost) {
    const FlipStencil s = flipStencil(mesh, e);
    const Places places = placesOf(mesh);
    if (!flipIsConvex(s, places)) return -std::numeric_limits<double>::infinity();
    const uint32_t id = uint32_t(cost);
    double gain = costFlipGain(id, s, stencilValues(field.luma, s), places);
    if (!field.alpha.empty()) gain += costFlipGain(id, s, stencilValues(field.alpha, s), places);
    return gain;
}

}  // namespace ddt
