// `--simplify R`: the image is optimized whole, its mesh simplified to a fraction R of the
// vertices by the backend (Backend::simplify: the serial greedy simplifier on the CPU, the
// parallel rule on a device), and the output is rendered from that mesh by the same
// exact-coverage renderer: the surface linear on each triangle, with each vertex's best colour.
//
// The flips do not run again on the simplified mesh: measured, Sederberg's cost made it worse
// (PSNR against the original at ×4 from quarter size, 10 % of the vertices: astronaut 23.20 dB
// without, 22.66 with the flips again; chelsea 27.51 / 26.84; building 23.39 / 22.86; at the
// original's size, astronaut at 20 %: 41.01 / 39.04), also with the cost taken on the
// vertices' best colours (22.72, 26.78, 22.90). The consistent reconstruction (core/image/reconstruct.h) does not fit coarse
// meshes: it keeps each vertex within its 3 × 3 pixels' range, and measured on the astronaut
// at ×4 (128² → 512², PSNR against the original) it scored 21.3 dB at 10 % of the vertices
// where the linear surface scores 22.7 dB.
//
// An image too large for the backend in one piece is refused: simplified tiles would not join.
#pragma once

#include <functional>

#include "greedy_simplify.h"
#include "tiled_upscale.h"

namespace ddt {

struct SimplifiedUpscale {
    OptimizeStats optimize;   // the backend's optimization
    ParallelSimplifyStats simplify;  // rounds: 0 where the serial simplifier ran
    Image values;             // the vertices' colours (greedy_simplify.h): what a mesh file holds
};

// The vertices `fraction` of a width × height image's asks for: at least the four corners.
uint32_t simplifiedVertexCount(uint32_t width, uint32_t height, double fraction);

// `fraction` of the vertices (0: down to the corners) or as far as `max_error` allows
// (greedy_simplify.h; 0: no limit).
SimplifiedUpscale upscaleSimplified(Backend& backend, const Image& image, OutputSize out, double fraction, double max_error,
                                    const TileOptions& options, const std::function<void(OutputRows&& rows)>& sink,
                                    const TileStepCallback& on_step = {});

}  // namespace ddt
