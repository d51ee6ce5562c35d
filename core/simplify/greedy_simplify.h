// Serial greedy simplification, the quality reference for the parallel rule (as
// core/image/lawson.h is for the flips): Garland and Heckbert's loop — always the legal collapse of
// least quadric error next (core/simplify/quadric.h), ties by edge id and then b into a first —
// until at most the target count of vertices is left. Each vertex starts with the quadric of
// its triangles; a collapse adds `from`'s quadric to `to`'s. The merged vertex goes where the
// summed quadric is least, if that is legal, else stays at `to`'s place (placement.h); the
// cost is the summed quadric there. The mesh's positions become explicit (core/image/mesh.h).
#pragma once

#include <cstdint>

#include "image.h"
#include "mesh.h"

namespace ddt {

struct SimplifyStats {
    uint32_t vertices_before = 0, vertices_after = 0;
    uint64_t collapses = 0;
    double last_cost = 0.0;  // the error of the last collapse: what the next vertex would have cost at least
};

// The vertices a mesh uses (a simplified mesh keeps a subset of the grid's).
uint32_t usedVertexCount(const Mesh& mesh);

// Simplifies `mesh` down to at most `target` vertices, or as far as legal collapses go (the
// four corners stay); the result is compacted (core/simplify/edge_collapse.h). `values` holds
// the picture's pixels, the vertices' colours, on entry; on return each kept vertex has the
// colour its quadric calls for where it stands (the least-squares colour of the planes it
// absorbed), within [0, 1] for integer sample types and, premultiplied, within its alpha.
// The mesh's sides must be at most kMaxPositionedSide (glsl/fixed_position.h).
//
// With `max_error` > 0, no collapse is made whose error exceeds it, as a root-mean-square
// distance to the planes the merged vertices stood for, in 8-bit levels (1/255 of the colour
// range; colour dominates the distance, see quadric.h): simplification stops where every
// remaining collapse would cost more, or at `target`, whichever comes first.
SimplifyStats simplifySerial(Mesh& mesh, Image& values, uint32_t target, double max_error = 0.0);

// What a simplification by simplifySerial holds beyond the optimised mesh it starts from, per
// pixel of a grid mesh with `channels` channels: the copy of the mesh it works on (3 edges of
// 32 + 16 bytes, as the CPU backend counts its own), each vertex's quadric (232), explicit
// position (8) and first edge (4), each edge's version (4) and its queued candidates (at the
// peak 2.6 per edge, measured on a 1000 × 750 photograph simplified to 0.1, 24 bytes each, in
// a vector that may have doubled: 125), the copy of the values (4 per channel) and the colour
// fit's sample of each pixel (24). Measured: 733 to 786 bytes per pixel above the same run
// without --simplify (400², 1000 × 750 and 2000 × 1500 RGB photographs; 811 counted here).
constexpr uint64_t simplifyBytesPerPixel(uint32_t channels) {
    return 3 * (32 + 16) + 232 + 8 + 4 + 3 * (4 + 125) + 4 * uint64_t(channels) + 24;
}

}  // namespace ddt
