#include "simplified_upscale.h"

#include <algorithm>
#include <cmath>

#include "user_error.h"

namespace ddt {

uint32_t simplifiedVertexCount(uint32_t width, uint32_t height, double fraction) {
    return uint32_t(std::max<uint64_t>(4, uint64_t(std::ceil(fraction * double(width) * height))));
}

SimplifiedUpscale upscaleSimplified(Backend& backend, const Image& image, OutputSize out, double fraction, double max_error,
                                    const TileOptions& options, const std::function<void(OutputRows&& rows)>& sink,
                                    const TileStepCallback& on_step) {
    if (options.tile && options.tile < std::max(image.width, image.height))
        throw UserError("simplification needs the image in one piece, and " + std::to_string(image.width) + "×" +
                        std::to_string(image.height) + " is larger than --tile");
    if (std::string problem = untiledMemoryProblem(backend, image.width, image.height, image.channels,
                                                   backend.simplifyMemoryNeeded(image.width, image.height, image.channels));
        !problem.empty())
        throw UserError("simplification needs the image in one piece: " + problem);
    if (image.width > kMaxPositionedSide || image.height > kMaxPositionedSide)
        throw UserError("simplification places vertices on a fixed-point grid for sides up to " +
                        std::to_string(kMaxPositionedSide) + " pixels, and " + std::to_string(image.width) + "×" +
                        std::to_string(image.height) + " is wider or taller");
    SimplifiedUpscale result;
    if (on_step) on_step({0, 1, TilePhase::Optimize});
    backend.prepare(image);
    result.optimize = backend.optimize();
    Mesh mesh = backend.takeMesh();
    result.values = image;
    result.simplify = backend.simplify(mesh, result.values, simplifiedVertexCount(image.width, image.height, fraction),
                                       max_error);
    if (options.mesh) options.mesh->add(mesh, {0, 0, image.width, image.height}, {0, 0, image.width, image.height});

    const MeshRenderer renderer(mesh, result.values);
    if (on_step) on_step({0, 1, TilePhase::Render});
    const size_t row_floats = size_t(out.width) * image.channels;
    const uint32_t band_rows = uint32_t(std::max<size_t>(1, (size_t(2) << 20) / row_floats));  // 8 MiB bands, as tiles have
    for (uint32_t y = 0; y < out.height; y += band_rows) {
        OutputRows band(y, std::min(out.height, y + band_rows), row_floats);
        renderInParallel(renderer, wholeRows(image.width, image.height, out, band.y_begin, band.y_end), image.channels,
                         band.floats.get());
        sink(std::move(band));
    }
    return result;
}

}  // namespace ddt
