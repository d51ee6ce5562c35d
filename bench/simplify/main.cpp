// ddtup-bench-simplify: how much of the picture a simplified mesh keeps (issue: the mesh as a
// product). For each photograph, the optimised mesh of the original is simplified to a share
// of its vertices by ddtup's serial greedy simplifier (core/simplify/) and, as the anchor, by
// meshoptimizer's meshopt_simplify on the same mesh taken as a height field (x, y, k·luma);
// each result is rendered at the original's size by ddtup's renderer and compared with the
// original (PSNR over RGB, 8 bits). Also: the time each takes, and the file sizes of the
// simplified mesh (PLY, SVG, SVG gzipped) beside the PNG of the same picture.
//
// meshoptimizer's side: its simplifier only removes vertices (each kept vertex keeps its
// pixel's colour), its error is geometric, so k sets how much luma counts against position:
// each image and share gets the k of {1, 4, 16, 64, 256} that renders best. Borders are locked
// (meshopt_SimplifyLockBorder), which keeps the picture's rectangle but every border vertex:
// its counts are compared at the vertices it actually kept. Its triangles of no area in the
// picture (three border vertices in a row, not in a line in 3-D) are dropped. Its error is
// 3-D, so nothing stops a triangle turning over in x, y: a result that is not a valid
// triangulation of the picture is rendered as a triangle soup (renderTriangleSoup) and
// counted as folded.
//
//   ddtup-bench-simplify [--data DIR] [--out DIR] [--images A,B,…] [--quick] [--parallel] [--vulkan]
//   ddtup-bench-simplify --from-csv FILE [--out DIR]   the table and plot again from a run's CSV
// --parallel adds the parallel rule (core/simplify/parallel_simplify.h) on the CPU, to compare
// with the serial reference; --vulkan adds the same rule on the first Vulkan device
// (compute/simplify/), whose mesh must equal the CPU rule's (checked with --parallel).
#include <meshoptimizer.h>
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cost.h"
#include "greedy_simplify.h"
#include "image_file.h"
#include "indexed_mesh.h"
#include "lawson.h"
#include "memory_png.h"
#include "mesh_file.h"
#include "metrics.h"
#include "parallel_simplify.h"
#include "simplify/device_simplify.h"
#include "render.h"
#include "svg_plot.h"

namespace fs = std::filesystem;
using namespace ddt;

namespace {

const std::string kParallelRule = "ddtup parallel rule";
const std::string kVulkanRule = "ddtup parallel rule, Vulkan";

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<uint32_t> triangleIds(const Mesh& mesh) {
    std::vector<uint32_t> ids;
    forEachTriangle(mesh, [&](const Triangle& t) { ids.insert(ids.end(), {t.v0, t.v1, t.v2}); });
    return ids;
}

double psnrOf(const Mesh& mesh, const Image& values, const Image& original) {
    return peakSignalToNoiseRatio(toBytes(original),
                                  toBytes(renderImage(mesh, values, {original.width, original.height})));
}

size_t fileSize(MeshFormat format, const IndexedMesh& mesh) {
    size_t size = 0;
    writeMesh(format, mesh, "bench", [&](const char*, size_t n) { size += n; });
    return size;
}

size_t gzippedSize(MeshFormat format, const IndexedMesh& mesh) {
    std::string bytes;
    writeMesh(format, mesh, "bench", [&](const char* data, size_t n) { bytes.append(data, n); });
    uLongf size = compressBound(uLong(bytes.size()));
    std::vector<Bytef> out(size);
    compress2(out.data(), &size, reinterpret_cast<const Bytef*>(bytes.data()), uLong(bytes.size()), 9);
    return size;
}

struct Row {
    std::string image;
    double share = 0.0;  // asked for
    std::string method;  // "ddtup" or "meshopt k=K"
    uint32_t vertices = 0;
    double psnr = 0.0;
    bool folded = false;  // not a valid triangulation of the picture (rendered as a triangle soup)
    double seconds = 0.0;
    size_t ply = 0, svg = 0, svg_gz = 0, png = 0;  // bytes; svg 0 beyond the SVG limit
};

// A triangle list that need not be a valid triangulation (a peer's), rendered at the picture's
// own size by barycentric interpolation of the vertices' pixels: each pixel centre takes the
// last triangle that holds it, whatever its orientation; one that none holds stays black.
Image renderTriangleSoup(const std::vector<uint32_t>& triangles, const Image& picture) {
    Image out = picture;
    std::fill(out.pixels.begin(), out.pixels.end(), 0.0f);
    const uint32_t w = picture.width, c = picture.channels;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        double x[3], y[3];
        for (int k = 0; k < 3; ++k) {
            x[k] = triangles[t + k] % w;
            y[k] = triangles[t + k] / w;
        }
        const double area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        if (area == 0.0) continue;
        const int x0 = int(std::min({x[0], x[1], x[2]})), x1 = int(std::max({x[0], x[1], x[2]}));
        const int y0 = int(std::min({y[0], y[1], y[2]})), y1 = int(std::max({y[0], y[1], y[2]}));
        for (int py = y0; py <= y1; ++py)
            for (int px = x0; px <= x1; ++px) {
                const double l0 = ((x[1] - px) * (y[2] - py) - (y[1] - py) * (x[2] - px)) / area;
                const double l1 = ((x[2] - px) * (y[0] - py) - (y[2] - py) * (x[0] - px)) / area;
                const double l2 = 1.0 - l0 - l1;
                if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
                float* pixel = &out.pixels[(size_t(py) * w + px) * c];
                for (uint32_t k = 0; k < c; ++k)
                    pixel[k] = float(l0 * picture.pixels[size_t(triangles[t]) * c + k] +
                                     l1 * picture.pixels[size_t(triangles[t + 1]) * c + k] +
                                     l2 * picture.pixels[size_t(triangles[t + 2]) * c + k]);
            }
    }
    return out;
}

