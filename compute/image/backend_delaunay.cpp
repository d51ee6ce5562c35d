// The Vulkan backend's Delaunay triangulations of samples: on its device
// (compute/delaunay/device_delaunay.h, the same records as the host's) where --delaunay asks.
#include <stdexcept>

#include "delaunay/device_delaunay.h"
#include "vulkan_backend.h"
#include "vulkan_backend_state.h"

namespace ddt {

namespace {

// `device()` unless the place says host; where it allows, the host's `host()` for inputs the
// device cannot hold (std::invalid_argument: more edge records than its texel buffers take).
// `on_device` says which ran.
template <class Device, class Host>
Mesh triangulate(DelaunayPlace place, Device device, Host host, bool& on_device) {
    on_device = false;
    if (place == DelaunayPlace::host) return host();
    try {
        Mesh mesh = device();
        on_device = true;
        return mesh;
    } catch (const std::invalid_argument& error) {
        if (place == DelaunayPlace::device_where_fits) return host();
        throw UserError(std::string("the device's Delaunay cannot take them (") + error.what() + "); --delaunay cpu can");
    }
}

}  // namespace

void VulkanBackend::setDelaunayPlace(DelaunayPlace place) { state_->options.delaunay = place; }

Mesh VulkanBackend::delaunayPixels(uint32_t width, uint32_t height, const std::vector<uint32_t>& pixel_ids) {
    State& s = *state_;
    return triangulate(
        s.options.delaunay, [&] { return deviceDelaunayOfPixels(*s.context, width, height, pixel_ids); },
        [&] { return Backend::delaunayPixels(width, height, pixel_ids); }, s.delaunay_on_device);
}

Mesh VulkanBackend::delaunayPoints(uint32_t width, uint32_t height, const std::vector<Position>& points) {
    State& s = *state_;
    return triangulate(
        s.options.delaunay, [&] { return deviceDelaunayOfPoints(*s.context, width, height, points); },
        [&] { return Backend::delaunayPoints(width, height, points); }, s.delaunay_on_device);
}

bool VulkanBackend::lastDelaunayOnDevice() const { return state_->delaunay_on_device; }

}  // namespace ddt
