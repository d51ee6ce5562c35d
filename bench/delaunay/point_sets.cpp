#include "point_sets.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "delaunay.h"

namespace bench {

using ddt::Position;

namespace {

// The largest frame: coordinates up to (65536 − 1) · 1024, below the in-circle test's 2^26.
constexpr uint32_t kSide = ddt::kMaxDelaunaySide;
constexpr int32_t kMaxCoordinate = int32_t(kSide - 1) * ddt::kPositionOne;
// The frame's centre, a lattice point.
constexpr int64_t kCentre = kMaxCoordinate / 2;

void sortRowMajorUnique(std::vector<Position>& points) {
    std::sort(points.begin(), points.end(), [](Position p, Position q) { return p.y != q.y ? p.y < q.y : p.x < q.x; });
    points.erase(std::unique(points.begin(), points.end()), points.end());
}

std::vector<Position> uniformPoints(uint64_t n, std::mt19937_64& rng) {
    std::uniform_int_distribution<int32_t> coordinate(0, kMaxCoordinate);
    std::vector<Position> points(n);
    for (Position& p : points) p = {coordinate(rng), coordinate(rng)};
    return points;
}

// Two clusters, half the points each: a wide one (σ = 6 % of the side) and a tight one (2 %),
// so that the density differs by an order of magnitude between and inside them. Draws that
// fall outside the frame are drawn again.
std::vector<Position> gaussianPoints(uint64_t n, std::mt19937_64& rng) {
    struct Cluster {
        double cx, cy, sigma;
    };
    const Cluster clusters[2] = {{0.30, 0.35, 0.06}, {0.65, 0.70, 0.02}};
    std::normal_distribution<double> normal;
    std::vector<Position> points;
    points.reserve(n);
    for (uint64_t i = 0; i < n; ++i) {
        const Cluster& c = clusters[i % 2];
        for (;;) {
            const double x = (c.cx + c.sigma * normal(rng)) * kMaxCoordinate;
            const double y = (c.cy + c.sigma * normal(rng)) * kMaxCoordinate;
            if (x < 0 || y < 0 || x > kMaxCoordinate || y > kMaxCoordinate) continue;
            points.push_back({int32_t(std::lround(x)), int32_t(std::lround(y))});
            break;
        }
    }
    return points;
}

// n points at equal angles on a circle of radius 33 000 000 (about 32 227 pixels), each
// rounded to the nearest lattice point: off the circle by up to 0.71 units, so no 4 are
// exactly cocircular (in general) but every in-circle test of 4 neighbours is nearly 0.
std::vector<Position> roundedCirclePoints(uint64_t n) {
    const double radius = 33'000'000.0;
    std::vector<Position> points(n);
    for (uint64_t i = 0; i < n; ++i) {
        const double angle = 2.0 * std::numbers::pi * double(i) / double(n);
        points[i] = {int32_t(kCentre + std::lround(radius * std::cos(angle))),
                     int32_t(kCentre + std::lround(radius * std::sin(angle)))};
    }
    return points;
}

// Every lattice point (x, y) with x² + y² = r² around the centre: exactly cocircular. The
// count is 4 · Π (2 e + 1) over the primes p ≡ 1 (mod 4) dividing r, p^e exactly, so r is
// the product of the smallest such primes that keeps it below the frame's half side
// (2^25 units): r = 5³ · 13 · 17 · 29 · 37 = 29 641 625 has 4 · 7 · 3⁴ = 2268 points.
std::vector<Position> exactCirclePoints() {
    const int64_t r = 5LL * 5 * 5 * 13 * 17 * 29 * 37;
    std::vector<Position> points;
    for (int64_t x = 0; x <= r; ++x) {
        const int64_t rest = r * r - x * x;
        int64_t y = int64_t(std::sqrt(double(rest)));
        while (y * y > rest) --y;
        while ((y + 1) * (y + 1) <= rest) ++y;
        if (y * y != rest) continue;
        for (int64_t sx : {-1, 1})
            for (int64_t sy : {-1, 1}) points.push_back({int32_t(kCentre + sx * x), int32_t(kCentre + sy * y)});
    }
    return points;  // the axis points came twice; sortRowMajorUnique drops the copies
}

}  // namespace

const char* pointSetName(PointSetKind kind) {
    switch (kind) {
        case PointSetKind::uniform: return "uniform";
        case PointSetKind::gaussian: return "2 Gaussians";
        case PointSetKind::grid: return "grid";
        case PointSetKind::circle: return "circle (rounded)";
        case PointSetKind::exact_circle: return "circle (exact)";
    }
    return "?";
}

PointSet makePointSet(PointSetKind kind, uint64_t n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    PointSet set;
    set.name = pointSetName(kind);
    set.width = set.height = kSide;
    switch (kind) {
        case PointSetKind::uniform:
            set.points = uniformPoints(n, rng);
            set.unique_delaunay = true;
            break;
        case PointSetKind::gaussian:
            set.points = gaussianPoints(n, rng);
            set.unique_delaunay = true;
            break;
        case PointSetKind::grid: {
            const uint32_t k = uint32_t(std::ceil(std::sqrt(double(n))));
            set.width = set.height = k;
            set.points.reserve(uint64_t(k) * k);
            for (uint32_t y = 0; y < k; ++y)
                for (uint32_t x = 0; x < k; ++x)
                    set.points.push_back({int32_t(x) * ddt::kPositionOne, int32_t(y) * ddt::kPositionOne});
            break;
        }
        case PointSetKind::circle: set.points = roundedCirclePoints(n); break;
        case PointSetKind::exact_circle: set.points = exactCirclePoints(); break;
    }
    sortRowMajorUnique(set.points);
    return set;
}

}  // namespace bench
