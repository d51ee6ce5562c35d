#include "tet_resample.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#include "divide_by.h"
#include "parallel.h"
#include "raster.h"

namespace ddt {

namespace {

using Point = std::array<int64_t, 3>;  // in the exact units (tet_resample.h)

// Where the output samples lie along each axis: per output index its coordinate in the exact
// units (ascending, equal where clamped) and its push σ; per input index x the output indices
// whose samples lie at or after x (from first[x]) and at or before it (up to end[x]). Tables, so
// that a tet's box of samples costs no search.
struct SampleGrid {
    std::array<uint32_t, 3> out{};
    std::array<int64_t, 3> unit{};  // 2m: vertex x lies at unit · x
    std::array<std::vector<int64_t>, 3> coord;
    std::array<std::vector<int8_t>, 3> push;
    std::array<std::vector<uint32_t>, 3> first, end;
};

SampleGrid sampleGridOf(const std::array<uint32_t, 3>& in, const std::array<uint32_t, 3>& out) {
    SampleGrid grid;
    grid.out = out;
    for (int a = 0; a < 3; ++a) {
        grid.unit[a] = vertexCoord(1, out[a]);
        for (uint32_t i = 0; i < out[a]; ++i) {
            const int64_t s = sampleCoord(i, in[a], out[a]);
            grid.coord[a].push_back(s);
            grid.push[a].push_back(int8_t(sampleDirection(s, in[a], out[a])));
        }
        const auto& s = grid.coord[a];
        for (uint32_t x = 0; x < in[a]; ++x) {
            const int64_t at = grid.unit[a] * x;
            grid.first[a].push_back(uint32_t(std::lower_bound(s.begin(), s.end(), at) - s.begin()));
            grid.end[a].push_back(uint32_t(std::upper_bound(s.begin(), s.end(), at) - s.begin()));
        }
    }
    return grid;
}

template <typename Wide>
Wide crossComponent(int64_t u1, int64_t u2, int64_t w1, int64_t w2) {
    return Wide(u1) * w2 - Wide(u2) * w1;
}

// The four face functions of a positive tet, f_i(p) = g_i · (p − anchor_i), in integers of
// type Wide (tet_resample.h's bound says which suffices).
template <typename Wide>
struct FaceFunctions {
    std::array<std::array<Wide, 3>, 4> gradient;
    std::array<Point, 4> anchor;
    // Per face the axis a of g's first nonzero component and whether that component is
    // positive: a sample on the face's plane pushed by σ counts as inside when σ_a · g_a > 0.
    std::array<uint8_t, 4> tie_axis;
    std::array<bool, 4> tie_positive;
    Wide total;  // orient(tet) = Σ f_i(p)

