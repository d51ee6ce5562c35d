#include "cgal_peer.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/natural_neighbor_coordinates_2.h>

#include <algorithm>
#include <memory>
#include <utility>

namespace bench {

namespace {

// Each vertex carries its input index, to name edges as ddtup does and to find values.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, CGAL::Triangulation_face_base_2<Kernel>>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using Point = Kernel::Point_2;
using Indexed = std::pair<Point, uint32_t>;

std::vector<uint64_t> sortedEdges(const Delaunay& dt) {
    std::vector<uint64_t> edges;
    edges.reserve(dt.number_of_vertices() * 3);
    for (const Delaunay::Edge& e : dt.finite_edges()) {
        const uint32_t p = e.first->vertex(Delaunay::cw(e.second))->info();
        const uint32_t q = e.first->vertex(Delaunay::ccw(e.second))->info();
        edges.push_back(uint64_t(std::min(p, q)) << 32 | std::max(p, q));
    }
    std::sort(edges.begin(), edges.end());
    return edges;
}

}  // namespace

CgalTriangulation cgalDelaunay(const std::vector<ddt::Position>& points, Span& span, uint32_t repeats, bool want_edges) {
    std::vector<Indexed> input;
    input.reserve(points.size());
    for (uint32_t i = 0; i < points.size(); ++i) input.emplace_back(Point(points[i].x, points[i].y), i);
    std::unique_ptr<Delaunay> dt;
    for (uint32_t r = 0; r < repeats; ++r) {
        dt.reset();
        dt = std::make_unique<Delaunay>();
        span.begin();
        // A range of (point, info) pairs: CGAL sorts it along a Hilbert curve, then inserts.
        dt->insert(input.begin(), input.end());
        span.end();
    }
    CgalTriangulation result;
    result.triangles = dt->number_of_faces();
    result.valid = dt->is_valid();
    if (want_edges) result.edges = sortedEdges(*dt);
    return result;
}

ddt::Image cgalNaturalNeighbours(const ddt::Image& image, const std::vector<uint32_t>& known) {
    const uint32_t w = image.width, h = image.height, c = image.channels;
    std::vector<Indexed> input;
    input.reserve(known.size());
    std::vector<bool> is_known(size_t(w) * h, false);
    for (uint32_t v : known) {
        input.emplace_back(Point(v % w, v / w), v);
        is_known[v] = true;
    }
    Delaunay dt;
    dt.insert(input.begin(), input.end());

    ddt::Image result = image;
    using Coordinate = std::pair<Delaunay::Vertex_handle, double>;
    std::vector<Coordinate> coordinates;
    Delaunay::Face_handle hint;  // the last query's neighbourhood: row-major queries walk a step
    for (uint32_t v = 0; v < w * h; ++v) {
        if (is_known[v]) continue;
        const Point p(v % w, v / w);
        coordinates.clear();
        const auto [end, norm, inside] = CGAL::natural_neighbor_coordinates_2(
            dt, p, std::back_inserter(coordinates), [](const Coordinate& pair) { return pair; }, hint);
        (void)end;
        float* pixel = result.pixels.data() + size_t(v) * c;
        if (!inside) {  // outside the known pixels' hull
            const Delaunay::Vertex_handle nearest = dt.nearest_vertex(p, hint);
            std::copy_n(image.pixels.data() + size_t(nearest->info()) * c, c, pixel);
            hint = nearest->face();
            continue;
        }
        for (uint32_t k = 0; k < c; ++k) {
            double sum = 0.0;
            for (const Coordinate& neighbour : coordinates)
                sum += neighbour.second * image.pixels[size_t(neighbour.first->info()) * c + k];
            pixel[k] = float(sum / norm);
        }
        hint = coordinates.front().first->face();
    }
    return result;
}

}  // namespace bench
