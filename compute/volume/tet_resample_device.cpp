#include "tet_resample_device.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

#include "buffer.h"
#include "commands.h"
#include "kernel_layout.h"
#include "raster.h"
#include "transfer.h"

// SPIR-V written by glslangValidator at build time (see CMakeLists.txt).
#include "spirv/tet_resample.h"

namespace ddt {

namespace {

// A float NaN's bits: the slab starts as NaN, as core's output does, so a voxel no tet stored
// shows as NaN (a deferred tet's voxels are written by core afterwards).
constexpr uint32_t kNanBits = 0x7fc00000u;

std::vector<VkDescriptorType> resampleBindingTypes() {
    std::vector<VkDescriptorType> types(kTetResampleBindingCount, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER);
    types[kTetResampleBindingDeferred] = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    return types;
}

// core's SampleGrid tables per axis (tet_resample_layout.h's kTetResampleBindingSampleRanges),
// from the same sample coordinates (glsl/raster.h).
std::vector<uint32_t> sampleRangesOf(const std::array<uint32_t, 3>& in, const std::array<uint32_t, 3>& out) {
    std::vector<uint32_t> ranges;
    for (int a = 0; a < 3; ++a) {
        std::vector<int64_t> samples(out[a]);
        for (uint32_t i = 0; i < out[a]; ++i) samples[i] = sampleCoord(i, in[a], out[a]);
        const size_t first = ranges.size();
        ranges.resize(first + 2 * size_t(in[a]));
        for (uint32_t x = 0; x < in[a]; ++x) {
            const int64_t at = vertexCoord(x, out[a]);
            ranges[first + x] = uint32_t(std::lower_bound(samples.begin(), samples.end(), at) - samples.begin());
            ranges[first + in[a] + x] = uint32_t(std::upper_bound(samples.begin(), samples.end(), at) - samples.begin());
        }
    }
    return ranges;
}

// One slab of the window: rows [y_begin, y_end) of planes [z_begin, z_end).
struct Slab {
    uint32_t y_begin, y_end, z_begin, z_end;
};

// The window cut into slabs of at most `voxels` voxels: whole planes while a plane fits, else
// runs of whole rows within one plane.
std::vector<Slab> slabsOf(const TetResampleWindow& window, uint64_t voxels) {
    const uint64_t width = window.out_end[0] - window.out_begin[0];
    const uint32_t height = window.out_end[1] - window.out_begin[1];
    const uint64_t rows = voxels / width;
    std::vector<Slab> slabs;
    if (rows >= height) {
        const uint32_t planes = uint32_t(std::min<uint64_t>(rows / height, window.out_end[2] - window.out_begin[2]));
        for (uint32_t z = window.out_begin[2]; z < window.out_end[2]; z += planes)
            slabs.push_back({window.out_begin[1], window.out_end[1], z, std::min(z + planes, window.out_end[2])});
    } else {
        for (uint32_t z = window.out_begin[2]; z < window.out_end[2]; ++z)
            for (uint32_t y = window.out_begin[1]; y < window.out_end[1]; y += uint32_t(rows))
                slabs.push_back({y, uint32_t(std::min<uint64_t>(y + rows, window.out_end[1])), z, z + 1});
    }
    return slabs;
}

// Workgroups for one invocation per slot: (x, y), y > 1 only beyond kTetResampleMaxGroups.
std::array<uint32_t, 2> groupsFor(uint32_t slots) {
    const uint32_t groups = (slots + kTetResampleGroupSize - 1) / kTetResampleGroupSize;
    const uint32_t rows = (groups + kTetResampleMaxGroups - 1) / kTetResampleMaxGroups;
    return {rows ? (groups + rows - 1) / rows : 0, rows};
}

class DeviceTetResampler {
public:
    DeviceTetResampler(VulkanContext& context, const TetMesh& mesh, const std::vector<float>& values,
                       const TetResampleWindow& window, const TetResampleDeviceOptions& options);
    ~DeviceTetResampler() {
        for (Buffer& buffer : buffers_) destroyBuffer(context_, buffer);
    }
    DeviceTetResampler(const DeviceTetResampler&) = delete;
    DeviceTetResampler& operator=(const DeviceTetResampler&) = delete;

