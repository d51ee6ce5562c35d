#include "tet_device.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <sys/mman.h>
#include <unistd.h>

#include "buffer.h"
#include "commands.h"
#include "tet_kernels.h"
#include "transfer.h"
#include "vulkan_error.h"

namespace ddt {

namespace {

// How an array whose size follows the slot capacity must start. Only what the kernels read
// before they write is zeroed: on a device whose memory is host memory (lavapipe) a page
// becomes resident once written, by a kernel or by a fill, so the spare slots, the lists'
// unused tails and the claims of slots no candidate reads cost no memory.
enum class Start {
    as_allocated,   // written before read
    zeroed_in_use,  // the state bits: zeroed over the slots in use; tet_apply.comp zeroes an appended slot's
    zeroed,         // the scan words (a bit or two a slot): the plan sums over all blocks
};
struct SlotArray {
    uint32_t binding;
    VkFormat format;
    Start start;
};
// The claims start as allocated: tet_select.comp's kTetStepClear sets those of the round's read
// sets to 0 before the claims, and no other claim is read.
constexpr SlotArray kSlotArrays[] = {
    {kTetBindingVertices, VK_FORMAT_R32G32B32A32_UINT, Start::as_allocated},
    {kTetBindingNeighbours, VK_FORMAT_R32G32B32A32_UINT, Start::as_allocated},
    {kTetBindingCost, VK_FORMAT_R32G32_UINT, Start::as_allocated},
    {kTetBindingGradient, VK_FORMAT_R32G32_UINT, Start::as_allocated},
    {kTetBindingState, VK_FORMAT_R32_UINT, Start::zeroed_in_use},
    {kTetBindingClaimHigh, VK_FORMAT_R32_UINT, Start::as_allocated},
    {kTetBindingClaimLow, VK_FORMAT_R32_UINT, Start::as_allocated},
    {kTetBindingFreeSlots, VK_FORMAT_R32_UINT, Start::as_allocated},
    {kTetBindingFreed, VK_FORMAT_R32_UINT, Start::as_allocated},
    {kTetBindingActive, VK_FORMAT_R32_UINT, Start::as_allocated},
    {kTetBindingEvaluate, VK_FORMAT_R32_UINT, Start::as_allocated},
    {kTetBindingCandidates, VK_FORMAT_R32G32_UINT, Start::as_allocated},
    {kTetBindingCarried, VK_FORMAT_R32G32_UINT, Start::as_allocated},
    {kTetBindingMasks, VK_FORMAT_R32_UINT, Start::zeroed},
    {kTetBindingWordPrefix, VK_FORMAT_R32G32_UINT, Start::zeroed},
    {kTetBindingBlocks, VK_FORMAT_R32G32B32A32_UINT, Start::zeroed},
};
// The claims' contents matter only within a round's selection, so a growth (between the
// selection and the flips) does not copy them.
bool keptOnGrowth(uint32_t binding) { return binding != kTetBindingClaimHigh && binding != kTetBindingClaimLow; }
// TetDeviceOptions::poison's fill: no valid state word, claim, slot or vertex.
constexpr uint32_t kPoison = 0xffffffffu;

uint32_t blocksFor(uint64_t capacity) { return uint32_t((capacity + 32 * kTetScanWords - 1) / (32 * kTetScanWords)); }

// Bytes of a capacity-sized array. The freed slots of one round: a 3–2 replaces three tets of
// its own by two, so a round frees at most a third of the tets.
VkDeviceSize slotArrayBytes(uint32_t binding, uint64_t capacity, TetWeight weight) {
    const uint64_t words = uint64_t(blocksFor(capacity)) * kTetScanWords;
    switch (binding) {
        case kTetBindingVertices:
        case kTetBindingNeighbours: return capacity * 16;
        // The variance weight's costs are recomputed where read: a chunk for the totals only.
        case kTetBindingCost: return (weight == TetWeight::face_scf ? capacity : std::min<uint64_t>(capacity, kTetCostChunk)) * 8;
        case kTetBindingCandidates:
        case kTetBindingCarried: return capacity * 8;
        case kTetBindingGradient: return weight == TetWeight::face_scf ? capacity * 24 : 8;
        case kTetBindingFreed: return (capacity / 3 + 1) * 4;
        case kTetBindingMasks:
        case kTetBindingWordPrefix: return words * 8;
        case kTetBindingBlocks: return uint64_t(blocksFor(capacity)) * 16;
        default: return capacity * 4;
    }
}

// TetCosts::total's sum: compensated (Neumaier), in slot order, fed a chunk at a time.
struct CompensatedSum {
    double sum = 0.0, compensation = 0.0;
    void add(const double* costs, size_t count) {
        for (size_t i = 0; i < count; ++i) {
            const double c = costs[i], next = sum + c;
            compensation += std::abs(sum) >= std::abs(c) ? (sum - next) + c : (c - next) + sum;
            sum = next;
        }
    }
    double total() const { return sum + compensation; }
};

// Uploads a host array and releases it. Into memory the host can map (on lavapipe, device
// memory is host memory) it goes a chunk at a time, and each chunk's whole pages go back to the
// system as soon as they are copied (MADV_DONTNEED; the array is freed right after and never
// read again), so the host's copy and the device's are never whole together: for the mesh's
// vertices and neighbours that was the run's peak (two copies of 16 bytes a slot).
template <class T>
void uploadReleasing(VulkanContext& context, Buffer& buffer, std::vector<T>& host) {
    const size_t bytes = host.size() * sizeof(T);
    if (!buffer.mapped) {
        if (bytes) uploadToBuffer(context, buffer, host.data(), bytes);
    } else {
        constexpr size_t kChunk = size_t(16) << 20;
        const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
        const char* source = reinterpret_cast<const char*>(host.data());
        for (size_t done = 0; done < bytes; done += kChunk) {
            const size_t chunk = std::min(kChunk, bytes - done);
            std::memcpy(static_cast<char*>(buffer.mapped) + done, source + done, chunk);
            const uintptr_t begin = (uintptr_t(source + done) + page - 1) & ~(page - 1);
            const uintptr_t end = uintptr_t(source + done + chunk) & ~(page - 1);
            if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_DONTNEED);
        }
    }
    std::vector<T>().swap(host);
}

uint32_t uintOf(uint64_t value, const char* what) {
    if (value > kTetMaxSlots) throw std::invalid_argument(std::string("device tet optimizer: too many ") + what);
    return uint32_t(value);
}

class DeviceTetOptimizer {
public:
    // Takes the mesh's arrays: each host array is released as soon as the device holds it, so
    // that the two copies are never whole at once (moveMeshTo gives them back). With
    // `owned_values` (the field's values), those too once uploaded.
    DeviceTetOptimizer(VulkanContext& context, TetMesh& mesh, const TetCostField& field,
                       const TetParallelOptions& options, const TetDeviceOptions& device,
                       std::vector<double>* owned_values);
    ~DeviceTetOptimizer() {
        for (Buffer& buffer : buffers_) destroyBuffer(context_, buffer);
    }
    DeviceTetOptimizer(const DeviceTetOptimizer&) = delete;
    DeviceTetOptimizer& operator=(const DeviceTetOptimizer&) = delete;

