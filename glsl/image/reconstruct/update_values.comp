#version 460
#extension GL_GOOGLE_include_directive : require
// Per vertex: the projection onto its basis function, gathered from the half-edges facing it
// around its star (each written by one triangle in project_triangles), in an order fixed by
// the mesh: from its lowest-id edge one way round, then, at a vertex on the hull, the other
// way. push.step 0 stores it as the vertex's SART weight; 1 applies the step
// v += ω·Σ / weight (ω = kSartRelaxation; every vertex has weight > 0: its own pixel centre is a supersample with
// λ = 1), clamps v to its bounds and premultiplied colour to at most alpha (as core).
#include "../common.glsl"
#include "surface.glsl"

// Triangles a star walk visits at most, each way: far above any vertex degree DDT produces,
// and with kItemsPerInvocation vertices it keeps an invocation's loops below lavapipe's 65535.
const uint kMaxStarTriangles = 1024;

// The walk leaves edge e from vertex v into the triangle on its left (forward) or right
// (backward), as seen from v: that triangle's edge opposite v and its next edge around v.
struct StarStep {
    bool hull;  // no triangle there
    uint opposite, next;
};
StarStep starStep(uint e, uint vertex, bool forward) {
    const uvec4 v = verticesOf(e);
    const uvec4 n = neighboursOf(e);
    const bool left = (v.x == vertex) == forward;  // from a, forward is the left triangle (a, b, l)
    StarStep step;
    step.hull = (left ? v.z : v.w) == kNone;
    if (v.x == vertex) {
        step.opposite = left ? n.x : n.w;  // bl, or rb of (b, a, r)
        step.next = left ? n.y : n.z;      // la, or ar
    } else {
        step.opposite = left ? n.y : n.z;  // la of (a, b, l), or ar of (b, a, r)
        step.next = left ? n.x : n.w;      // bl, or rb
    }
    return step;
}

vec4 starSum(uint vertex) {
    const uint start = imageLoad(star_start, int(vertex)).x;
    vec4 sum = vec4(0);
    uint e = start;
    bool closed = false;
    for (uint i = 0; i < kMaxStarTriangles; ++i) {
        const StarStep step = starStep(e, vertex, true);
        if (step.hull) break;
        sum += imageLoad(half_edge_value_sums, int(halfEdgeFacing(step.opposite, vertex)));
        e = step.next;
        if (e == start) {
            closed = true;
            break;
        }
    }
    if (closed) return sum;
    e = start;
    for (uint i = 0; i < kMaxStarTriangles; ++i) {
        const StarStep step = starStep(e, vertex, false);
        if (step.hull) break;
        sum += imageLoad(half_edge_value_sums, int(halfEdgeFacing(step.opposite, vertex)));
        e = step.next;
    }
    return sum;
}

void main() {
    const uint count = push.width * push.height;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const vec4 sum = starSum(i);
        if (push.step == 0) {
            imageStore(value_weights, int(i), sum);
            continue;
        }
        const vec4 value = imageLoad(surface_values, int(i)) + kSartRelaxation * sum / imageLoad(value_weights, int(i));
        imageStore(surface_values, int(i),
                   colourAtMostAlpha(clamp(value, imageLoad(value_low, int(i)), imageLoad(value_high, int(i)))));
    }
}