// meshopt_simplify on (x, y, k·luma) with the border locked; the best k by rendered PSNR.
Row meshoptimizerRow(const Mesh& optimised, const Image& original, double share) {
    const CostField field = costFieldOf(original);
    const std::vector<uint32_t> indices = triangleIds(optimised);
    const size_t vertex_count = size_t(original.width) * original.height;
    Row best;
    best.method = "meshopt";
    best.psnr = -1.0;
    for (double k : {1.0, 4.0, 16.0, 64.0, 256.0}) {
        std::vector<float> positions(3 * vertex_count);
        for (size_t v = 0; v < vertex_count; ++v) {
            positions[3 * v] = float(v % original.width);
            positions[3 * v + 1] = float(v / original.width);
            positions[3 * v + 2] = float(k * field.luma[v]);
        }
        std::vector<uint32_t> result(indices.size());
        const size_t target_triangles = size_t(2.0 * share * double(vertex_count));
        const auto start = std::chrono::steady_clock::now();
        const size_t count = meshopt_simplify(result.data(), indices.data(), indices.size(), positions.data(), vertex_count,
                                              3 * sizeof(float), std::min(indices.size(), 3 * target_triangles), 1e9f,
                                              meshopt_SimplifyLockBorder, nullptr);
        const double seconds = secondsSince(start);
        result.resize(count);
        // Three border vertices in a row make a triangle of no area in the picture (they are
        // not in a line in 3-D); it covers nothing and is dropped.
        std::vector<uint32_t> kept;
        for (size_t t = 0; t < result.size(); t += 3) {
            const int64_t w = original.width;
            const int64_t px = result[t] % w, py = result[t] / w, qx = result[t + 1] % w, qy = result[t + 1] / w;
            const int64_t rx = result[t + 2] % w, ry = result[t + 2] / w;
            if ((qx - px) * (ry - py) - (qy - py) * (rx - px) != 0) kept.insert(kept.end(), &result[t], &result[t] + 3);
        }
        result = std::move(kept);
        std::vector<bool> used(vertex_count, false);
        for (uint32_t v : result) used[v] = true;
        Row row;
        row.method = "meshopt";
        row.vertices = uint32_t(std::count(used.begin(), used.end(), true));
        row.seconds = seconds;
        const Mesh mesh = meshFromTriangles(original.width, original.height, result);
        row.folded = !checkMesh(mesh).empty();
        row.psnr = row.folded ? peakSignalToNoiseRatio(toBytes(original), toBytes(renderTriangleSoup(result, original)))
                              : psnrOf(mesh, original, original);
        char label[32];
        std::snprintf(label, sizeof(label), "meshopt k=%g", k);
        row.method = label;
        if (row.psnr > best.psnr) best = row;
    }
    return best;
}

