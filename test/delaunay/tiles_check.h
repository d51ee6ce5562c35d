// The check that the tests of samples in tiles share (test_masked_tiles.cpp,
// test_point_tiles.cpp): tiled outputs against the one-piece output, sample for sample.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backend.h"
#include "delaunay/sampled_upscale.h"
#include "known_samples.h"
#include "output_rows.h"
#include "tiled_upscale.h"
#include "vulkan_backend.h"

namespace ddt::test {

using RowSink = std::function<void(OutputRows&&)>;

// The rows `run` hands its sink, in order, `row_floats` floats each.
inline std::vector<float> collectRows(const std::function<void(const RowSink&)>& run, size_t row_floats) {
    std::vector<float> pixels;
    run([&](OutputRows&& rows) {
        pixels.insert(pixels.end(), rows.floats.get(), rows.floats.get() + rows.rows() * row_floats);
    });
    return pixels;
}

// On the CPU backend and on Vulkan (validation on), at ×1 and ×2: the output of
// `one_piece(backend, out, sink)` against upscaleRows of `input` in tiles of 64 and 128 with
// `overlap`, the tiles' samples from `known()` (measured here). Every sample must be equal.
inline void checkTilesMatchOnePiece(PackedImage input, uint32_t overlap,
                                    const std::function<void(Backend&, OutputSize, const RowSink&)>& one_piece,
                                    const std::function<std::unique_ptr<KnownSamples>()>& known) {
    const Image& header = input.header();
    for (const std::string name : {"cpu", "vulkan"}) {
        std::unique_ptr<Backend> backend;
        if (name == "cpu") {
            backend = makeCpuBackend();
        } else {
            VulkanOptions options;
            options.validation = true;
            backend = std::make_unique<VulkanBackend>(options);
        }
        for (double scale : {1.0, 2.0}) {
            CAPTURE(name, scale);
            const OutputSize out = scaledOutputSize(header.width, header.height, scale);
            const size_t row_floats = size_t(out.width) * header.channels;
            const std::vector<float> untiled =
                collectRows([&](const RowSink& sink) { one_piece(*backend, out, sink); }, row_floats);
            for (uint32_t side : {64u, 128u}) {
                const std::unique_ptr<KnownSamples> samples = known();
                samples->measureHoles();
                TileOptions options;
                options.tile = side;
                options.overlap = overlap;
                options.known = samples.get();
                const std::vector<float> tiled = collectRows(
                    [&](const RowSink& sink) { upscaleRows(*backend, input, out, options, sink); }, row_floats);
                REQUIRE(tiled.size() == untiled.size());
                size_t differing = 0;
                float largest = 0.0f;
                for (size_t i = 0; i < tiled.size(); ++i) {
                    differing += tiled[i] != untiled[i];
                    largest = std::max(largest, std::abs(tiled[i] - untiled[i]));
                }
                CAPTURE(side, differing, largest);
                CHECK(differing == 0);
            }
        }
        auto* vulkan = dynamic_cast<VulkanBackend*>(backend.get());
        if (vulkan) CHECK(vulkan->validationMessages() == 0);
    }
}

}  // namespace ddt::test