    // Every slab on the device, each copied into `out`; the deferred tets' slots.
    std::vector<uint32_t> run(float* out, TetResampleDeviceReport& report);
    uint64_t bytes() const;

private:
    void copySlab(const Slab& slab, float* out) const;

    VulkanContext& context_;
    KernelLayout layout_;
    VkPipeline kernel_ = VK_NULL_HANDLE;
    TetResampleWindow window_;
    TetResamplePush push_{};
    std::vector<Slab> slabs_;
    Buffer buffers_[kTetResampleBindingCount];
};

DeviceTetResampler::DeviceTetResampler(VulkanContext& context, const TetMesh& mesh, const std::vector<float>& values,
                                       const TetResampleWindow& window, const TetResampleDeviceOptions& options)
    : context_(context), layout_(context, resampleBindingTypes(), sizeof(TetResamplePush)), window_(window) {
    kernel_ = layout_.createKernel(kSpirvTetResample, sizeof(kSpirvTetResample));
    for (int a = 0; a < 3; ++a) {
        push_.mesh_size[a] = mesh.size[a];
        push_.vertex_offset[a] = window.vertex_offset[a];
        push_.in_size[a] = window.size[a];
        push_.out_size[a] = window.new_size[a];
        push_.out_begin[a] = window.out_begin[a];
        push_.out_end[a] = window.out_end[a];
    }
    push_.slot_count = mesh.slotCount();
    push_.max_box_trips = options.max_box_trips;
    push_.narrow_log2 = options.narrow_log2;
    const uint64_t slab_voxels = std::min<uint64_t>(options.slab_voxels, context.properties.limits.maxTexelBufferElements);
    slabs_ = slabsOf(window, slab_voxels);
    uint64_t largest = 0;
    for (const Slab& slab : slabs_)
        largest = std::max<uint64_t>(largest, uint64_t(window.out_end[0] - window.out_begin[0]) *
                                                  (slab.y_end - slab.y_begin) * (slab.z_end - slab.z_begin));
    const std::vector<uint32_t> ranges = sampleRangesOf(window.size, window.new_size);
    try {
        auto make = [&](uint32_t binding, VkDeviceSize bytes, VkFormat format, const void* data = nullptr,
                        Placement placement = Placement::Device) {
            buffers_[binding] = createBuffer(context, std::max<VkDeviceSize>(bytes, 16), placement, format);
            if (data && bytes) uploadToBuffer(context, buffers_[binding], data, bytes);
        };
        make(kTetResampleBindingVertices, VkDeviceSize(mesh.slotCount()) * 16, VK_FORMAT_R32G32B32A32_UINT,
             mesh.vertices.data());
        make(kTetResampleBindingValues, values.size() * 4, VK_FORMAT_R32_SFLOAT, values.data());
        make(kTetResampleBindingSampleRanges, ranges.size() * 4, VK_FORMAT_R32_UINT, ranges.data());
        make(kTetResampleBindingSlab, largest * 4, VK_FORMAT_R32_SFLOAT, nullptr, Placement::Readback);
        make(kTetResampleBindingDeferred, 4 + (VkDeviceSize(mesh.slotCount()) + 31) / 32 * 4, VK_FORMAT_UNDEFINED,
             nullptr, Placement::Readback);
    } catch (...) {
        for (Buffer& buffer : buffers_) destroyBuffer(context, buffer);
        throw;
    }
    layout_.bind(buffers_);
}

uint64_t DeviceTetResampler::bytes() const {
    uint64_t total = 0;
    for (const Buffer& buffer : buffers_) total += buffer.size;
    return total;
}

// The slab's rows into their places in the whole output.
void DeviceTetResampler::copySlab(const Slab& slab, float* out) const {
    const uint32_t width = window_.out_end[0] - window_.out_begin[0];
    const uint32_t height = slab.y_end - slab.y_begin;
    const Buffer& buffer = buffers_[kTetResampleBindingSlab];
    std::vector<float> staged;  // only where the slab's memory is not mapped
    if (!buffer.mapped) {
        staged.resize(size_t(width) * height * (slab.z_end - slab.z_begin));
        downloadFromBuffer(context_, buffer, staged.data(), staged.size() * 4);
    }
    const float* rows = buffer.mapped ? static_cast<const float*>(buffer.mapped) : staged.data();
    for (uint32_t z = slab.z_begin; z < slab.z_end; ++z)
        for (uint32_t y = slab.y_begin; y < slab.y_end; ++y) {
            const float* row = rows + size_t(width) * ((y - slab.y_begin) + size_t(height) * (z - slab.z_begin));
            std::memcpy(out + window_.out_begin[0] + size_t(window_.new_size[0]) * (y + size_t(window_.new_size[1]) * z),
                        row, size_t(width) * 4);
        }
}

std::vector<uint32_t> DeviceTetResampler::run(float* out, TetResampleDeviceReport& report) {
    const std::array<uint32_t, 2> groups = groupsFor(push_.slot_count);
    const Buffer& deferred = buffers_[kTetResampleBindingDeferred];
    for (size_t s = 0; s < slabs_.size(); ++s) {
        const Slab& slab = slabs_[s];
        TetResamplePush push = push_;
        push.slab_begin_y = slab.y_begin;
        push.slab_end_y = slab.y_end;
        push.slab_begin_z = slab.z_begin;
        push.slab_end_z = slab.z_end;
        CommandBatch batch(context_);
        // After the previous slab's kernel and the host's copy: its writes before the fills.
        computeBarrier(batch.buffer());
        if (s == 0) vkCmdFillBuffer(batch.buffer(), deferred.buffer, 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(batch.buffer(), buffers_[kTetResampleBindingSlab].buffer, 0, VK_WHOLE_SIZE, kNanBits);
        computeBarrier(batch.buffer());
        if (groups[0]) {
            layout_.bindKernel(batch.buffer(), kernel_, &push);
            vkCmdDispatch(batch.buffer(), groups[0], groups[1], 1);
        }
        batch.finishRecording();
        batch.submitAndWait();
        copySlab(slab, out);
        ++report.slabs;
    }
    uint32_t count = 0;
    downloadFromBuffer(context_, deferred, &count, 4);
    std::vector<uint32_t> slots;
    if (count == 0) return slots;
    std::vector<uint32_t> bits((push_.slot_count + 31) / 32);
    downloadFromBuffer(context_, deferred, bits.data(), bits.size() * 4, 4);
    slots.reserve(count);
    for (uint32_t word = 0; word < bits.size(); ++word)
        for (uint32_t b = bits[word]; b; b &= b - 1) slots.push_back(32 * word + uint32_t(std::countr_zero(b)));
    return slots;
}

}  // namespace

std::string tetResampleDeviceProblem(const VulkanContext& context, const TetMesh& mesh, const TetResampleWindow& window,
                                     const TetResampleDeviceOptions& options) {
    const uint64_t texels = context.properties.limits.maxTexelBufferElements;
    if (mesh.slotCount() > texels || mesh.vertexCount() > texels)
        return std::to_string(std::max(mesh.slotCount(), mesh.vertexCount())) +
               " tets or vertices in one array, more than the device's " + std::to_string(texels) + " texels";
    const uint64_t width = window.out_end[0] - window.out_begin[0];
    if (width > std::min<uint64_t>(options.slab_voxels, texels))
        return "an output row of " + std::to_string(width) + " voxels, longer than a slab";
    if (!checkTetResampleSize(window.size, window.new_size).empty()) return checkTetResampleSize(window.size, window.new_size);
    return "";
}

void resampleTetsVulkan(VulkanContext& context, const TetMesh& mesh, const std::vector<float>& values,
                        const TetResampleWindow& window, float* out, const TetResampleDeviceOptions& options,
                        TetResampleDeviceReport* report) {
    if (values.size() != mesh.vertexCount()) throw std::invalid_argument("device tet resampler: one value per vertex");
    if (const std::string problem = tetResampleDeviceProblem(context, mesh, window, options); !problem.empty())
        throw std::invalid_argument("device tet resampler: " + problem);
    TetResampleDeviceReport local;
    TetResampleDeviceReport& result = report ? *report : local;
    for (int a = 0; a < 3; ++a)
        if (window.out_begin[a] >= window.out_end[a]) return;
    std::vector<uint32_t> deferred;
    {
        DeviceTetResampler resampler(context, mesh, values, window, options);
        deferred = resampler.run(out, result);
        result.device_bytes = resampler.bytes();
    }
    // After the device's memory is given back: core's resampling of the tets the kernel left.
    result.deferred = uint32_t(deferred.size());
    if (!deferred.empty()) resampleTetSlotsInto(mesh, values, window, &deferred, out);
}

}  // namespace ddt
