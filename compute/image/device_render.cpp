// Rendering on the device: the rows each triangle spans (glsl/image/row_spans.comp), then
// bands of output rows (glsl/image/render.comp), blended with the fallback on
// (device_fallback.cpp), read back into the caller's rows.
#include <algorithm>
#include <cmath>

#include "raster.h"
#include "vulkan_backend_state.h"

namespace ddt {

void VulkanBackend::State::computeRowSpans() {
    std::vector<uint32_t> initial(2 * size_t(height) + 1, 0);
    for (uint32_t y = 0; y < height; ++y) initial[2 * y] = kNone;  // first row: min over none yet
    uploadToBuffer(*context, row_spans, initial.data(), initial.size() * 4);
    CommandBatch commands(*context);
    dispatch(commands.buffer(), kernels.row_spans, bindings(), push(), groupsFor(edge_count));
    commands.submitAndWait();
    spans.resize(initial.size());
    downloadFromBuffer(*context, row_spans, spans.data(), spans.size() * 4);
}

PushConstants VulkanBackend::State::windowPush(const RenderWindow& window) const {
    PushConstants p = push();
    p.out_width = window.out.width;
    p.out_height = window.out.height;
    p.input_width = window.input_width;
    p.input_height = window.input_height;
    p.crop_x = window.crop_x;
    p.crop_y = window.crop_y;
    p.band_first_col = window.x_begin;
    p.band_width = window.width();
    return p;
}

// Records `kernel`, a per-triangle pass (render.comp's frame), over output rows
// [y_begin, y_end) and columns [x_begin, x_end) of the window: 2D dispatches over the edge
// rows whose triangles may touch them.
void VulkanBackend::State::recordTrianglePart(VkCommandBuffer commands, VkPipeline kernel, const RenderWindow& window,
                                              uint32_t y_begin, uint32_t y_end, uint32_t x_begin, uint32_t x_end) {
    // Crop rows the part samples, and the edge rows whose triangles touch them.
    const OutputSize out = window.out;
    const int64_t unit = vertexCoord(1, out.height);
    const uint32_t v_first = uint32_t(sampleCoord(y_begin, window.input_height, out.height) / unit);
    const uint32_t v_last = uint32_t((sampleCoord(y_end - 1, window.input_height, out.height) + unit - 1) / unit);
    const uint32_t local_first = v_first > window.crop_y ? v_first - window.crop_y : 0;
    const uint32_t local_last = v_last > window.crop_y ? v_last - window.crop_y : 0;
    uint32_t first_row = height, last_row = 0;
    for (uint32_t y = 0; y < height; ++y) {
        if (spans[2 * y] <= local_last && spans[2 * y + 1] >= local_first) {
            first_row = std::min(first_row, y);
            last_row = std::max(last_row, y);
        }
    }
    PushConstants p = windowPush(window);
    p.first_row = y_begin;
    p.row_count = y_end - y_begin;
    p.first_col = x_begin;
    p.col_count = x_end - x_begin;
    const uint32_t groups_per_row = (3 * width - 2 + kGroupSize - 1) / kGroupSize;
    for (uint32_t row = first_row; row <= last_row && first_row <= last_row; row += kMaxGroups) {
        p.first_edge_row = row;
        dispatch2D(commands, kernel, bindings(), p, groups_per_row, std::min(last_row - row + 1, kMaxGroups));
    }
}

// Renders output rows [y_begin, y_end), columns [x_begin, x_end) of the window into the
// band buffer, which holds rows of the window's width from y_begin on.
void VulkanBackend::State::renderPart(const RenderWindow& window, uint32_t y_begin, uint32_t y_end, uint32_t x_begin,
                                      uint32_t x_end) {
    CommandBatch commands(*context);
    recordTrianglePart(commands.buffer(), kernels.render, window, y_begin, y_end, x_begin, x_end);
    commands.submitAndWait();
}

// An invocation rasterises two triangles, each looping over its rows and columns within the
// part; keep that below lavapipe's loop budget (kItemsPerInvocation).
VulkanBackend::State::PartShape VulkanBackend::State::partShape(const RenderWindow& window) const {
    const uint32_t widest =
        uint32_t(std::ceil(double(spans[2 * height] + 1) * window.out.width / window.input_width)) + 2;
    const uint32_t cols = std::min(window.width(), kRasterLoopBudget / 4);
    return {std::max(1u, kRasterLoopBudget / (std::min(widest, cols) + 2) - 1), cols};
}

void VulkanBackend::renderWindow(const RenderWindow& window, float* rows) {
    State& s = *state_;
    if (window.x_begin >= window.x_end || window.y_begin >= window.y_end) return;
    if (s.spans.empty()) s.computeRowSpans();
    const uint32_t window_w = window.width();
    const State::PartShape part = s.partShape(window);
    const VkDeviceSize row_bytes = VkDeviceSize(window_w) * 16;  // an rgba32f texel per pixel
    const VkDeviceSize band_bytes =
        std::min<VkDeviceSize>(kBandBytes, VkDeviceSize(s.context->properties.limits.maxTexelBufferElements) * 16);
    const uint32_t band_rows =
        uint32_t(std::min<VkDeviceSize>(part.rows, std::max<VkDeviceSize>(1, band_bytes / row_bytes)));
    const VkDeviceSize band_needed = std::min<VkDeviceSize>(window.height(), band_rows) * row_bytes;
    if (s.band.size < band_needed) {
        destroyBuffer(*s.context, s.band);
        // The host reads every rendered row: keep the band in host-visible memory.
        s.band = createBuffer(*s.context, band_needed, Placement::Readback, VK_FORMAT_R32G32B32A32_SFLOAT);
        s.writeDescriptors();
    }
    const uint32_t c = s.image->channels;
    for (uint32_t y = window.y_begin; y < window.y_end; y += band_rows) {
        const uint32_t band_end = std::min(window.y_end, y + band_rows);
        for (uint32_t x = window.x_begin; x < window.x_end; x += part.cols)
            s.renderPart(window, y, band_end, x, std::min(window.x_end, x + part.cols));
        if (s.fallback) s.blendBand(window, y, band_end);
        // The band holds four floats per pixel; the caller wants `channels`.
        const size_t pixels = size_t(band_end - y) * window_w;
        float* band_rows_out = rows + size_t(y - window.y_begin) * window_w * c;
        if (c == 4) {
            downloadFromBuffer(*s.context, s.band, band_rows_out, pixels * 16);
        } else {
            s.band_texels.resize(pixels * 4);
            downloadFromBuffer(*s.context, s.band, s.band_texels.data(), pixels * 16);
            for (size_t i = 0; i < pixels; ++i) std::copy_n(s.band_texels.data() + 4 * i, c, band_rows_out + c * i);
        }
    }
}

}  // namespace ddt