// The rows of a CSV that a run wrote.
std::vector<Row> readRows(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);  // the header
    std::vector<Row> rows;
    while (std::getline(in, line)) {
        std::vector<std::string> fields;
        size_t start = 0;
        for (size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
            fields.push_back(line.substr(start, comma - start));
        fields.push_back(line.substr(start));
        if (fields.size() != 11) continue;
        Row r;
        r.image = fields[0];
        r.share = std::stod(fields[1]);
        r.method = fields[2];
        r.vertices = uint32_t(std::stoul(fields[3]));
        r.psnr = std::stod(fields[4]);
        r.folded = fields[5] == "1";
        r.seconds = std::stod(fields[6]);
        r.ply = std::stoull(fields[7]);
        r.svg = std::stoull(fields[8]);
        r.svg_gz = std::stoull(fields[9]);
        r.png = std::stoull(fields[10]);
        rows.push_back(r);
    }
    return rows;
}

}  // namespace

namespace {

// simplify.md and simplify.svg from the rows: means over the images per share.
void writeSummary(const std::vector<Row>& rows, const std::vector<double>& shares, size_t images, const std::string& data,
                  const std::string& out, const std::string& vulkan_device) {
    std::ofstream md(out + "/simplify.md");
    md << "| vertices asked | ddtup kept | ddtup PSNR dB | ddtup s | parallel rule PSNR dB | parallel rule s | Vulkan s | "
          "meshopt kept | meshopt PSNR dB | meshopt s | PLY MB | SVG MB | SVG.gz MB | PNG MB |\n"
          "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    bench::PlotSeries ours_series{"ddtup (greedy QEM, colour)", "#1f77b4", "", true, false, {}};
    bench::PlotSeries peer_series{"meshoptimizer (height field, best k)", "#d62728", "6 3", true, true, {}};
    for (double share : shares) {
        double sums[4][3] = {};  // per method (ddtup, meshopt, the parallel rule, on Vulkan): kept, PSNR, seconds
        int counts[4] = {}, unrenderable = 0;
        double ply = 0, svg = 0, svg_gz = 0, png = 0;
        bool all_svg = true;
        for (const Row& r : rows) {
            if (r.share != share) continue;
            const int m = r.method == "ddtup" ? 0 : r.method == kParallelRule ? 2 : r.method == kVulkanRule ? 3 : 1;
            if (r.folded) ++unrenderable;
            sums[m][0] += r.vertices;
            sums[m][1] += r.psnr;
            sums[m][2] += r.seconds;
            ++counts[m];
            if (m == 0) {
                ply += r.ply;
                svg += r.svg;
                svg_gz += r.svg_gz;
                png += r.png;
                all_svg = all_svg && r.svg > 0;
            }
        }
        char line[512], parallel[64] = "— | —", vulkan[32] = "—";
        const double n0 = std::max(1, counts[0]), n1 = std::max(1, counts[1]);
        if (counts[2]) std::snprintf(parallel, sizeof(parallel), "%.2f | %.2f", sums[2][1] / counts[2], sums[2][2] / counts[2]);
        if (counts[3]) std::snprintf(vulkan, sizeof(vulkan), "%.2f", sums[3][2] / counts[3]);
        std::snprintf(line, sizeof(line), "| %g %% | %.0f | %.2f | %.2f | %s | %s | %.0f | %.2f%s | %.3f | %.2f | %s | %s | %.2f |\n",
                      100 * share, sums[0][0] / n0, sums[0][1] / n0, sums[0][2] / n0, parallel, vulkan, sums[1][0] / n1, sums[1][1] / n1,
                      unrenderable ? (" (" + std::to_string(unrenderable) + " folded)").c_str() : "", sums[1][2] / n1,
                      ply / n0 / 1e6, all_svg ? std::to_string(svg / n0 / 1e6).substr(0, 5).c_str() : "over limit",
                      all_svg ? std::to_string(svg_gz / n0 / 1e6).substr(0, 5).c_str() : "over limit", png / n0 / 1e6);
        md << line;
        // All the vertices give the picture itself: an infinite PSNR, off the plot.
        if (std::isfinite(sums[0][1])) ours_series.points.push_back({100 * share, sums[0][1] / n0});
        if (counts[1] && std::isfinite(sums[1][1])) peer_series.points.push_back({100 * share, sums[1][1] / n1});
    }
    md << "\nMeans over " << images << " images of " << data << "; PSNR of the mesh rendered at the original's size "
       << "against the original (8-bit RGB; inf: the mesh is the picture). Parallel rule (with --parallel): "
          "core/simplify/parallel_simplify.h on the CPU"
       << (vulkan_device.empty() ? "" : "; Vulkan (with --vulkan): the same rule, the same meshes, on " + vulkan_device)
       << ". meshopt: k of {1, 4, 16, 64, 256} best per image and share; "
          "border locked; folded: not a valid triangulation of the picture, rendered as a triangle soup.\n";
    bench::Plot plot;
    plot.title = "Simplified meshes: picture kept against vertices kept";
    plot.x_label = "vertices kept (%)";
    plot.y_label = "PSNR against the original (dB)";
    for (double share : shares) plot.x_ticks.push_back({100 * share, std::to_string(100 * share).substr(0, 4)});
    plot.series = {ours_series, peer_series};
    plot.notes = {"means over the bench's photographs; rendered at the original's size"};
    std::ofstream(out + "/simplify.svg") << bench::renderLogLogSvg(plot);
}

}  // namespace

