// Filling the pixels a mesh does not cover: each takes the value of the nearest covered pixel
// (Euclidean distance between pixel centres). A triangulation of samples covers only their
// convex hull; outside it the output holds the hull's nearest value, as the grid's renderer
// clamps samples into its rectangle.
#pragma once

#include <cstdint>

namespace ddt {

// `pixels`: width × height pixels of `channels` floats; a pixel whose first channel is NaN is
// uncovered (the readers refuse NaN, so no rendered value is one). Each uncovered pixel gets
// a copy of the nearest covered one's channels; ties go to the smaller column, then the
// smaller row. Nothing changes if no pixel is covered. Exact: the squared distances are
// integers, compared without rounding (Felzenszwalb and Huttenlocher's lower envelope of
// parabolas, "Distance Transforms of Sampled Functions", 2012, with the minimiser kept).
void fillFromNearest(float* pixels, uint32_t width, uint32_t height, uint32_t channels);

}  // namespace ddt
