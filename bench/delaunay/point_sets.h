// The point sets of the Delaunay table (bench/README.md, ddtup-bench-delaunay): fixed-point
// positions (core/image/mesh.h, 1/1024 pixel) in a frame of at most kMaxDelaunaySide pixels a side,
// distinct and in row-major order (y, then x), as delaunayOfPoints wants them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh.h"

namespace bench {

enum class PointSetKind {
    uniform,       // uniform random in the square frame
    gaussian,      // two Gaussian clusters of different spread (the non-uniform case)
    grid,          // every pixel centre of a k × k grid: every cell's 4 corners cocircular
    circle,        // n points rounded to the fixed-point lattice from a circle: nearly cocircular
    exact_circle,  // every lattice point on one circle: all cocircular, at most a few thousand
};

struct PointSet {
    std::string name;
    uint32_t width = 0, height = 0;  // the frame, in pixels: points lie in [0, (w − 1) · 1024] × …
    std::vector<ddt::Position> points;
    bool unique_delaunay = false;  // true where no 4 points are expected cocircular (random sets)
};

const char* pointSetName(PointSetKind kind);

// About n points of `kind` (exactly n for the random and circle sets before duplicates are
// removed; the grid rounds up to a square, the exact circle ignores n), from `seed`.
PointSet makePointSet(PointSetKind kind, uint64_t n, uint64_t seed);

}  // namespace bench
