// The optimisation on the device: batches of accept/reject rounds and flips (glsl/image/plan,
// candidates, select, flip, edge_cost), recorded into few submits.
#include <algorithm>
#include <cassert>
#include <cstring>
#include <numeric>

#include "vulkan_backend_state.h"
#include "vulkan_error.h"

namespace ddt {

namespace {

// How many accept/reject rounds and iterations one submit records. Local-max needs one
// round per iteration; the round-based rules need more rounds, and MaxGain far fewer than
// lowest-id keys (~11 vs ~160 per iteration on a 1024-wide input). Empty dispatches after
// convergence cost little, a host round trip per round would cost more.
struct BatchShape {
    uint32_t rounds_per_iteration;
    uint32_t iterations;
};

BatchShape batchShapeFor(const FlipRule& rule) {
    if (rule.single_round) return {1, 8};
    if (rule.key_by_gain) return {8, 2};
    return {32, 1};
}

}  // namespace

// Zeroes the statuses, marks and counters: the state at the start of an optimisation.
void VulkanBackend::State::resetOptimisation() {
    CommandBatch commands(*context);
    for (Buffer* b : {&status[0], &status[1], &mark, &control})
        vkCmdFillBuffer(commands.buffer(), b->buffer, 0, VK_WHOLE_SIZE, 0);
    computeBarrier(commands.buffer());
    commands.submitAndWait();
    spans.clear();
    quadratic = false;
}

double VulkanBackend::State::meshCost() {
    CommandBatch commands(*context);
    dispatch(commands.buffer(), edgeCostKernel(), bindings(), push(), groupsFor(edge_count));
    commands.submitAndWait();
    std::vector<double> sums(groupsFor(edge_count));
    downloadFromBuffer(*context, partial_sums, sums.data(), sums.size() * 8);
    return std::accumulate(sums.begin(), sums.end(), 0.0);
}

double VulkanBackend::deviceMeshCost() { return state_->meshCost(); }

std::vector<double> VulkanBackend::deviceEdgeCosts() {
    State& s = *state_;
    CommandBatch commands(*s.context);
    PushConstants p = s.push();
    p.step = 1;
    dispatch(commands.buffer(), s.edgeCostKernel(), s.bindings(), p, groupsFor(s.edge_count));
    commands.submitAndWait();
    std::vector<double> costs(s.edge_count);
    downloadFromBuffer(*s.context, s.gain, costs.data(), costs.size() * 8);
    return costs;
}

std::vector<std::pair<std::string, KernelTime>> VulkanBackend::kernelTimes() const {
    return {state_->kernel_times.begin(), state_->kernel_times.end()};
}

Control VulkanBackend::State::readControl() {
    Control c;
    downloadFromBuffer(*context, control_readback, &c, sizeof(c));
    return c;
}

void VulkanBackend::State::markStep(VkCommandBuffer commands, const char* label) {
    if (!step_timestamps) return;
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, step_timestamps, uint32_t(step_labels.size()));
    step_labels.push_back(label);
}

// A planned step: the plan kernel sizes the step's indirect dispatch, then the step runs.
void VulkanBackend::State::recordStep(VkCommandBuffer commands, uint32_t step, VkPipeline kernel) {
    static const char* const kLabels[] = {"candidates", "select", "flip"};
    PushConstants p = push();
    p.step = step;
    dispatch(commands, kernels.plan, bindings(), p, 1);
    markStep(commands, "plan");
    dispatchIndirect(commands, kernel, bindings(), p, args, step);
    markStep(commands, kLabels[step]);
}

