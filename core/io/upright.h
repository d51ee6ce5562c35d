// Turning and mirroring decoded samples as an EXIF orientation asks, so that the image is
// upright. Orientation 5 is the mirror across the main diagonal (the transpose), 7 across
// the other one: OpenImageIO 2.4's reorient swaps these two (its issue #4661).
#pragma once

#include <cstddef>
#include <cstdint>

namespace ddt {

// EXIF orientations 5..8 turn the stored image a quarter: the upright size is the stored size swapped.
bool swapsSides(int orientation);

// Rearranges the pixels of `samples` in place (`pixel_bytes` each: channels times the sample
// size) from the stored image, `stored_width`×`stored_height`, to the upright one. Does
// nothing for orientation 1 or any value outside 1..8.
void makeUpright(void* samples, size_t pixel_bytes, uint32_t stored_width, uint32_t stored_height, int orientation);

}  // namespace ddt
