// Known samples in a frame, and the crop a tile of them needs so that its Delaunay
// triangulation equals the whole frame's where the tile renders: the part a mask's known
// pixels (known_pixels.h) and a point file's points (known_points.h) share.
//
// Why a crop can be exact. A triangle of the whole triangulation has an empty circumcircle:
// no sample inside. It stays empty among fewer samples, so every whole-frame triangle with its
// three vertices in a crop is also a triangle of the crop's triangulation; if such triangles
// cover a region, the crop's triangulation there is the whole one. An empty circle of radius r
// centred at c has no sample nearer to c than r: r <= d(c), the distance from c to the nearest
// sample. So a triangle meeting a region R lies within r of its centre and its centre within r
// of R: inside R grown by 2r. The distances are measured on a grid of cells (a pixel each for a
// mask), each marked where a sample lies in it; with m the largest cell distance over R grown
// by g, in pixels, d(c) <= m + s, where s (the spread) covers c lying anywhere in its cell and
// the sample anywhere in its own. If g >= 2·(m + s) + 1 (+1 spare), every triangle meeting R
// lies in the crop; a centre beyond R + g would need a place on its way in with d >= g − 1 > m + s.
// A long thin gap asks for little (m is half its width), a wide one for its width.
//
// Not covered: a circle centred outside the frame, whose centre the argument cannot follow in.
// Along the frame's border long thin triangles (the hull's, with few points near the border)
// have circles mostly outside the frame while the distances inside stay small, and the rule's
// crop may cut them (a point file's sparse hull; a mask's border mostly unknown). A crop's
// triangulation is therefore checked near its tile (samplesBreaking): any sample found
// missing joins, and the crop is triangulated again. A point file's crop on the border first
// takes the samples of a band along the frame's sides it touches (samplesAlongBorder), as
// deep as the rule asks there; a mask's does not (known_pixels.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"
#include "mesh.h"
#include "packed_image.h"
#include "tiling.h"

namespace ddt {

// Samples ready to triangulate, in one of two forms: pixel_ids of a width × height grid
// (positions implicit, `values` the grid's pixels), or `places` in row-major order, fixed
// point (glsl/fixed_position.h), `values` one pixel a place (places.size() × 1).
struct SampleSet {
    Image values;
    std::vector<uint32_t> pixel_ids;
    std::vector<Position> places;
};

class KnownSamples {
public:
    virtual ~KnownSamples() = default;

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    // Why the samples of `rect` have no triangulation ("fewer than 3 points", "all points are
    // collinear", as delaunayInputProblem says), "" if they have one.
    virtual std::string problemIn(const PixelRect& rect) const = 0;
    // The samples of `rect` (pixel centres x0 … x1 − 1, y0 … y1 − 1) and the samples `extra`
    // (ids from samplesBreaking, ascending), in the coordinates of boundsOf(rect, extra);
    // `input` holds a mask's pixel values (a point file's are its own).
    virtual SampleSet samplesIn(const PackedImage& input, const PixelRect& rect,
                                const std::vector<uint32_t>& extra = {}) const = 0;
    // The samples (ids, ascending) in a band along each side of the frame that `rect` touches,
    // outside `rect`: the band is as deep as the rule asks for the blocks along that side.
    // None by default (a mask's pixels: known_pixels.h says why).
    virtual std::vector<uint32_t> samplesAlongBorder(const PixelRect& rect) const;
    // The pixels whose centres' rectangle holds those samples: `rect` grown to hold `extra`.
    PixelRect boundsOf(const PixelRect& rect, const std::vector<uint32_t>& extra) const;
    // The samples (ids, ascending) other than those of `rect` and `extra` that make `mesh`,
    // those samples' Delaunay triangulation (in boundsOf's coordinates), differ from the whole
    // frame's near `near`: inside the circle of a triangle near it, or beyond a hull edge near
    // it. None: the triangulations agree near `near`. Each triangle near `near` is checked
    // against the other samples in its circle (addSamplesNear, then the exact in-circle test
    // with its tie-break; none if the circle lies inside `rect`), each hull edge near it
    // against the whole hull's corners.
    std::vector<uint32_t> samplesBreaking(const Mesh& mesh, const PixelRect& rect, const std::vector<uint32_t>& extra,
                                          const PixelRect& near) const;
    // Finds each block's largest distance to a sample (exact Euclidean distance transform of
    // the cells); holds 5 bytes a cell while it runs.
    virtual void measureHoles() = 0;

    // `rect` grown, within the frame, until the rule above holds for it (or by at most
    // `max_growth` pixels a side: wider gaps may then triangulate differently near the crop's
    // border); the whole frame where that crop's samples have no triangulation (problemIn).
    // Needs measureHoles() first.
    PixelRect cropFor(const PixelRect& rect, uint32_t max_growth) const;

protected:
    // `cell`: the side of the distance grid's cells in pixels, a power of two up to 32;
    // `spread`: s of the rule above.
    KnownSamples(uint32_t width, uint32_t height, uint32_t cell, float spread)
        : width_(width), height_(height), cell_(cell), spread_(spread) {}
    KnownSamples(const KnownSamples&) = default;
    KnownSamples(KnownSamples&&) = default;
    KnownSamples& operator=(const KnownSamples&) = default;
    KnownSamples& operator=(KnownSamples&&) = default;

    uint32_t cell() const { return cell_; }
    // Sample `id`'s place in the frame, fixed point (glsl/fixed_position.h).
    virtual Position placeOf(uint32_t id) const = 0;
    // Appends to `ids` every sample that may lie in the disk of `radius` around (cx, cy), fixed
    // point (a superset), except perhaps those of `rect`.
    virtual void addSamplesNear(long double cx, long double cy, long double radius, const PixelRect& rect,
                                std::vector<uint32_t>& ids) const = 0;
    // The corners of `places`' convex hull (row-major, distinct), by index: Andrew's monotone
    // chain, along y here, without the places on its sides.
    static std::vector<uint32_t> convexHullOf(const std::vector<Position>& places);
    // The ids of the corners of all the samples' convex hull, for samplesBreaking.
    void keepHullCorners(std::vector<uint32_t> ids) { hull_ = std::move(ids); }
    // The distance transform of `marked`: ceil(width / cell) × ceil(height / cell) bytes,
    // row-major, non-zero where a sample lies in the cell.
    void measureFrom(const std::vector<uint8_t>& marked);

    // The largest distance to a sample over the blocks `rect` touches (an upper bound), in pixels.
    float largestDistanceIn(const PixelRect& rect) const;
    // 2·(m + s) + 1 for the m of `rect`, rounded up: the growth the rule asks for it.
    uint32_t growthFor(const PixelRect& rect) const;

private:

    uint32_t width_ = 0, height_ = 0;
    uint32_t cell_ = 1;
    float spread_ = 1.0f;
    uint32_t block_columns_ = 0;
    std::vector<float> block_distance_;  // per kBlock × kBlock pixels, row-major
    std::vector<uint32_t> hull_;         // the corners of all the samples' convex hull, by id
};

}  // namespace ddt
