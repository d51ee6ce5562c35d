// The Delaunay table's rows: ddtup's serial Delaunay (delaunayOfPoints) against CGAL's
// Delaunay_triangulation_2 on one point set, each in its own forked child (child_run.h):
// median time of `repeats` runs, peak memory of the first, and the checks. With `vulkan`, also
// the device's Delaunay (compute/delaunay/device_delaunay.h) on the first Vulkan device, in a
// child of its own, compared with the serial result edge for edge on every set.
#pragma once

#include <cstdint>
#include <string>

#include "point_sets.h"

namespace bench {

struct TriangulationRow {
    std::string set;
    uint64_t points = 0;
    // Per library: "" if its child finished, else why not ("timeout after 600 s").
    std::string ddtup_failure, cgal_failure;
    double ddtup_s = 0.0, cgal_s = 0.0;            // CPU time (Span)
    double ddtup_wall_s = 0.0, cgal_wall_s = 0.0;  // wall-clock time
    uint64_t ddtup_bytes = 0, cgal_bytes = 0;  // peak RSS growth over the run
    uint64_t ddtup_triangles = 0, cgal_triangles = 0;
    std::string ddtup_check;  // "" if checkDelaunay and checkMesh(convex) pass, else the first problem
    bool cgal_valid = false;  // Delaunay_triangulation_2::is_valid
    // Where the triangulation is unique: "equal" or "N edges differ"; on cocircular sets
    // "both valid" (both checks pass, same triangle count) or what failed.
    std::string comparison;
    // The Vulkan Delaunay, when measured: "" or why not; median wall-clock time of the whole
    // call (sweep, device rounds, numbering; the device and its kernels set up before); peak
    // RSS growth (on lavapipe the device's memory is the process's); rounds, flips and the
    // stages' seconds of the last run (DeviceDelaunayStats); "equal" to the serial edges or
    // "N edges differ".
    bool vulkan_measured = false;
    std::string vulkan_failure;
    double vulkan_wall_s = 0.0;
    uint64_t vulkan_bytes = 0;
    uint32_t vulkan_rounds = 0;
    uint64_t vulkan_flips = 0;
    double vulkan_sweep_s = 0.0, vulkan_device_s = 0.0, vulkan_number_s = 0.0;
    std::string vulkan_comparison;
};

TriangulationRow measureTriangulations(const PointSet& set, uint32_t repeats, uint32_t timeout_s, bool vulkan);

}  // namespace bench
