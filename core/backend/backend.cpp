#include "backend.h"

#include "delaunay.h"

namespace ddt {

Mesh Backend::delaunayPixels(uint32_t width, uint32_t height, const std::vector<uint32_t>& pixel_ids) {
    return delaunayOfPixels(width, height, pixel_ids);
}

Mesh Backend::delaunayPoints(uint32_t width, uint32_t height, const std::vector<Position>& points) {
    return delaunayOfPoints(width, height, points);
}

}  // namespace ddt
