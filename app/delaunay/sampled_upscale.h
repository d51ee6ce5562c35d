// `--mask`: magnifying an image from some of its pixels. The known pixels are triangulated
// (core/delaunay/: the exact Delaunay triangulation, with the symbolic tie-break that makes a
// full mask today's grid), the backend optimizes that mesh with the same flips as the grid's,
// and the host renders it (core/delaunay/sampled_render.h): the plain DDT surface inside the
// known pixels' hull, the nearest rendered value outside it. The unknown pixels' values are
// never read.
//
// Here the image is processed in one piece: a point file's samples, a mask's that fits the
// backend's working memory, whose mesh --mesh writes or that is simplified. Larger masks go in tiles whose crops
// grow around their holes (app/delaunay/sampled_tile.h). The consistent reconstruction does not
// apply (it corrects each pixel against its own value, which an unknown pixel does not have).
#pragma once

#include <functional>

#include "tiled_upscale.h"

namespace ddt {

// The known pixels of `mask` (the same size as the image): the ids y·width + x where any colour
// channel is non-zero (a fully transparent mask pixel is unknown), ascending.
std::vector<uint32_t> knownPixels(const Image& mask);

// `--simplify R`, `--max-error E` on the optimised triangulation of samples, by the backend
// (Backend::simplify) as an image's is (app/simplified_upscale.h), in one piece: to a fraction R
// of the samples (at least 3; 0: as few as the hull allows) or as far as E allows. The samples'
// hull stays as it is (core/simplify/edge_collapse.h), so every sample is still rendered by
// the mesh, and the kept vertices' colours are fitted to the samples (colour_fit.h).
struct SampleSimplification {
    double fraction = 0.0, max_error = 0.0;
    ParallelSimplifyStats stats;  // on return
    Image values;                 // on return: the vertices' colours, by vertex id, as `image` holds the samples'
};

// The vertices a fraction of `samples` asks for.
uint32_t simplifiedSampleCount(uint32_t samples, double fraction);

// Optimizes `initial` (a triangulation of some of `image`'s pixels) on `backend`, simplifies it
// if `simplification` is given, and sends the output of size `out` to `sink` in bands; the
// mesh goes to `optimized` if given (for `--mesh`). Throws UserError when the image is too
// large for the backend in one piece.
OptimizeStats upscaleFromSamples(Backend& backend, const Image& image, Mesh initial, OutputSize out,
                                 const std::function<void(OutputRows&& rows)>& sink, const TileStepCallback& on_step = {},
                                 Mesh* optimized = nullptr, SampleSimplification* simplification = nullptr);

}  // namespace ddt
