// From a point file's samples (core/io/point_file.h) to what the optimizer and the renderer
// take: a Delaunay mesh with explicit positions and an image of its vertex values.
//
// The frame: points lie in input pixels with pixel centres at integers, so a width × height
// frame holds x in [0, width − 1] and y in [0, height − 1]; the output size is the frame's
// magnified. Positions are rounded to the nearest 1/kPositionOne pixel (glsl/fixed_position.h),
// the renderer's grid, and points equal after rounding are one point: merged if their values
// are equal, refused if not.
#pragma once

#include <cstdint>
#include <string>

#include "backend.h"
#include "image.h"
#include "known_samples.h"
#include "mesh.h"
#include "point_file.h"

namespace ddt {

struct Frame {
    uint32_t width = 0, height = 0;
};

// The smallest frame from pixel 0 that holds every point: ceil(largest x) + 1 wide, the same
// for y, at least 2 × 2 (the smallest image DDT magnifies). Sides beyond 32 bits saturate.
Frame frameOfPoints(const PointSamples& points);

// The distinct points' Delaunay triangulation and the vertex values (colour premultiplied, as
// images hold it). Two forms: points all on pixel centres and dense enough (point_mesh.cpp)
// give the frame's pixel mesh (positions implicit, vertex ids y · width + x) and a frame-sized
// values image; any others a mesh with explicit positions and a vertexCount() × 1 image.
struct SampledPoints {
    Mesh mesh;
    Image values;
};

// The distinct points of a file, checked and merged, ready to triangulate: the pixel form
// (pixel_ids, values frame-sized) or the general one (places in row-major order, one value
// each). Checks and merges `points` in `frame` (sides of at most kMaxDelaunaySide).
// Throws UserError("reason"), one line without a file name, for a point outside the frame,
// two points at one place with different values, and points with no triangulation
// (fewer than 3 distinct, or all collinear).
SampleSet mergePoints(const PointSamples& points, Frame frame);

// The merged points' Delaunay triangulation, where `backend` runs it (Backend::delaunayPixels).
Mesh triangulateMerged(const SampleSet& merged, Frame frame, Backend& backend);

// mergePoints, then the triangulation on the host.
SampledPoints triangulatePoints(const PointSamples& points, Frame frame);

}  // namespace ddt
