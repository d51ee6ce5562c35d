#include "triangulation_table.h"

#include <algorithm>
#include <memory>

#include "cgal_peer.h"
#include "child_run.h"
#include "context.h"
#include "delaunay.h"
#include "delaunay/device_delaunay.h"

namespace bench {

namespace {

std::vector<uint64_t> sortedEdges(const ddt::Mesh& mesh) {
    std::vector<uint64_t> edges;
    edges.reserve(mesh.edgeCount());
    for (const ddt::EdgeVertices& e : mesh.vertices)
        edges.push_back(uint64_t(std::min(e.a, e.b)) << 32 | std::max(e.a, e.b));
    std::sort(edges.begin(), edges.end());
    return edges;
}

// Edges in one sorted set and not the other, both ways.
uint64_t differingEdges(const std::vector<uint64_t>& p, const std::vector<uint64_t>& q) {
    uint64_t common = 0;
    for (size_t i = 0, j = 0; i < p.size() && j < q.size();) {
        if (p[i] == q[j]) ++common, ++i, ++j;
        else if (p[i] < q[j]) ++i;
        else ++j;
    }
    return p.size() + q.size() - 2 * common;
}

}  // namespace

TriangulationRow measureTriangulations(const PointSet& set, uint32_t repeats, uint32_t timeout_s, bool vulkan) {
    TriangulationRow row;
    row.set = set.name;
    row.points = set.points.size();
    const std::string problem = ddt::delaunayInputProblem(set.points);
    if (!problem.empty()) {
        row.ddtup_failure = row.cgal_failure = problem;
        return row;
    }
    const bool want_edges = set.unique_delaunay;
    // The device's result equals the serial one on every set (the same symbolic tie-break).
    const bool want_serial_edges = want_edges || vulkan;

    ChildResult ddtup = runInChild(
        [&](Payload& out) {
            Span span;
            ddt::Mesh mesh;
            for (uint32_t r = 0; r < repeats; ++r) {
                mesh = ddt::Mesh();
                span.begin();
                mesh = ddt::delaunayOfPoints(set.width, set.height, set.points);
                span.end();
            }
            uint64_t triangles = 0;
            ddt::forEachTriangle(mesh, [&](const ddt::Triangle&) { ++triangles; });
            std::string check = ddt::checkDelaunay(mesh);
            // checkMesh's listTriangles reserves 2 (w − 1)(h − 1) triangles, the grid's count:
            // 200 GB for the 65536² frame. With explicit positions and a convex hull nothing
            // else reads the frame, so the check sees the smallest one.
            mesh.width = mesh.height = 2;
            if (check.empty()) check = ddt::checkMesh(mesh, ddt::MeshHull::convex);
            out.put(span.medianCpuSeconds());
            out.put(span.medianWallSeconds());
            out.put(span.peakBytes());
            out.put(triangles);
            out.putString(check);
            out.putArray(want_serial_edges ? sortedEdges(mesh) : std::vector<uint64_t>());
        },
        timeout_s);
    std::vector<uint64_t> ddtup_edges;
    row.ddtup_failure = ddtup.failure;
    if (ddtup.failure.empty()) {
        row.ddtup_s = ddtup.payload.get<double>();
        row.ddtup_wall_s = ddtup.payload.get<double>();
        row.ddtup_bytes = ddtup.payload.get<uint64_t>();
        row.ddtup_triangles = ddtup.payload.get<uint64_t>();
        row.ddtup_check = ddtup.payload.getString();
        ddtup_edges = ddtup.payload.getArray();
    }
    ddtup.payload = Payload();

    ChildResult cgal = runInChild(
        [&](Payload& out) {
            Span span;
            const CgalTriangulation result = cgalDelaunay(set.points, span, repeats, want_edges);
            out.put(span.medianCpuSeconds());
            out.put(span.medianWallSeconds());
            out.put(span.peakBytes());
            out.put(result.triangles);
            out.put(result.valid);
            out.putArray(result.edges);
        },
        timeout_s);
    std::vector<uint64_t> cgal_edges;
    row.cgal_failure = cgal.failure;
    if (cgal.failure.empty()) {
        row.cgal_s = cgal.payload.get<double>();
        row.cgal_wall_s = cgal.payload.get<double>();
        row.cgal_bytes = cgal.payload.get<uint64_t>();
        row.cgal_triangles = cgal.payload.get<uint64_t>();
        row.cgal_valid = cgal.payload.get<bool>();
        cgal_edges = cgal.payload.getArray();
    }

    if (vulkan) {
        row.vulkan_measured = true;
        ChildResult device = runInChild(
            [&](Payload& out) {
                // The device, and a first run that compiles the kernels, outside the timed runs.
                std::unique_ptr<ddt::VulkanContext> context = ddt::createContext({});
                ddt::deviceDelaunayOfPoints(*context, 4, 4, {{0, 0}, {3 * ddt::kPositionOne, 1000}, {2000, 3 * ddt::kPositionOne}});
                Span span;
                ddt::Mesh mesh;
                ddt::DeviceDelaunayStats stats;
                for (uint32_t r = 0; r < repeats; ++r) {
                    mesh = ddt::Mesh();
                    span.begin();
                    mesh = ddt::deviceDelaunayOfPoints(*context, set.width, set.height, set.points, &stats);
                    span.end();
                }
                out.put(span.medianWallSeconds());
                out.put(span.peakBytes());
                out.put(stats.rounds);
                out.put(stats.flips);
                out.put(stats.sweep_seconds);
                out.put(stats.flip_seconds);
                out.put(stats.number_seconds);
                out.putArray(sortedEdges(mesh));
            },
            timeout_s);
        row.vulkan_failure = device.failure;
        if (device.failure.empty()) {
            row.vulkan_wall_s = device.payload.get<double>();
            row.vulkan_bytes = device.payload.get<uint64_t>();
            row.vulkan_rounds = device.payload.get<uint32_t>();
            row.vulkan_flips = device.payload.get<uint64_t>();
            row.vulkan_sweep_s = device.payload.get<double>();
            row.vulkan_device_s = device.payload.get<double>();
            row.vulkan_number_s = device.payload.get<double>();
            const std::vector<uint64_t> device_edges = device.payload.getArray();
            if (!row.ddtup_failure.empty()) {
                row.vulkan_comparison = "n/a";
            } else {
                const uint64_t differ = differingEdges(device_edges, ddtup_edges);
                row.vulkan_comparison = differ == 0 ? "equal" : std::to_string(differ) + " edges differ";
            }
        }
    }

    if (!row.ddtup_failure.empty() || !row.cgal_failure.empty()) {
        row.comparison = "n/a";
    } else if (want_edges) {
        const uint64_t differ = differingEdges(ddtup_edges, cgal_edges);
        row.comparison = differ == 0 ? "equal" : std::to_string(differ) + " edges differ";
    } else if (row.ddtup_check.empty() && row.cgal_valid && row.ddtup_triangles == row.cgal_triangles) {
        row.comparison = "both valid";
    } else {
        row.comparison = "not both valid";
    }
    return row;
}

}  // namespace bench
