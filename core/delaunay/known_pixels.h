// A mask's known pixels as one byte a pixel (known_samples.h: the crop a tile of them needs).
// The distance grid is the pixels themselves: a known pixel is its cell's sample, at its
// centre, so the spread is 1 (√½ for a place between pixel centres, rounded up).
//
// A sample's id is its pixel's in the frame, y · width + x. The rule holds wherever the
// frame's border is known; where it is not (a border run of unknown pixels makes long, thin
// hull triangles along it), samplesBreaking finds the far pixels a crop needs. There is no
// band along the border (samplesAlongBorder): its pixels would widen the crop of every tile on
// that side to the whole side, a crop of floats (SampleSet::values) a whole frame wide, where
// the check adds only the pixels that the triangles near the tile reach.
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
    // The pixels of `input` in boundsOf(rect, extra), and as ids of that grid the known
    // pixels of `rect` and the pixels `extra` (frame ids outside `rect`).
    SampleSet samplesIn(const PackedImage& input, const PixelRect& rect,
                        const std::vector<uint32_t>& extra = {}) const override;
    // Also finds the corners of the known pixels' convex hull (samplesBreaking).
    void measureHoles() override;

protected:
    Position placeOf(uint32_t id) const override {
        return {int32_t(id % width()) * kPositionOne, int32_t(id / width()) * kPositionOne};
    }
    // The known pixels of the disk and a pixel around it, without `rect`'s.
    void addSamplesNear(long double cx, long double cy, long double radius, const PixelRect& rect,
                        std::vector<uint32_t>& ids) const override;

private:
    // The known pixels of `rect` as ids of the grid `grid` (a rect holding it), ascending.
    std::vector<uint32_t> idsIn(const PixelRect& rect, const PixelRect& grid) const;

    std::vector<uint8_t> known_;
};

}  // namespace ddt
