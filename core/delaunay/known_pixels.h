// A mask's known pixels as one byte a pixel (known_samples.h: the crop a tile of them needs).
// The distance grid is the pixels themselves: a known pixel is its cell's sample, at its
// centre, so the spread is 1 (√½ for a place between pixel centres, rounded up).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "known_samples.h"

namespace ddt {

class KnownPixels final : public KnownSamples {
public:
    KnownPixels() : KnownSamples(0, 0, 1, 1.0f) {}
    // `known`: width × height bytes, row-major, non-zero where the pixel is known.
    KnownPixels(uint32_t width, uint32_t height, std::vector<uint8_t> known);

    bool known(uint32_t x, uint32_t y) const { return known_[size_t(y) * width() + x] != 0; }
    // The known pixels of `rect` as ids of the rect's own grid, (y − y0)·width + (x − x0), ascending.
    std::vector<uint32_t> idsIn(const PixelRect& rect) const;
    std::string problemIn(const PixelRect& rect) const override;
    // The rect's pixels of `input` and its known pixels' ids (`extra` is always empty).
    SampleSet samplesIn(const PackedImage& input, const PixelRect& rect,
                        const std::vector<uint32_t>& extra = {}) const override;
    void measureHoles() override { measureFrom(known_); }

private:
    std::vector<uint8_t> known_;
};

}  // namespace ddt
