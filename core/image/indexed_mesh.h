// The optimised mesh as mesh files hold it (`--mesh`, core/io/mesh_file.h): vertices with
// positions and colours, triangles as vertex indices.
//
// Conventions, chosen for viewers (MeshLab, Blender, assimp) and stated in every file:
// - Positions in output pixels with y up: a vertex at input position (x, y) (pixel centres at
//   integers; a simplified mesh's vertices may lie between them) sits at
//   ((x + 0.5)·sx, H − (y + 0.5)·sy), sx = W/w and sy = H/h the realised factors of the
//   W × H output. A viewer shows the picture upright.
// - Triangles counter-clockwise seen from +z (front-facing in y-up viewers). The mesh's own
//   triangles are positive in its y-down frame (core/image/mesh.h), so flipping y reverses them.
// - A ring of border triangles extends the mesh from the hull of the pixel centres to the
//   image rectangle [0, W] × [0, H]: each hull vertex gets a copy on the rectangle's side, with
//   its colour, and each corner pixel a copy at the rectangle's corner. The renderer clamps a
//   sample outside the hull to the nearest hull point (core/image/render.h), which is exactly what
//   the ring interpolates, so the mesh covers what the raster covers with the same values.
// - Colours straight (not premultiplied), as the input stores them: [0, 1] for 8- and 16-bit
//   inputs, any value for half and float ones. They are the input's pixel values, so the
//   surface the file describes is plain DDT's (`--reconstruct plain`): the consistent
//   reconstruction's edge bubbles are quadratic and have no place in these formats.
// - z = 0, or luma × height for a 2.5-D view (`--mesh-height`): luma = 0.2126 R + 0.7152 G +
//   0.0722 B (Rec. 709's weights, applied to the stored values), the value itself for grey.
#pragma once

#include <cstdint>
#include <vector>

#include "image.h"
#include "mesh.h"
#include "render.h"

namespace ddt {

struct IndexedMesh {
    uint32_t channels = 0;                    // per vertex colour: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
    SampleType colour_type = SampleType::UInt8;  // the input's, which files store colours as
    OutputSize out;                           // the rectangle covered: [0, out.width] × [0, out.height]
    std::vector<double> positions;            // x, y, z per vertex
    std::vector<float> colours;               // `channels` per vertex, straight
    std::vector<uint32_t> faces;              // three vertex indices per triangle, counter-clockwise

    uint32_t vertexCount() const { return uint32_t(positions.size() / 3); }
    uint32_t faceCount() const { return uint32_t(faces.size() / 3); }
};

// The mesh of `triangles` (three vertex ids each, positive in the grid's y-down frame, as
// core/image/mesh.h's triangles are) over the pixel grid of `input` (vertex id y·width + x of the
// whole input, which tiles stitched together use too), each vertex at `positions` (explicit,
// per id: a simplified mesh's) or else at its pixel centre, coloured by `input`'s pixels, for
// an output of size `out`, with z = luma × `height` (0: flat). The vertices the triangles use
// come first, in id order (all the pixels, unless the mesh was simplified); the ring's follow.
// A vertex at input position (x, y) lies at output ((x + 0.5)·sx, H − (y + 0.5)·sy).
IndexedMesh indexedMeshOf(const std::vector<uint32_t>& triangles, const std::vector<Position>& positions,
                          const Image& input, OutputSize out, double height = 0.0);

// The mesh file of a sample mesh (a mask's known pixels, a point file's points; core/delaunay/)
// optimised: its triangles only, without a ring, as the hull of the samples need not reach
// the image's rectangle (the raster fills outside the hull from its nearest rendered pixels,
// core/delaunay/sampled_render.h, which no mesh of these formats can say). `values` holds
// the vertex values by id, premultiplied: a frame-sized image (ids y · width + x) or one value
// per vertex; positions are the mesh's, in the `frame` of input pixels that `out` magnifies.
IndexedMesh indexedSampleMeshOf(const Mesh& mesh, const Image& values, OutputSize frame, OutputSize out,
                                double height = 0.0);

// The triangles indexedMeshOf makes from a triangulation of all a width × height grid's
// vertices: the grid's 2(w − 1)(h − 1), two per hull segment and two per corner (a simplified
// mesh makes fewer).
inline uint64_t indexedFaceCount(uint32_t width, uint32_t height) {
    return 2 * uint64_t(width - 1) * (height - 1) + 4 * uint64_t(width - 1) + 4 * uint64_t(height - 1) + 8;
}

}  // namespace ddt