void VulkanBackend::State::collectStepTimes(uint32_t first_iteration) {
    if (!step_timestamps || step_labels.size() < 2) return;
    uint32_t iteration = first_iteration;  // each iteration's steps end with its flip
    std::vector<uint64_t> ticks(step_labels.size());
    VK_CHECK(vkGetQueryPoolResults(context->device, step_timestamps, 0, uint32_t(ticks.size()),
                                   ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (size_t i = 1; i < ticks.size(); ++i) {
        KernelTime& t = kernel_times[step_labels[i]];
        const double ms = double(ticks[i] - ticks[i - 1]) * context->properties.limits.timestampPeriod * 1e-6;
        t.dispatches += 1;
        t.ms += ms;
        if (t.iteration_ms.size() <= iteration) t.iteration_ms.resize(iteration + 1, 0.0);
        t.iteration_ms[iteration] += ms;
        if (std::strcmp(step_labels[i], "flip") == 0) ++iteration;
    }
}

void VulkanBackend::State::recordIteration(VkCommandBuffer commands, uint32_t rounds, bool candidates, bool flip) {
    if (candidates) recordStep(commands, kArgsCandidates, candidatesKernel());
    for (uint32_t r = 0; r < rounds; ++r) recordStep(commands, kArgsSelect, kernels.select);
    if (flip) recordStep(commands, kArgsFlip, kernels.flip);
}

void VulkanBackend::State::recordControlReadback(VkCommandBuffer commands) {
    VkBufferCopy region{0, 0, sizeof(Control)};
    vkCmdCopyBuffer(commands, control.buffer, control_readback.buffer, 1, &region);
}

OptimizeStats VulkanBackend::State::finishStats(const Control& c, double cost_init, uint64_t dispatches,
                                                double device_ns) {
    OptimizeStats stats;
    stats.cost_init = cost_init;
    stats.cost_final = meshCost();
    stats.flips = uint64_t(c.total_flips_high) << 32 | c.total_flips_low;
    // Like the serial sweeps, count the last iteration, which found no candidate.
    stats.iterations = c.iteration + (c.capped ? 0 : 1);
    stats.rounds = c.total_rounds;
    stats.max_rounds_in_iteration = c.max_rounds_in_iteration;
    stats.dispatches = dispatches;
    stats.device_ms = device_ns * 1e-6;
    stats.capped = c.capped != 0 || c.phase != kPhaseDone;
    spans.clear();
    return stats;
}

OptimizeStats VulkanBackend::optimize() {
    State& s = *state_;
    VulkanContext& c = *s.context;
    s.resetOptimisation();
    const double cost_init = s.meshCost();

    const BatchShape shape = batchShapeFor(s.rule);
    const uint64_t dispatches_per_batch = uint64_t(shape.iterations) * 2 * (2 + shape.rounds_per_iteration);
    CommandBatch batch(c);
    VkCommandBuffer commands = batch.buffer();
    if (s.timestamps) {
        vkCmdResetQueryPool(commands, s.timestamps, 0, 2);
        vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, s.timestamps, 0);
    }
    if (s.options.profile && s.context->timestamps) {
        if (s.step_timestamps) vkDestroyQueryPool(c.device, s.step_timestamps, nullptr);
        VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = uint32_t(dispatches_per_batch + 1);
        VK_CHECK(vkCreateQueryPool(c.device, &info, nullptr, &s.step_timestamps));
        vkCmdResetQueryPool(commands, s.step_timestamps, 0, info.queryCount);
        s.step_labels.clear();
        s.markStep(commands, "start");
    }
    for (uint32_t i = 0; i < shape.iterations; ++i) s.recordIteration(commands, shape.rounds_per_iteration, true, true);
    if (s.timestamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s.timestamps, 1);
    s.recordControlReadback(commands);
    batch.finishRecording();

    // Each submit advances the device's state machine; a loop that cannot end otherwise
    // is bounded by the caps on iterations and rounds.
    const uint64_t max_batches =
        (uint64_t(s.options.max_iterations) + 1) * (s.options.max_rounds / shape.rounds_per_iteration + 2);
    uint64_t batches = 0;
    double device_ns = 0.0;
    Control control{};
    do {
        batch.submitAndWait();
        ++batches;
        if (s.timestamps) {
            uint64_t ticks[2];
            VK_CHECK(vkGetQueryPoolResults(c.device, s.timestamps, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                                           VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
            device_ns += double(ticks[1] - ticks[0]) * c.properties.limits.timestampPeriod;
        }
        s.collectStepTimes(uint32_t((batches - 1) * shape.iterations));
        control = s.readControl();
    } while (control.phase != kPhaseDone && batches < max_batches);
    return s.finishStats(control, cost_init, batches * dispatches_per_batch, device_ns);
}

OptimizeStats VulkanBackend::optimizeStepwise(const std::function<void(const IterationSnapshot&)>& inspect) {
    State& s = *state_;
    VulkanContext& c = *s.context;
    s.resetOptimisation();
    const double cost_init = s.meshCost();
    uint64_t dispatches = 0;
    auto run = [&](uint32_t rounds, bool candidates, bool flip) {
        CommandBatch batch(c);
        s.recordIteration(batch.buffer(), rounds, candidates, flip);
        s.recordControlReadback(batch.buffer());
        batch.submitAndWait();
        dispatches += 2 * (rounds + candidates + flip);
        return s.readControl();
    };
    auto download = [&](const Buffer& buffer, uint32_t count) {
        std::vector<uint32_t> values(count);
        if (count) downloadFromBuffer(c, buffer, values.data(), count * 4);
        return values;
    };

    Control control = run(1, true, false);
    while (control.phase != kPhaseDone) {
        while (!s.rule.single_round && control.undecided_count[control.round & 1] > 0 &&
               control.round < s.options.max_rounds)
            control = run(1, false, false);

        IterationSnapshot snapshot;
        snapshot.iteration = control.iteration;
        snapshot.rounds = control.round;
        snapshot.mesh = mesh();
        snapshot.candidates = download(s.candidate_list, control.candidate_count);
        std::sort(snapshot.candidates.begin(), snapshot.candidates.end());
        const std::vector<uint32_t> status = download(s.status[control.round & 1], s.edge_count);
        std::vector<double> gains(s.edge_count);
        downloadFromBuffer(c, s.gain, gains.data(), gains.size() * 8);
        for (uint32_t e : snapshot.candidates) {
            snapshot.candidate_gains.push_back(gains[e]);
            if (status[e] == kStatusAccepted) snapshot.accepted.push_back(e);
            if (status[e] == kStatusUndecided) snapshot.undecided.push_back(e);
        }
        inspect(snapshot);

        run(0, false, true);
        control = run(1, true, false);
    }
    return s.finishStats(control, cost_init, dispatches, 0.0);
}

}  // namespace ddt