    // Rounds until a round accepts nothing (or the cap); the statistics but the costs.
    TetParallelStats run(TetDeviceReport& report);
    // TetCosts::total of the device's cost cache.
    double costTotal() const;
    std::vector<double> costs() const;
    // The mesh back from the device (without its neighbours unless `neighbours`); every device
    // array is released on the way, so that the host's copy and the device's are not both whole
    // at once.
    void moveMeshTo(TetMesh& mesh, bool neighbours);
    uint64_t bytes() const;
    uint32_t capacity() const { return capacity_; }
    uint64_t zeroedBytes() const { return zeroed_bytes_; }
    double initMs() const { return init_ms_; }  // wall time of the first cache's submit

private:
    TetControl readControl() const;
    void writeControl(const TetControl& control);
    void allocate(uint32_t capacity);
    void zeroArrays(uint32_t slots);
    void release(uint32_t binding) { destroyBuffer(context_, buffers_[binding]); }
    void grow(uint32_t need);
    // Calls consume(first, costs, count) for the cost of every slot, a chunk at a time in slot
    // order: read from the cache (face_scf) or computed into the cost buffer (variance).
    template <class Consume>
    void forEachCostChunk(Consume consume) const;
    TetPush pushFor(uint32_t step) const;

    VulkanContext& context_;
    TetKernels kernels_;
    TetWeight weight_;
    TetPush push_{};
    uint32_t capacity_ = 0;
    uint32_t rounds_per_submit_;
    bool profile_;
    bool poison_;
    double init_ms_ = 0.0;
    uint64_t zeroed_bytes_ = 0;
    Buffer buffers_[kTetBindingCount];
};

DeviceTetOptimizer::DeviceTetOptimizer(VulkanContext& context, TetMesh& mesh, const TetCostField& field,
                                       const TetParallelOptions& options, const TetDeviceOptions& device,
                                       std::vector<double>* owned_values)
    : context_(context), kernels_(context), weight_(options.weight), rounds_per_submit_(std::max(device.rounds_per_submit, 1u)),
      profile_(device.profile && context.timestamps), poison_(device.poison) {
    if (options.evaluate_all || options.after_round)
        throw std::invalid_argument("device tet optimizer: evaluate_all and after_round are CPU-only");
    if (field.size != mesh.size || field.values.size() != mesh.vertexCount())
        throw std::invalid_argument("device tet optimizer: the field does not fit the mesh");
    const uint32_t slots = mesh.slotCount();
    if (const std::string problem = tetDeviceProblem(context, slots, mesh.vertexCount(), weight_); !problem.empty())
        throw std::invalid_argument("device tet optimizer: " + problem);
    const uint32_t capacity = uintOf(std::max<uint64_t>(uint64_t(std::ceil(slots * (1.0 + device.slack))), slots + 1), "slots");
    push_.size_x = mesh.size[0];
    push_.size_y = mesh.size[1];
    push_.size_z = mesh.size[2];
    push_.face_scf = weight_ == TetWeight::face_scf;
    push_.max_rounds = options.max_rounds;
    for (uint32_t a = 0; a < 3; ++a) {
        const uint64_t bits = std::bit_cast<uint64_t>(field.spacing[a]);
        push_.spacing_bits[2 * a] = uint32_t(bits);
        push_.spacing_bits[2 * a + 1] = uint32_t(bits >> 32);
    }
    // tet_cost.cpp's contentScaleOf, the same operations.
    const uint64_t scale = std::bit_cast<uint64_t>(field.spacing[0] * field.spacing[1] * field.spacing[2] / 6.0);
    push_.content_scale_bits[0] = uint32_t(scale);
    push_.content_scale_bits[1] = uint32_t(scale >> 32);

    try {
        buffers_[kTetBindingValues] = createBuffer(context, std::max<VkDeviceSize>(field.values.size() * 8, 16),
                                                   Placement::Device, VK_FORMAT_R32G32_UINT);
        uploadToBuffer(context, buffers_[kTetBindingValues], field.values.data(), field.values.size() * 8);
        if (owned_values) std::vector<double>().swap(*owned_values);
        buffers_[kTetBindingControl] = createBuffer(context, sizeof(TetControl), Placement::Readback);
        buffers_[kTetBindingArgs] = createBuffer(context, kTetStepCount * 16, Placement::Device);
        allocate(capacity);
        // The first round's active tets are listed by the first cache (tet_refresh.comp).
        TetControl control{};
        control.phase = kTetPhaseRunning;
        control.next_step = kTetStepMark;
        control.slot_count = slots;
        control.free_count = uint32_t(mesh.free_slots.size());
        writeControl(control);
        uploadReleasing(context, buffers_[kTetBindingVertices], mesh.vertices);
        uploadReleasing(context, buffers_[kTetBindingNeighbours], mesh.neighbours);
        if (!mesh.free_slots.empty())
            uploadToBuffer(context, buffers_[kTetBindingFreeSlots], mesh.free_slots.data(), mesh.free_slots.size() * 4);
        std::vector<uint32_t>().swap(mesh.free_slots);
        // After the mesh, so that the positions' host and device copies do not add to its upload.
        std::vector<int32_t> positions(size_t(mesh.vertexCount()) * 4, 0);
        for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
            const VertexCoordinates c = coordinatesOf(mesh, v);
            positions[4 * size_t(v)] = c.x;
            positions[4 * size_t(v) + 1] = c.y;
            positions[4 * size_t(v) + 2] = c.z;
        }
        buffers_[kTetBindingPositions] = createBuffer(context, std::max<VkDeviceSize>(positions.size() * 4, 16),
                                                      Placement::Device, VK_FORMAT_R32G32B32A32_SINT);
        uploadToBuffer(context, buffers_[kTetBindingPositions], positions.data(), positions.size() * 4);
        std::vector<int32_t>().swap(positions);
        zeroArrays(slots);  // after the host arrays are gone: on lavapipe the zeroed pages become resident
    } catch (...) {
        for (Buffer& buffer : buffers_) destroyBuffer(context, buffer);
        throw;
    }
    kernels_.bind(buffers_);
    CommandBatch init(context);
    kernels_.recordInit(init.buffer(), pushFor(kTetStepInit), slots);
    const auto start = std::chrono::steady_clock::now();
    init.submitAndWait();
    init_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

TetPush DeviceTetOptimizer::pushFor(uint32_t step) const {
    TetPush push = push_;
    push.step = step;
    push.capacity = capacity_;
    push.blocks = blocksFor(capacity_);
    return push;
}

TetControl DeviceTetOptimizer::readControl() const {
    TetControl control;
    downloadFromBuffer(context_, buffers_[kTetBindingControl], &control, sizeof(control));
    return control;
}

void DeviceTetOptimizer::writeControl(const TetControl& control) {
    uploadToBuffer(context_, buffers_[kTetBindingControl], &control, sizeof(control));
}

// Every capacity-sized array, as allocated (zeroArrays zeroes what must start at 0), or poisoned.
void DeviceTetOptimizer::allocate(uint32_t capacity) {
    capacity_ = capacity;
    for (const SlotArray& array : kSlotArrays)
        buffers_[array.binding] =
            createBuffer(context_, slotArrayBytes(array.binding, capacity, weight_), Placement::Device, array.format);
    if (!poison_) return;
    CommandBatch batch(context_);
    for (const SlotArray& array : kSlotArrays)
        vkCmdFillBuffer(batch.buffer(), buffers_[array.binding].buffer, 0, VK_WHOLE_SIZE, kPoison);
    batch.submitAndWait();
}

// What must start at 0 (SlotArray::start) set to 0, `slots` slots in use.
void DeviceTetOptimizer::zeroArrays(uint32_t slots) {
    CommandBatch batch(context_);
    for (const SlotArray& array : kSlotArrays) {
        const Buffer& buffer = buffers_[array.binding];
        const VkDeviceSize bytes = array.start == Start::zeroed          ? buffer.size
                                   : array.start == Start::zeroed_in_use ? VkDeviceSize(slots) * 4
                                                                         : 0;
        if (bytes == 0) continue;
        vkCmdFillBuffer(batch.buffer(), buffer.buffer, 0, bytes, 0);
        zeroed_bytes_ += bytes;
    }
    batch.submitAndWait();
}

// Larger arrays holding the old ones' contents (the scan words zeroed first, the claims not
// kept): the round that stopped for want of slots goes on where it stopped (kTetStepApply), with
// the same lists, masks and prefix sums (the blocks added beyond the old ones are empty).
void DeviceTetOptimizer::grow(uint32_t need) {
    const uint64_t wanted = std::max<uint64_t>(uint64_t(need) + need / 4, uint64_t(capacity_) + capacity_ / 2);
    const uint32_t capacity = uintOf(wanted, "slots for the flips");
    if (const std::string problem = tetDeviceProblem(context_, capacity, push_.size_x * push_.size_y * push_.size_z, weight_);
        !problem.empty())
        throw std::invalid_argument("device tet optimizer: cannot grow: " + problem);
    Buffer old[kTetBindingCount];
    CommandBatch batch(context_);
    for (const SlotArray& array : kSlotArrays) {
        Buffer& buffer = buffers_[array.binding];
        old[array.binding] = buffer;
        buffer = createBuffer(context_, slotArrayBytes(array.binding, capacity, weight_), Placement::Device, array.format);
        if (array.start == Start::zeroed) {
            vkCmdFillBuffer(batch.buffer(), buffer.buffer, 0, VK_WHOLE_SIZE, 0);
            zeroed_bytes_ += buffer.size;
        } else if (poison_) {
            vkCmdFillBuffer(batch.buffer(), buffer.buffer, 0, VK_WHOLE_SIZE, kPoison);
        }
    }
    computeBarrier(batch.buffer());
    for (const SlotArray& array : kSlotArrays) {
        if (!keptOnGrowth(array.binding)) continue;
        const VkBufferCopy region{0, 0, old[array.binding].size};
        vkCmdCopyBuffer(batch.buffer(), old[array.binding].buffer, buffers_[array.binding].buffer, 1, &region);
    }
    batch.submitAndWait();
    for (const SlotArray& array : kSlotArrays) destroyBuffer(context_, old[array.binding]);
    capacity_ = capacity;
    kernels_.bind(buffers_);
}

TetParallelStats DeviceTetOptimizer::run(TetDeviceReport& report) {
    // Profiling: a timestamp before the first step and after each.
    VkQueryPool timestamps = VK_NULL_HANDLE;
    const uint32_t queries = rounds_per_submit_ * kTetStepCount + 1;
    if (profile_) {
        VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = queries;
        VK_CHECK(vkCreateQueryPool(context_.device, &info, nullptr, &timestamps));
    }
    TetControl control = readControl();
    try {
        while (control.phase != kTetPhaseDone) {
            // Recorded anew after a growth: the pushes carry the capacity, the set the new arrays.
            CommandBatch batch(context_);
            if (timestamps) {
                vkCmdResetQueryPool(batch.buffer(), timestamps, 0, queries);
                vkCmdWriteTimestamp(batch.buffer(), VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, 0);
            }
            for (uint32_t round = 0; round < rounds_per_submit_; ++round)
                for (uint32_t step = 0; step < kTetStepCount; ++step)
                    kernels_.recordStep(batch.buffer(), pushFor(step), buffers_[kTetBindingArgs], timestamps,
                                        round * kTetStepCount + step + 1);
            batch.finishRecording();
            for (;;) {
                batch.submitAndWait();
                ++report.submits;
                if (timestamps) {
                    std::vector<uint64_t> ticks(queries);
                    VK_CHECK(vkGetQueryPoolResults(context_.device, timestamps, 0, queries, queries * 8, ticks.data(), 8,
                                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
                    for (uint32_t q = 1; q < queries; ++q)
                        report.step_ms[(q - 1) % kTetStepCount] +=
                            double(ticks[q] - ticks[q - 1]) * context_.properties.limits.timestampPeriod * 1e-6;
                }
                control = readControl();
                if (control.phase != kTetPhaseRunning) break;
            }
            if (control.phase == kTetPhaseGrow) {
                grow(control.need);
                ++report.grows;
                control.phase = kTetPhaseRunning;
                writeControl(control);
            }
        }
    } catch (...) {
        if (timestamps) vkDestroyQueryPool(context_.device, timestamps, nullptr);
        throw;
    }
    if (timestamps) vkDestroyQueryPool(context_.device, timestamps, nullptr);
    TetParallelStats stats;
    for (uint32_t k = 0; k < kFlipKindCount; ++k) stats.flips[k] = control.flips[k];
    stats.rounds = control.rounds;
    stats.capped = control.capped != 0;
    stats.evaluated = control.evaluated;
    stats.candidates = control.candidates;
    return stats;
}

template <class Consume>
void DeviceTetOptimizer::forEachCostChunk(Consume consume) const {
    const uint32_t slots = readControl().slot_count;
    std::vector<double> chunk(std::min(slots, kTetCostChunk));
    for (uint32_t first = 0; first < slots; first += kTetCostChunk) {
        const uint32_t count = std::min(kTetCostChunk, slots - first);
        VkDeviceSize offset = VkDeviceSize(first) * 8;
        if (weight_ == TetWeight::variance) {
            CommandBatch batch(context_);
            kernels_.recordTotals(batch.buffer(), pushFor(kTetStepTotals), first);
            batch.submitAndWait();
            offset = 0;
        }
        downloadFromBuffer(context_, buffers_[kTetBindingCost], chunk.data(), VkDeviceSize(count) * 8, offset);
        consume(first, chunk.data(), count);
    }
}

std::vector<double> DeviceTetOptimizer::costs() const {
    std::vector<double> costs(readControl().slot_count);
    forEachCostChunk([&](uint32_t first, const double* chunk, uint32_t count) { std::copy_n(chunk, count, costs.data() + first); });
    return costs;
}

double DeviceTetOptimizer::costTotal() const {
    CompensatedSum sum;
    forEachCostChunk([&](uint32_t, const double* chunk, uint32_t count) { sum.add(chunk, count); });
    return sum.total();
}

void DeviceTetOptimizer::moveMeshTo(TetMesh& mesh, bool neighbours) {
    const TetControl control = readControl();
    for (uint32_t binding = 0; binding < kTetBindingCount; ++binding)
        if (binding != kTetBindingVertices && binding != kTetBindingNeighbours && binding != kTetBindingFreeSlots)
            release(binding);
    mesh.free_slots.resize(control.free_count);
    if (control.free_count)
        downloadFromBuffer(context_, buffers_[kTetBindingFreeSlots], mesh.free_slots.data(), VkDeviceSize(control.free_count) * 4);
    release(kTetBindingFreeSlots);
    if (!neighbours) release(kTetBindingNeighbours);
    mesh.vertices.resize(control.slot_count);
    if (control.slot_count)
        downloadFromBuffer(context_, buffers_[kTetBindingVertices], mesh.vertices.data(), VkDeviceSize(control.slot_count) * 16);
    release(kTetBindingVertices);
    if (!neighbours) return;
    mesh.neighbours.resize(control.slot_count);
    if (control.slot_count)
        downloadFromBuffer(context_, buffers_[kTetBindingNeighbours], mesh.neighbours.data(), VkDeviceSize(control.slot_count) * 16);
    release(kTetBindingNeighbours);
}

uint64_t DeviceTetOptimizer::bytes() const {
    uint64_t total = 0;
    for (const Buffer& buffer : buffers_) total += buffer.size;
    return total;
}

}  // namespace

uint64_t tetDeviceBytes(uint64_t capacity, uint64_t vertices, TetWeight weight) {
    uint64_t total = vertices * (8 + 16) + sizeof(TetControl) + kTetStepCount * 16;
    for (const SlotArray& array : kSlotArrays) total += slotArrayBytes(array.binding, capacity, weight);
    return total;
}

std::string tetDeviceProblem(const VulkanContext& context, uint64_t slots, uint64_t vertices, TetWeight weight) {
    if (slots >= kTetMaxSlots) return std::to_string(slots) + " slots, more than the kernels can name (2^28)";
    const uint64_t limit = context.properties.limits.maxTexelBufferElements;
    const uint64_t elements = std::max(weight == TetWeight::face_scf ? 3 * slots : slots, vertices);
    if (elements > limit)
        return std::to_string(elements) + " texels in one array, more than the device's " + std::to_string(limit);
    const uint64_t largest = slots * (weight == TetWeight::face_scf ? 24 : 16);
    VkPhysicalDeviceMaintenance3Properties maintenance{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &maintenance;
    vkGetPhysicalDeviceProperties2(context.physical, &properties);
    if (largest > maintenance.maxMemoryAllocationSize)
        return "an array of " + std::to_string(largest >> 20) + " MiB, more than the largest allocation of " +
               std::to_string(maintenance.maxMemoryAllocationSize >> 20) + " MiB";
    return "";
}

namespace {

TetParallelStats optimizeOnDevice(VulkanContext& context, TetMesh& mesh, const TetCostField& field,
                                  std::vector<double>* owned_values, const TetParallelOptions& options,
                                  const TetDeviceOptions& device, TetDeviceReport* report) {
    TetDeviceReport local;
    TetDeviceReport& out = report ? *report : local;
    // Holds the mesh until moveMeshTo.
    DeviceTetOptimizer optimizer(context, mesh, field, options, device, owned_values);
    const double cost_before = optimizer.costTotal();
    TetParallelStats stats = optimizer.run(out);
    stats.cost_before = cost_before;
    stats.cost_after = optimizer.costTotal();
    if (report) out.costs = optimizer.costs();
    out.capacity = optimizer.capacity();
    out.init_ms = optimizer.initMs();
    out.device_bytes = optimizer.bytes();
    out.zeroed_bytes = optimizer.zeroedBytes();
    optimizer.moveMeshTo(mesh, device.return_neighbours);
    return stats;
}

}  // namespace

TetParallelStats optimizeTetMeshVulkan(VulkanContext& context, TetMesh& mesh, const TetCostField& field,
                                       const TetParallelOptions& options, const TetDeviceOptions& device,
                                       TetDeviceReport* report) {
    return optimizeOnDevice(context, mesh, field, nullptr, options, device, report);
}

TetParallelStats optimizeTetMeshVulkan(VulkanContext& context, TetMesh& mesh, TetCostField&& field,
                                       const TetParallelOptions& options, const TetDeviceOptions& device,
                                       TetDeviceReport* report) {
    return optimizeOnDevice(context, mesh, field, &field.values, options, device, report);
}

}  // namespace ddt