int main(int argc, char** argv) {
    std::string data = std::string(DDTUP_BENCH_DATA) + "/real", out = "simplify-results";
    std::string from_csv, only;  // only: comma-separated image names (without .png), or all
    bool quick = false, parallel = false, vulkan = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--data" && i + 1 < argc) data = argv[++i];
        else if (arg == "--out" && i + 1 < argc) out = argv[++i];
        else if (arg == "--from-csv" && i + 1 < argc) from_csv = argv[++i];
        else if (arg == "--images" && i + 1 < argc) only = "," + std::string(argv[++i]) + ",";
        else if (arg == "--quick") quick = true;
        else if (arg == "--parallel") parallel = true;
        else if (arg == "--vulkan") vulkan = true;
        else {
            std::fprintf(stderr, "usage: ddtup-bench-simplify [--data DIR] [--out DIR] [--images A,B,...] [--quick] [--parallel] [--vulkan] | "
                                 "--from-csv FILE "
                                 "[--out DIR]\n");
            return 2;
        }
    }
    parallel = parallel || vulkan;  // the device's meshes are checked against the CPU rule's
    fs::create_directories(out);
    if (!from_csv.empty()) {
        const std::vector<Row> rows = readRows(from_csv);
        std::vector<double> shares;
        std::set<std::string> names;
        for (const Row& r : rows) {
            if (std::find(shares.begin(), shares.end(), r.share) == shares.end()) shares.push_back(r.share);
            names.insert(r.image);
        }
        writeSummary(rows, shares, names.size(), from_csv, out, "the device of that run");
        return 0;
    }
    std::vector<fs::path> images;
    for (const auto& entry : fs::directory_iterator(data))
        if (entry.path().extension() == ".png" &&
            (only.empty() || only.find("," + entry.path().stem().string() + ",") != std::string::npos))
            images.push_back(entry.path());
    std::sort(images.begin(), images.end());
    if (quick) images.resize(std::min<size_t>(images.size(), 1));
    const std::vector<double> shares = quick ? std::vector<double>{0.1} : std::vector<double>{1.0, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01};

    std::unique_ptr<VulkanContext> context;
    if (vulkan) context = createContext({-1, false});
    std::vector<Row> rows;
    int differing_meshes = 0;
    for (const fs::path& path : images) {
        Image original = readImage(path.string());
        if (quick) {  // a 96² crop: seconds, not minutes
            Image crop = original;
            crop.width = crop.height = 96;
            crop.pixels.clear();
            for (uint32_t y = 0; y < 96; ++y)
                crop.pixels.insert(crop.pixels.end(), original.row(y), original.row(y) + 96 * original.channels);
            original = crop;
        }
        Mesh optimised = buildGridMesh(original.width, original.height);
        optimizeSerial(optimised, costFieldOf(original));
        for (double share : shares) {
            Row ours;
            ours.image = path.stem().string();
            ours.share = share;
            ours.method = "ddtup";
            Mesh mesh = optimised;
            Image values = original;
            const auto start = std::chrono::steady_clock::now();
            const uint32_t target = uint32_t(std::max(4.0, std::ceil(share * original.width * original.height)));
            simplifySerial(mesh, values, target);
            ours.seconds = secondsSince(start);
            ours.vertices = usedVertexCount(mesh);
            const Image rendered = renderImage(mesh, values, {original.width, original.height});
            ours.psnr = peakSignalToNoiseRatio(toBytes(original), toBytes(rendered));
            const IndexedMesh file = indexedMeshOf(triangleIds(mesh), mesh.positions, values, {original.width, original.height});
            ours.ply = fileSize(MeshFormat::Ply, file);
            if (file.faceCount() <= kMaxSvgTriangles) {
                ours.svg = fileSize(MeshFormat::Svg, file);
                ours.svg_gz = gzippedSize(MeshFormat::Svg, file);
            }
            ours.png = bench::encodePng(rendered).bytes.size();
            rows.push_back(ours);
            if (parallel) {
                Row rule = ours;
                rule.method = kParallelRule;
                Mesh parallel_mesh = optimised;
                Image parallel_values = original;
                const auto parallel_start = std::chrono::steady_clock::now();
                simplifyParallel(parallel_mesh, parallel_values, target);
                rule.seconds = secondsSince(parallel_start);
                rule.vertices = usedVertexCount(parallel_mesh);
                rule.psnr = psnrOf(parallel_mesh, parallel_values, original);
                rule.ply = rule.svg = rule.svg_gz = rule.png = 0;
                std::printf("%-10s %5.1f %%  parallel rule %7u vertices %6.2f dB %6.2f s\n", rule.image.c_str(), 100 * share,
                            rule.vertices, rule.psnr, rule.seconds);
                rows.push_back(rule);
                if (vulkan) {
                    Mesh device_mesh = optimised;
                    Image device_values = original;
                    const auto device_start = std::chrono::steady_clock::now();
                    simplifyOnDevice(*context, device_mesh, device_values, target);
                    Row device = rule;
                    device.method = kVulkanRule;
                    device.seconds = secondsSince(device_start);
                    const bool same = device_mesh.edgeCount() == parallel_mesh.edgeCount() &&
                                      std::memcmp(device_mesh.vertices.data(), parallel_mesh.vertices.data(),
                                                  parallel_mesh.edgeCount() * sizeof(EdgeVertices)) == 0 &&
                                      std::memcmp(device_mesh.neighbours.data(), parallel_mesh.neighbours.data(),
                                                  parallel_mesh.edgeCount() * sizeof(EdgeNeighbours)) == 0 &&
                                      device_values.pixels == parallel_values.pixels;
                    differing_meshes += !same;
                    std::printf("%-10s %5.1f %%  on %s %6.2f s, %s mesh\n", rule.image.c_str(), 100 * share,
                                context->info.name.c_str(), device.seconds, same ? "the same" : "A DIFFERENT");
                    rows.push_back(device);
                }
            }
            Row peer = meshoptimizerRow(optimised, original, share);
            peer.image = ours.image;
            peer.share = share;
            rows.push_back(peer);
            std::printf("%-10s %5.1f %%  ddtup %7u vertices %6.2f dB %6.2f s | %-14s %7u vertices %6.2f dB %6.3f s%s\n",
                        ours.image.c_str(), 100 * share, ours.vertices, ours.psnr, ours.seconds, peer.method.c_str(),
                        peer.vertices, peer.psnr, peer.seconds, peer.folded ? " (folded)" : "");
            std::fflush(stdout);
        }
    }

    std::ofstream csv(out + "/simplify.csv");
    csv << "image,share,method,vertices,psnr_db,folded,seconds,ply_bytes,svg_bytes,svg_gz_bytes,png_bytes\n";
    for (const Row& r : rows)
        csv << r.image << "," << r.share << "," << r.method << "," << r.vertices << "," << r.psnr << "," << r.folded << "," << r.seconds << ","
            << r.ply << "," << r.svg << "," << r.svg_gz << "," << r.png << "\n";

    writeSummary(rows, shares, images.size(), data, out, context ? context->info.name : "");
    if (differing_meshes) {
        std::fprintf(stderr, "%d meshes from the device differ from the CPU rule's\n", differing_meshes);
        return 1;
    }
    std::printf("wrote %s/simplify.md, simplify.csv, simplify.svg\n", out.c_str());
    return 0;
}
