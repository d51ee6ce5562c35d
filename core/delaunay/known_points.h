// A point file's points (app/delaunay/point_mesh.h's general form: anywhere in the frame, in
// fixed point) kept by block for tiles (known_samples.h: the crop a tile of them needs).
//
// The distance grid's cells are 1, 2, 4 … 32 pixels wide, the smallest whose grid has at most
// kCellsPerPoint cells a point: sparse points in a large frame do not cost a byte a pixel.
// A point lies anywhere in its cell and so does a circle's centre: the spread is a cell's
// diagonal.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "known_samples.h"

namespace ddt {

class KnownPoints final : public KnownSamples {
public:
    // `places`: distinct, inside [0, (width − 1) · kPositionOne] × [0, (height − 1) · kPositionOne];
    // `values`: one pixel each (places.size() × 1).
    KnownPoints(uint32_t width, uint32_t height, const std::vector<Position>& places, const Image& values);

    // Bytes held a point (places, values and the block index) with `channels` channels.
    static uint64_t bytesPerPoint(uint32_t channels);

    std::string problemIn(const PixelRect& rect) const override;
    // The points of `rect` and `extra`, row-major, moved by their bounds' corner, with their
    // values; `input` unused.
    SampleSet samplesIn(const PackedImage& input, const PixelRect& rect,
                        const std::vector<uint32_t>& extra = {}) const override;
    std::vector<uint32_t> samplesAlongBorder(const PixelRect& rect) const override;
    void measureHoles() override;

protected:
    Position placeOf(uint32_t id) const override { return places_[id]; }
    // The points of the blocks the disk meets, `rect`'s among them.
    void addSamplesNear(long double cx, long double cy, long double radius, const PixelRect& rect,
                        std::vector<uint32_t>& ids) const override;

private:
    // Calls visit(i) for each point i (of the block order) inside `rect`.
    template <typename Visit>
    void forEachIn(const PixelRect& rect, Visit visit) const;

    std::vector<Position> places_;      // block by block, row-major blocks; row-major within each
    Image values_;                      // in the same order
    uint32_t block_columns_ = 0;
    std::vector<uint32_t> block_first_;  // each block's first point, and the end
};

}  // namespace ddt
