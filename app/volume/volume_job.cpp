#include "volume_job.h"

#include <chrono>
#include <filesystem>
#include <new>

#include "backend_factory.h"
#include "exit_codes.h"
#include "parallel.h"
#include "user_error.h"
#include "volume.h"
#include "volume_file.h"
#include "volume_slices.h"
#include "volume_stack.h"

namespace ddt {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The output's sample type: the input's, or --depth's within what volume formats hold (8 and
// 16 bits keep the input's signedness).
VoxelType outputType(VoxelType input, const std::string& depth) {
    const bool is_signed = input == VoxelType::i8 || input == VoxelType::i16;
    if (depth == "8") return is_signed ? VoxelType::i8 : VoxelType::u8;
    if (depth == "16") return is_signed ? VoxelType::i16 : VoxelType::u16;
    if (depth == "float") return VoxelType::f32;
    return input;
}

std::array<double, 3> factorsOf(const Settings& settings) {
    if (settings.axis_scales[0] > 0.0) return settings.axis_scales;
    return {settings.scale, settings.scale, settings.scale};
}

// Throws UserError when the output would be too large.
void checkOutputSize(const std::string& input, const std::array<uint32_t, 3>& out) {
    const uint64_t voxels = uint64_t(out[0]) * out[1] * out[2];
    if (voxels > kMaxOutputVoxels)
        throw UserError(input + ": the output would have " + std::to_string(voxels) + " voxels, more than the limit of 2^31");
}

// --slices' folder, made before the long part so that a bad one fails first.
void makeSlicesFolder(const std::string& folder) {
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error || !std::filesystem::is_directory(folder, error))
        throw UserError(folder + ": cannot make the folder for --slices" + (error ? ": " + error.message() : ""));
}

VolumeReport magnifyVolume(size_t index, const ImageTask& task, const Settings& settings, const VolumeEngine& engine,
                           Reporter& reporter) {
    VolumeReport report;
    auto start = std::chrono::steady_clock::now();
    if (!settings.slices.empty()) makeSlicesFolder(settings.slices);
    reporter.stage(index, task.input, Stage::Read);
    const Volume volume = settings.stack ? readImageStack(task.input) : readVolume(task.input);
    report.in = volume.size;
    report.out = resampledSize(volume.size, factorsOf(settings));
    checkOutputSize(task.input, report.out);
    report.read_s = secondsSince(start);

    reporter.stage(index, task.input, Stage::Optimize);
    VolumeMagnifyOptions options;
    options.weight = settings.cost == "face-scf" ? TetWeight::face_scf : TetWeight::variance;
    options.brick_side = settings.tile;
    options.optimize = engine.optimize;
    options.resample = engine.resample;
    report.on_device = bool(engine.optimize);
    Volume output;
    output.size = report.out;
    output.type = outputType(volume.type, settings.depth);
    output.metadata = volume.metadata;
    output.index_to_world = resampledAffine(volume.index_to_world, volume.size, output.size);
    output.values = magnifyVolumeValues(volume, output.size, options, report.stats);

    start = std::chrono::steady_clock::now();
    reporter.stage(index, task.input, Stage::Write);
    for (const std::string& note : writeVolume(task.output, output, output.type)) reporter.notice(task.input, note);
    if (!settings.slices.empty()) {
        const std::string stem = std::filesystem::path(withoutVolumeExtension(task.output)).filename().string();
        writeMiddleSlices(output, settings.slices, stem);
    }
    report.write_s = secondsSince(start);
    return report;
}

}  // namespace

bool runVolumeTasks(const std::vector<ImageTask>& tasks, const Settings& settings, Reporter& reporter,
                    const std::function<void(const ImageTask&, const VolumeReport&)>& on_done) {
    VolumeEngine engine;
    try {
        engine = makeVolumeEngine(settings);
    } catch (const UserError& error) {
        reporter.fatal(error.what(), kExitNoDevice);
        return false;
    }
    reporter.backend(engine.choice);
    for (size_t i = 0; i < tasks.size(); ++i) {
        const ImageTask& task = tasks[i];
        if (task.state != ImageTask::State::Ready || !task.volume) continue;
        const auto start = std::chrono::steady_clock::now();
        try {
            const VolumeReport report = magnifyVolume(i, task, settings, engine, reporter);
            reporter.done(i, task, OutputSize{report.out[0], report.out[1], report.out[2]}, secondsSince(start));
            if (on_done) on_done(task, report);
        } catch (const UserError& error) {
            reporter.failed(task.input, error.what());
        } catch (const std::bad_alloc&) {
            reporter.failed(task.input, task.input + ": out of memory");
        } catch (const std::exception& error) {
            reporter.failed(task.input, task.input + ": internal error: " + error.what(), true);
        }
    }
    return true;
}

}  // namespace ddt
