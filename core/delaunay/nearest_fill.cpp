#include "nearest_fill.h"

#include <cmath>
#include <cstring>
#include <vector>

#include "parallel.h"

namespace ddt {

namespace {

constexpr uint32_t kFar = UINT32_MAX;  // no covered pixel in the column

// Per column, the row of the nearest covered pixel in that column (kFar if none): a
// downward and an upward sweep.
std::vector<uint32_t> nearestRowInColumns(const float* pixels, uint32_t width, uint32_t height, uint32_t channels) {
    std::vector<uint32_t> nearest(size_t(width) * height, kFar);
    parallelFor(width, 64, [&](size_t begin, size_t end) {
        for (size_t x = begin; x < end; ++x) {
            uint32_t last = kFar;
            for (uint32_t y = 0; y < height; ++y) {
                if (!std::isnan(pixels[(size_t(y) * width + x) * channels])) last = y;
                nearest[size_t(y) * width + x] = last;
            }
            last = kFar;
            for (uint32_t y = height; y-- > 0;) {
                if (!std::isnan(pixels[(size_t(y) * width + x) * channels])) last = y;
                uint32_t& best = nearest[size_t(y) * width + x];
                // On equal distance the upper row (smaller y) stays.
                if (last != kFar && (best == kFar || last - y < y - best)) best = last;
            }
        }
    });
    return nearest;
}

}  // namespace

void fillFromNearest(float* pixels, uint32_t width, uint32_t height, uint32_t channels) {
    const std::vector<uint32_t> column_row = nearestRowInColumns(pixels, width, height, channels);
    // Row by row: the lower envelope of the parabolas f(x) = (x − q)² + dy(q)², one per column
    // q with a covered pixel; the envelope's minimiser at x is the nearest covered pixel.
    // Distances are below 2^32 per axis, squares below 2^64 summed as exact __int128.
    parallelFor(height, 16, [&](size_t begin, size_t end) {
        std::vector<uint32_t> columns(width);   // the envelope's parabolas, by column
        std::vector<uint32_t> source(width);    // per pixel of the row: the column it copies
        for (size_t y = begin; y < end; ++y) {
            const uint32_t* rows = column_row.data() + y * width;
            auto height_at = [&](uint32_t q) {
                const __int128 dy = __int128(rows[q]) - __int128(y);
                return dy * dy;
            };
            // The parabolas at columns p < q cross at s = (f(q) + q² − f(p) − p²) / (2(q − p)),
            // compared as fractions, never divided. q leaves the envelope when r overtakes it
            // no later than q overtakes p: s(q, r) <= s(p, q) (at equality q is never alone lowest).
            auto crossesBefore = [&](uint32_t p, uint32_t q, uint32_t r) {
                const __int128 pq = (height_at(q) + __int128(q) * q - height_at(p) - __int128(p) * p) * (r - q);
                const __int128 qr = (height_at(r) + __int128(r) * r - height_at(q) - __int128(q) * q) * (q - p);
                return qr <= pq;
            };
            size_t count = 0;
            for (uint32_t q = 0; q < width; ++q) {
                if (rows[q] == kFar) continue;
                while (count >= 2 && crossesBefore(columns[count - 2], columns[count - 1], q)) --count;
                columns[count++] = q;
            }
            if (count == 0) continue;
            size_t k = 0;
            for (uint32_t x = 0; x < width; ++x) {
                // Move on while the next parabola is strictly lower at x (ties keep the smaller column).
                while (k + 1 < count) {
                    const uint32_t p = columns[k], q = columns[k + 1];
                    const __int128 dp = __int128(x) - p, dq = __int128(x) - q;
                    if (dq * dq + height_at(q) < dp * dp + height_at(p)) ++k;
                    else break;
                }
                source[x] = columns[k];
            }
            float* row = pixels + y * size_t(width) * channels;
            for (uint32_t x = 0; x < width; ++x) {
                if (!std::isnan(row[size_t(x) * channels])) continue;
                const uint32_t q = source[x];
                const float* from = pixels + (size_t(rows[q]) * width + q) * channels;
                std::memcpy(row + size_t(x) * channels, from, channels * sizeof(float));
            }
        }
    });
}

}  // namespace ddt
