#version 460
#extension GL_GOOGLE_include_directive : require
// The surface at every supersample, unclamped (the model sees the surface the solver moves).
#include "../common.glsl"
#include "surface.glsl"

void main() {
    const uint count = supersampledWidth() * supersampledHeight();
    for (uint i = gl_GlobalInvocationID.x; i < count; i += invocationStride()) {
        const uvec4 hit = imageLoad(hits, int(i));
        const uvec3 ids = slotVertices(hit.x), edges = slotEdges(hit.x);
        const vec4 value = quadraticSurface(
            uintBitsToFloat(hit.yzw), imageLoad(surface_values, int(ids.x)), imageLoad(surface_values, int(ids.y)),
            imageLoad(surface_values, int(ids.z)), imageLoad(bubbles, int(edges.x)), imageLoad(bubbles, int(edges.y)),
            imageLoad(bubbles, int(edges.z)));
        imageStore(supersamples, int(i), value);
    }
}
