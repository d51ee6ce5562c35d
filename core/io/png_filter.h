// PNG's row filters (the PNG specification, section 9): each byte of a row minus a prediction
// from its left neighbour a (the same byte of the pixel before), the byte above b and the
// byte above-left c, all 0 outside the image. Filtering turns smooth images into runs of
// small numbers, which deflate compresses far better than the samples themselves.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ddt {

// The filter types in the order of their type bytes, and Adaptive: per row, the filter whose
// output has the smallest sum of absolute values (bytes read as signed), libpng's heuristic.
// PieceAdaptive is for PngEncoder: one filter for each piece of rows it deflates, chosen by
// that heuristic summed over some of the piece's rows (png_encoder.cpp).
enum class PngFilter { None, Sub, Up, Average, Paeth, Adaptive, PieceAdaptive };

// Adds to costs[f], for each filter type f (None to Paeth), the heuristic's measure of `row`
// filtered with f: the sum of its bytes' magnitudes read as signed.
void addFilterCosts(const uint8_t* row, const uint8_t* above, size_t size, size_t bpp, uint64_t costs[5]);
// The filter type of the smallest of costs (the first in type order on ties).
PngFilter cheapestFilter(const uint64_t costs[5]);

// Writes `row` (`size` bytes, `bpp` bytes a pixel, 1 to 8) filtered against `above` (zeros
// for the first row) to `out`: the filter type byte, then `size` bytes. `out` must not
// overlap the inputs. Given either adaptive choice, the row is filtered as its own piece.
void filterPngRow(PngFilter filter, const uint8_t* row, const uint8_t* above, size_t size, size_t bpp, uint8_t* out);

}  // namespace ddt