    // `pushed_back`: bit a set where σ_a = −1.
    bool tieInside(int i, unsigned pushed_back) const { return tie_positive[i] != bool(pushed_back >> tie_axis[i] & 1); }
};

template <typename Wide>
FaceFunctions<Wide> faceFunctionsOf(const std::array<Point, 4>& v) {
    auto difference = [&](int to, int from) {
        return Point{v[to][0] - v[from][0], v[to][1] - v[from][1], v[to][2] - v[from][2]};
    };
    auto cross = [](const Point& u, const Point& w) {
        return std::array<Wide, 3>{crossComponent<Wide>(u[1], u[2], w[1], w[2]),
                                   crossComponent<Wide>(u[2], u[0], w[2], w[0]),
                                   crossComponent<Wide>(u[0], u[1], w[0], w[1])};
    };
    // orient(a, b, c, d) = (b − a) · ((c − a) × (d − a)), and by the triple product's cyclic
    // symmetry f_1 = (p − v0) · (v2 − v0) × (v3 − v0), f_2 = (p − v0) · (v3 − v0) × (v1 − v0),
    // f_3 = (p − v0) · (v1 − v0) × (v2 − v0); f_0 = orient(p, v1, v2, v3) = −orient(v1, p, v2, v3)
    // = (p − v1) · (v3 − v1) × (v2 − v1).
    FaceFunctions<Wide> faces;
    const Point d1 = difference(1, 0), d2 = difference(2, 0), d3 = difference(3, 0);
    faces.gradient[0] = cross(difference(3, 1), difference(2, 1));
    faces.gradient[1] = cross(d2, d3);
    faces.gradient[2] = cross(d3, d1);
    faces.gradient[3] = cross(d1, d2);
    faces.anchor = {v[1], v[0], v[0], v[0]};
    const auto& g1 = faces.gradient[1];
    faces.total = g1[0] * d1[0] + g1[1] * d1[1] + g1[2] * d1[2];
    for (int i = 0; i < 4; ++i) {
        const auto& g = faces.gradient[i];
        const int a = g[0] != 0 ? 0 : g[1] != 0 ? 1 : 2;
        assert(g[a] != 0);
        faces.tie_axis[i] = uint8_t(a);
        faces.tie_positive[i] = g[a] > 0;
    }
    return faces;
}

// Calls sample(index, f, total) for each output sample of [first, end) per axis that the tet
// with vertices v owns, f its four face functions there.
template <typename Wide, typename Sample>
void scanTet(const SampleGrid& grid, const std::array<Point, 4>& v, const std::array<uint32_t, 3>& first,
             const std::array<uint32_t, 3>& end, Sample sample) {
    const FaceFunctions<Wide> faces = faceFunctionsOf<Wide>(v);
    const auto &gx = grid.coord[0], &gy = grid.coord[1], &gz = grid.coord[2];
    for (uint32_t z = first[2]; z < end[2]; ++z) {
        for (uint32_t y = first[1]; y < end[1]; ++y) {
            // Along a row each f_i is base_i + g_i.x · (X − anchor_i.x).
            std::array<Wide, 4> base;
            for (int i = 0; i < 4; ++i)
                base[i] = faces.gradient[i][1] * (gy[y] - faces.anchor[i][1]) +
                          faces.gradient[i][2] * (gz[z] - faces.anchor[i][2]);
            const unsigned back_yz = unsigned(grid.push[1][y] < 0) << 1 | unsigned(grid.push[2][z] < 0) << 2;
            const size_t row = grid.out[0] * (y + size_t(grid.out[1]) * z);
            // The samples a convex tet owns along a row are consecutive (the pushed points lie on
            // one line, the last one pushed backwards being also the last), so stop on leaving.
            bool entered = false;
            for (uint32_t x = first[0]; x < end[0]; ++x) {
                std::array<Wide, 4> f;
                bool inside = true;
                for (int i = 0; i < 4 && inside; ++i) {
                    f[i] = base[i] + faces.gradient[i][0] * (gx[x] - faces.anchor[i][0]);
                    inside = f[i] > 0 || (f[i] == 0 && faces.tieInside(i, back_yz | unsigned(grid.push[0][x] < 0)));
                }
                if (!inside) {
                    if (entered) break;
                    continue;
                }
                entered = true;
                sample(row + x, f, faces.total);
            }
        }
    }
}

// Tets per parallelFor chunk: a Kuhn tet magnified ×2 tests about 8 samples.
constexpr size_t kTetsPerChunk = 2048;

TetResampleWindow wholeWindow(const TetMesh& mesh, const std::array<uint32_t, 3>& new_size) {
    return {mesh.size, new_size, {0, 0, 0}, {0, 0, 0}, new_size};
}

// Calls sample(t, index, f, total) (f: std::array<Wide, 4>, int64_t or __int128) for every
// output sample of the window and the tet t that owns it, on the threads of core/parallel.h;
// over every slot, or only over `slots` when given.
template <typename Sample>
void visitOwners(const TetMesh& mesh, const TetResampleWindow& window, TetArithmetic arithmetic,
                 const std::vector<uint32_t>* slots, Sample sample) {
    assert(checkTetResampleSize(window.size, window.new_size).empty());
    const SampleGrid grid = sampleGridOf(window.size, window.new_size);
    const uint32_t slice = mesh.size[0] * mesh.size[1];
    const DivideBy by_x(mesh.size[0]), by_xy(slice);
    parallelFor(slots ? slots->size() : mesh.slotCount(), kTetsPerChunk, [&](size_t begin, size_t end) {
        for (size_t item = begin; item < end; ++item) {
            const size_t t = slots ? (*slots)[item] : item;
            if (!mesh.inUse(uint32_t(t))) continue;
            // The vertices' index coordinates, their box, and the samples' box within it.
            std::array<std::array<uint32_t, 3>, 4> index;
            std::array<uint32_t, 3> lo, hi, first, last;
            for (int k = 0; k < 4; ++k) {
                const uint32_t id = mesh.vertices[t][k], z = by_xy.quotient(id), rest = id - z * slice;
                const uint32_t y = by_x.quotient(rest);
                index[k] = {rest - y * mesh.size[0] + window.vertex_offset[0], y + window.vertex_offset[1],
                            z + window.vertex_offset[2]};
                for (int a = 0; a < 3; ++a) {
                    lo[a] = k ? std::min(lo[a], index[k][a]) : index[k][a];
                    hi[a] = k ? std::max(hi[a], index[k][a]) : index[k][a];
                }
            }
            bool empty = false;
            for (int a = 0; a < 3; ++a) {
                first[a] = std::max(grid.first[a][lo[a]], window.out_begin[a]);
                last[a] = std::min(grid.end[a][hi[a]], window.out_end[a]);
                empty |= first[a] >= last[a];
            }
            if (empty) continue;
            std::array<Point, 4> v;
            for (int k = 0; k < 4; ++k)
                for (int a = 0; a < 3; ++a) v[k][a] = grid.unit[a] * index[k][a];
            auto owned = [&](size_t index, const auto& f, const auto& total) { sample(uint32_t(t), index, f, total); };
            // The bound of tet_resample.h: |f_i| ≤ 6 · Ex · Ey · Ez; double's rounding is far
            // inside the margin of 2 below 2^63.
            double bound = 6.0;
            for (int a = 0; a < 3; ++a) bound *= double(grid.unit[a]) * double(hi[a] - lo[a]);
            if (bound < std::ldexp(1.0, 62) && arithmetic == TetArithmetic::narrowest)
                scanTet<int64_t>(grid, v, first, last, owned);
            else
                scanTet<__int128>(grid, v, first, last, owned);
        }
    });
}

}  // namespace

std::string checkTetResampleSize(const std::array<uint32_t, 3>& size, const std::array<uint32_t, 3>& new_size) {
    double bound = 6.0;
    for (int a = 0; a < 3; ++a) {
        if (size[a] < 2 || size[a] > kMaxTetMeshSide) return "a tetrahedral mesh needs 2 to 2^16 voxels per axis";
        if (new_size[a] < 1) return "the output needs at least 1 voxel per axis";
        bound *= 2.0 * new_size[a] * double(size[a] - 1);
    }
    if (bound >= std::ldexp(1.0, 126))
        return "output too large for exact resampling (6 · Π 2 · output · (input − 1) voxels ≥ 2^126)";
    return "";
}

std::vector<float> resampleTets(const TetMesh& mesh, const std::vector<float>& values,
                                const std::array<uint32_t, 3>& new_size, TetArithmetic arithmetic) {
    assert(values.size() == mesh.vertexCount());
    // NaN marks a voxel no tet owned; there is none in a valid mesh.
    std::vector<float> out(size_t(new_size[0]) * new_size[1] * new_size[2], std::numeric_limits<float>::quiet_NaN());
    resampleTetsInto(mesh, values, wholeWindow(mesh, new_size), out.data(), arithmetic);
    return out;
}

void resampleTetsInto(const TetMesh& mesh, const std::vector<float>& values, const TetResampleWindow& window,
                      float* out, TetArithmetic arithmetic) {
    resampleTetSlotsInto(mesh, values, window, nullptr, out, arithmetic);
}

void resampleTetSlotsInto(const TetMesh& mesh, const std::vector<float>& values, const TetResampleWindow& window,
                          const std::vector<uint32_t>* slots, float* out, TetArithmetic arithmetic) {
    assert(values.size() == mesh.vertexCount());
    visitOwners(mesh, window, arithmetic, slots, [&](uint32_t t, size_t index, const auto& f, const auto& total) {
        const TetVertices& ids = mesh.vertices[t];
        // Divided, not multiplied by 1 / total: a weight f_i = total is then exactly 1.
        double sum = 0.0;
        for (int i = 0; i < 4; ++i) sum += double(f[i]) / double(total) * double(values[ids[i]]);
        out[index] = float(sum);
    });
}

std::vector<uint32_t> tetSampleOwners(const TetMesh& mesh, const std::array<uint32_t, 3>& new_size,
                                      TetArithmetic arithmetic) {
    std::vector<uint32_t> owners(size_t(new_size[0]) * new_size[1] * new_size[2], kNoTet);
    visitOwners(mesh, wholeWindow(mesh, new_size), arithmetic, nullptr, [&](uint32_t t, size_t index, const auto&, const auto&) {
        std::atomic_ref<uint32_t> owner(owners[index]);
        uint32_t expected = kNoTet;
        if (!owner.compare_exchange_strong(expected, t)) owner.store(kManyTets);
    });
    return owners;
}

}  // namespace ddt
