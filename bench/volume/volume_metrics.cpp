#include "volume_metrics.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "parallel.h"

namespace bench {

namespace {

using Point = std::array<double, 3>;

// A uniform grid of one-unit cells over a point set's bounding box, the points listed per cell
// (counting sort): the nearest point to a query is searched in rings of cells around it.
class PointGrid {
public:
    explicit PointGrid(const std::vector<Point>& points) : points_(points) {
        for (int a = 0; a < 3; ++a) {
            low_[a] = std::numeric_limits<double>::infinity();
            double high = -low_[a];
            for (const Point& p : points) low_[a] = std::min(low_[a], p[a]), high = std::max(high, p[a]);
            cells_[a] = int64_t(std::floor(high - low_[a])) + 1;
        }
        first_.assign(size_t(cells_[0] * cells_[1] * cells_[2]) + 1, 0);
        for (const Point& p : points) ++first_[cellIndex(cellOf(p)) + 1];
        for (size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
        order_.resize(points.size());
        std::vector<uint32_t> next(first_.begin(), first_.end() - 1);
        for (uint32_t i = 0; i < points.size(); ++i) order_[next[cellIndex(cellOf(points[i]))]++] = i;
    }

    double nearestDistance(const Point& q) const {
        // q's cell (possibly outside the grid). Every cell at Chebyshev distance ≥ r + 1 from it
        // lies ≥ r away from q along some axis, so once a point within r is found after ring r,
        // no farther ring can hold a nearer one. Rings below `start` miss the grid altogether.
        std::array<int64_t, 3> c;
        int64_t start = 0;
        for (int a = 0; a < 3; ++a) {
            c[a] = int64_t(std::floor(q[a] - low_[a]));
            start = std::max({start, -c[a], c[a] - (cells_[a] - 1)});
        }
        double best = std::numeric_limits<double>::infinity();
        for (int64_t r = start;; ++r) {
            visitRing(c, r, [&](size_t cell) {
                for (uint32_t k = first_[cell]; k < first_[cell + 1]; ++k) {
                    const Point& p = points_[order_[k]];
                    best = std::min(best, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
                }
            });
            if (best <= double(r)) return best;
        }
    }

private:
    std::array<int64_t, 3> cellOf(const Point& p) const {
        std::array<int64_t, 3> c;
        for (int a = 0; a < 3; ++a) c[a] = std::min(int64_t(std::floor(p[a] - low_[a])), cells_[a] - 1);
        return c;
    }
    size_t cellIndex(const std::array<int64_t, 3>& c) const { return size_t(c[0] + cells_[0] * (c[1] + cells_[1] * c[2])); }

    // Calls visit(cell index) for the grid's cells at Chebyshev distance exactly r from c.
    template <typename Visit>
    void visitRing(const std::array<int64_t, 3>& c, int64_t r, Visit visit) const {
        auto range = [&](int a) {
            return std::pair<int64_t, int64_t>{std::max<int64_t>(c[a] - r, 0), std::min<int64_t>(c[a] + r, cells_[a] - 1)};
        };
        const auto [z0, z1] = range(2);
        const auto [y0, y1] = range(1);
        const auto [x0, x1] = range(0);
        for (int64_t z = z0; z <= z1; ++z)
            for (int64_t y = y0; y <= y1; ++y) {
                if (std::abs(z - c[2]) == r || std::abs(y - c[1]) == r) {  // a face of the ring: the whole row
                    for (int64_t x = x0; x <= x1; ++x) visit(cellIndex({x, y, z}));
                    continue;
                }
                // Inside the ring's faces only its two ends (r > 0 here, so they differ).
                for (const int64_t x : {c[0] - r, c[0] + r})
                    if (x0 <= x && x <= x1) visit(cellIndex({x, y, z}));
            }
    }

    const std::vector<Point>& points_;
    std::array<double, 3> low_;
    std::array<int64_t, 3> cells_;
    std::vector<uint32_t> first_;  // per cell, its first entry in order_; + the end
    std::vector<uint32_t> order_;  // point indices by cell
};

}  // namespace

double dataRange(const ddt::Volume& original) {
    assert(!original.values.empty());
    const auto [low, high] = std::minmax_element(original.values.begin(), original.values.end());
    return double(*high) - double(*low);
}

double volumePsnr(const ddt::Volume& original, const ddt::Volume& result, double range) {
    assert(original.size == result.size && original.values.size() == result.values.size());
    double sum = 0.0;
    for (size_t i = 0; i < original.values.size(); ++i) {
        const double d = double(original.values[i]) - double(result.values[i]);
        sum += d * d;
    }
    const double mse = sum / double(original.values.size());
    return mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(range * range / mse);
}

namespace {

// Volume index p (fractional) into the index frame of `frame_size` voxels over the same box:
// volume voxel i lies at frame index (i + 0.5) · N / n − 0.5 (ddt::inputIndexOf).
Point inFrame(Point p, const std::array<uint32_t, 3>& n, const std::array<uint32_t, 3>& frame_size) {
    for (int a = 0; a < 3; ++a) p[a] = (p[a] + 0.5) * double(frame_size[a]) / double(n[a]) - 0.5;
    return p;
}

// The crossings on the grid's own edges, slice by slice.
void edgeCrossings(const ddt::Volume& volume, double level, uint32_t z, std::vector<Point>& points) {
    const std::array<uint32_t, 3>& n = volume.size;
    for (uint32_t y = 0; y < n[1]; ++y)
        for (uint32_t x = 0; x < n[0]; ++x) {
            const std::array<uint32_t, 3> at = {x, y, z};
            const double here = volume.at(x, y, z);
            for (int a = 0; a < 3; ++a) {
                if (at[a] + 1 >= n[a]) continue;
                std::array<uint32_t, 3> next = at;
                ++next[a];
                const double there = volume.at(next[0], next[1], next[2]);
                if ((here < level) == (there < level)) continue;
                Point p = {double(x), double(y), double(z)};
                p[a] += (level - here) / (there - here);
                points.push_back(p);
            }
        }
}

// The crossings on the edges of a grid `subdivision` times finer, of the trilinear interpolant,
// in the cells (between 8 voxel centres) whose corners lie on both sides of the level; no other
// cell's interpolant (a convex combination of its corners) reaches the level, nor does a face it
// shares. A cell takes the fine edges starting on its low faces, and those on its high faces
// only at the volume's side, so no point comes twice.
void cellCrossings(const ddt::Volume& volume, double level, uint32_t subdivision, uint32_t z, std::vector<Point>& points) {
    const std::array<uint32_t, 3>& n = volume.size;
    const uint32_t s = subdivision, nodes = s + 1;
    std::vector<double> node(size_t(nodes) * nodes * nodes);
    for (uint32_t y = 0; y + 1 < n[1]; ++y)
        for (uint32_t x = 0; x + 1 < n[0]; ++x) {
            double corner[8];
            int below = 0;
            for (int c = 0; c < 8; ++c) {
                corner[c] = volume.at(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1));
                below += corner[c] < level;
            }
            if (below == 0 || below == 8) continue;
            for (uint32_t k = 0; k < nodes; ++k)
                for (uint32_t j = 0; j < nodes; ++j)
                    for (uint32_t i = 0; i < nodes; ++i) {
                        const double u = double(i) / s, v = double(j) / s, w = double(k) / s;
                        double value = 0.0;
                        for (int c = 0; c < 8; ++c)
                            value += corner[c] * (c & 1 ? u : 1 - u) * (c >> 1 & 1 ? v : 1 - v) * (c >> 2 & 1 ? w : 1 - w);
                        node[i + nodes * (j + nodes * k)] = value;
                    }
            const std::array<uint32_t, 3> cell = {x, y, z};
            const std::array<size_t, 3> step = {1, nodes, size_t(nodes) * nodes};
            for (uint32_t k = 0; k < nodes; ++k)
                for (uint32_t j = 0; j < nodes; ++j)
                    for (uint32_t i = 0; i < nodes; ++i) {
                        const std::array<uint32_t, 3> q = {i, j, k};
                        for (int a = 0; a < 3; ++a) {
                            if (q[a] == s) continue;  // no edge beyond the cell
                            bool owned = true;
                            for (int b = 0; b < 3; ++b)
                                if (b != a && q[b] == s) owned &= cell[b] + 2 == n[b];
                            if (!owned) continue;
                            const size_t here_at = i + nodes * (j + size_t(nodes) * k);
                            const double here = node[here_at], there = node[here_at + step[a]];
                            if ((here < level) == (there < level)) continue;
                            Point p;
                            for (int b = 0; b < 3; ++b) p[b] = cell[b] + double(q[b]) / s;
                            p[a] += (level - here) / (there - here) / s;
                            points.push_back(p);
                        }
                    }
        }
}

}  // namespace

std::vector<Point> isosurfacePoints(const ddt::Volume& volume, double level, const std::array<uint32_t, 3>& frame_size,
                                    uint32_t subdivision) {
    assert(subdivision >= 1);
    const uint32_t slices = subdivision == 1 ? volume.size[2] : volume.size[2] - 1;
    // One list per z slice, filled in parallel and joined in order (the same points in the same
    // order for any thread count).
    std::vector<std::vector<Point>> lists(slices);
    ddt::parallelFor(slices, 1, [&](size_t begin, size_t end) {
        for (size_t z = begin; z < end; ++z) {
            if (subdivision == 1)
                edgeCrossings(volume, level, uint32_t(z), lists[z]);
            else
                cellCrossings(volume, level, subdivision, uint32_t(z), lists[z]);
            for (Point& p : lists[z]) p = inFrame(p, volume.size, frame_size);
        }
    });
    std::vector<Point> points;
    for (const auto& list : lists) points.insert(points.end(), list.begin(), list.end());
    return points;
}

double meanNearestDistance(const std::vector<Point>& from, const std::vector<Point>& to) {
    if (from.empty() || to.empty()) return std::numeric_limits<double>::quiet_NaN();
    const PointGrid grid(to);
    std::vector<double> distance(from.size());
    ddt::parallelFor(from.size(), 1024, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) distance[i] = grid.nearestDistance(from[i]);
    });
    double sum = 0.0;  // summed in order: the same for any thread count
    for (double d : distance) sum += d;
    return sum / double(from.size());
}

double isosurfaceDistance(const ddt::Volume& original, const ddt::Volume& result, double level) {
    auto points = [&](const ddt::Volume& volume, uint32_t subdivision) {
        return isosurfacePoints(volume, level, original.size, subdivision);
    };
    const double there = meanNearestDistance(points(original, 1), points(result, kIsosurfaceSubdivision));
    const double back = meanNearestDistance(points(result, 1), points(original, kIsosurfaceSubdivision));
    return 0.5 * (there + back);
}

}  // namespace bench
