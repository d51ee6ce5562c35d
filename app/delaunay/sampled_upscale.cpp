#include "sampled_upscale.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "sampled_render.h"
#include "user_error.h"

namespace ddt {

std::vector<uint32_t> knownPixels(const Image& mask) {
    // Alpha is left out: the colour is premultiplied, so a transparent pixel reads as black.
    const uint32_t colours = mask.hasAlpha() ? mask.channels - 1 : mask.channels;
    std::vector<uint32_t> known;
    for (size_t v = 0; v < size_t(mask.width) * mask.height; ++v) {
        const float* pixel = mask.pixels.data() + v * mask.channels;
        if (std::any_of(pixel, pixel + colours, [](float value) { return value != 0.0f; })) known.push_back(uint32_t(v));
    }
    return known;
}

uint32_t simplifiedSampleCount(uint32_t samples, double fraction) {
    return uint32_t(std::max<uint64_t>(3, uint64_t(std::ceil(fraction * samples))));
}

OptimizeStats upscaleFromSamples(Backend& backend, const Image& image, Mesh initial, OutputSize out,
                                 const std::function<void(OutputRows&& rows)>& sink, const TileStepCallback& on_step,
                                 Mesh* optimized, SampleSimplification* simplification) {
    // The output is rendered whole (the fill outside the hull reaches across it) beside the mesh
    // and, simplifying, the simplifier's arrays, counted per sample as for a grid of as many
    // pixels (measured: a 1600 × 1112 photograph's 1.42 M known pixels peaked at 1.18 GiB, the
    // count 1.15 GiB).
    const uint64_t output_bytes = uint64_t(out.width) * out.height * image.channels * sizeof(float),
                   simplify_bytes =
                       simplification ? backend.simplifyMemoryNeeded(usedVertexCount(initial), 1, image.channels) : 0;
    if (std::string problem =
            untiledMemoryProblem(backend, image.width, image.height, image.channels, output_bytes + simplify_bytes);
        !problem.empty())
        throw UserError(std::string("the known samples are triangulated") + (simplification ? " and simplified" : "") +
                        " in one piece: " + problem);
    if (on_step) on_step({0, 1, TilePhase::Optimize});
    backend.prepareFrom(image, std::move(initial));
    const OptimizeStats stats = backend.optimize();
    Mesh mesh = backend.takeMesh();
    const Image* values = &image;
    if (simplification) {
        simplification->values = image;
        const uint32_t target = simplifiedSampleCount(usedVertexCount(mesh), simplification->fraction);
        simplification->stats = backend.simplify(mesh, simplification->values, target, simplification->max_error);
        values = &simplification->values;
    }
    if (on_step) on_step({0, 1, TilePhase::Render});
    Image rendered = renderSampledMesh(mesh, *values, out);
    const size_t row_floats = size_t(out.width) * image.channels;
    const uint32_t band_rows = uint32_t(std::max<size_t>(1, (size_t(2) << 20) / row_floats));  // 8 MiB bands, as tiles have
    for (uint32_t y = 0; y < out.height; y += band_rows) {
        OutputRows band(y, std::min(out.height, y + band_rows), row_floats);
        std::memcpy(band.floats.get(), rendered.row(y), band.rows() * row_floats * sizeof(float));
        sink(std::move(band));
    }
    if (optimized) *optimized = std::move(mesh);
    return stats;
}

}  // namespace ddt
