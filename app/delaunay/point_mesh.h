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

#include "image.h"
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

// Checks, merges and triangulates `points` in `frame` (sides of at most kMaxDelaunaySide).
// Throws UserError("reason"), one line without a file name, for a point outside the frame,
// two points at one place with different values, and points with no triangulation
// (fewer than 3 distinct, or all collinear).
SampledPoints triangulatePoints(const PointSamples& points, Frame frame);

}  // namespace ddt
