#include "batch_plan.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>

#include "image.h"
#include "image_formats.h"
#include "mesh_file.h"
#include "user_error.h"
#include "volume_file.h"

namespace ddt {

namespace {

namespace fs = std::filesystem;

bool isHidden(const fs::path& path) { return path.filename().string().starts_with("."); }

// The images and volumes under `folder`, relative to it and sorted. Hidden files and folders (ddtup's own
// temporary files among them) are passed over, and so are the folders in `skip` (the output
// folder, the masks' folder) when they lie inside: results and masks must not become inputs.
std::vector<fs::path> imagesIn(const fs::path& folder, bool recursive, const std::vector<fs::path>& skip) {
    std::error_code error;
    if (!fs::is_directory(folder, error))
        throw UserError(folder.string() + (fs::exists(folder, error) ? ": not a folder" : ": no such folder"));
    std::vector<fs::path> images;
    fs::recursive_directory_iterator it(folder, fs::directory_options::none, error), end;
    if (error) throw UserError(folder.string() + ": cannot list the folder: " + error.message());
    for (; it != end; it.increment(error)) {
        if (error) throw UserError(it->path().string() + ": cannot list the folder: " + error.message());
        const fs::path& path = it->path();
        const bool folder_entry = it->is_directory(error);
        const auto skipped = [&] {
            return std::any_of(skip.begin(), skip.end(), [&](const fs::path& other) { return fs::equivalent(path, other, error); });
        };
        if (isHidden(path) || (folder_entry && (!recursive || skipped()))) {
            if (folder_entry) it.disable_recursion_pending();
            continue;
        }
        if (!folder_entry && (formatOfExtension(path.extension().string()) || isVolumePath(path.string())))
            images.push_back(fs::relative(path, folder));
    }
    std::sort(images.begin(), images.end());
    return images;
}

// Creates the output folder and checks that files can be made in it, so that a bad folder is
// one message rather than one per image.
void prepareOutputFolder(const fs::path& folder) {
    std::error_code error;
    fs::create_directories(folder, error);
    if (error) throw UserError(folder.string() + ": cannot create the output folder: " + error.message());
    if (!fs::is_directory(folder, error)) throw UserError(folder.string() + ": is not a folder");
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw UserError(folder.string() + ": cannot write into the output folder: " + std::strerror(errno));
}

// out/<relative>, with the format's extension when one is asked for.
std::string outputPathFor(const fs::path& output_folder, fs::path relative, const std::string& format) {
    if (!format.empty() && isVolumePath(relative.string()))
        relative = withoutVolumeExtension(relative.string()) + "." + format;
    else if (!format.empty())
        relative.replace_extension("." + format);
    else if (!relative.has_extension())
        relative += ".png";  // standard input, or a file without an extension
    return (output_folder / relative).string();
}

// The masks in --mask-dir by sub-folder and stem: each folder is listed once, however many
// inputs look in it. Only files with the extension of a format ddtup reads count.
class MaskIndex {
public:
    explicit MaskIndex(fs::path root) : root_(std::move(root)) {}

    // The mask of the input at `relative` (to the input folder, or its file name): the one
    // image in root/<relative's folder> with the same stem. Sets `reason` when there is none
    // or more than one.
    std::string maskFor(const fs::path& relative, std::string& reason) {
        const fs::path folder = root_ / relative.parent_path();
        const std::vector<std::string>& found = stemsIn(folder)[relative.stem().string()];
        const std::string wanted = (folder / relative.stem()).string() + ".*";
        if (found.empty()) reason = "no mask " + wanted + " (--mask-dir)";
        if (found.size() > 1) reason = "more than one mask matches " + wanted + ": " + found[0] + ", " + found[1];
        return found.size() == 1 ? found.front() : "";
    }

private:
    std::map<std::string, std::vector<std::string>>& stemsIn(const fs::path& folder) {
        auto [at, added] = folders_.try_emplace(folder.string());
        if (!added) return at->second;
        std::error_code error;
        for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
            const fs::path& path = entry.path();
            if (formatOfExtension(path.extension().string()) && !entry.is_directory(error))
                at->second[path.stem().string()].push_back(path.string());
        }
        for (auto& [stem, paths] : at->second) std::sort(paths.begin(), paths.end());
        return at->second;
    }

    fs::path root_;
    std::map<std::string, std::map<std::string, std::vector<std::string>>> folders_;
};

// Gives each image its mask: --mask's for the one input, or its namesake in --mask-dir; an
// image without one, or whose mask is also an output, is refused.
void assignMasks(std::vector<ImageTask>& tasks, const std::vector<fs::path>& relatives, const Settings& settings) {
    MaskIndex masks(settings.mask_folder);
    for (size_t i = 0; i < tasks.size(); ++i) {
        ImageTask& task = tasks[i];
        if (task.volume || task.state != ImageTask::State::Ready) continue;
        if (!settings.mask.empty()) task.mask = settings.mask;
        if (settings.mask_folder.empty()) continue;
        std::string reason;
        if (task.input == kStandardStream) reason = "--mask-dir finds masks by the inputs' names; standard input has none";
        else task.mask = masks.maskFor(relatives[i], reason);
        if (reason.empty() && sameFile(task.mask, task.input)) reason = "its mask " + task.mask + " is the input itself";
        if (reason.empty() && sameFile(task.mask, task.output)) reason = "its mask " + task.mask + " is also its output";
        if (!reason.empty()) {
            task.state = ImageTask::State::Refused;
            task.reason = task.input + ": " + reason;
        }
    }
}

ImageTask readyTask(const std::string& input, const std::string& output) {
    ImageTask task;
    task.input = input;
    task.output = output;
    task.volume = input != kStandardStream && isVolumePath(input);
    return task;
}

// The extension of the mesh format `name` ("ply", ".OBJ") names, lower case, with the dot.
const char* meshExtension(const std::string& name) {
    const MeshFormat format = *meshFormatOf(name);
    return format == MeshFormat::Ply ? ".ply" : format == MeshFormat::Obj ? ".obj" : ".svg";
}

// Refuses volumes the settings cannot magnify, and images the volume-only settings were given to.
void refuseMismatchedKinds(std::vector<ImageTask>& tasks, const Settings& settings) {
    for (ImageTask& task : tasks) {
        const bool volume = task.volume;
        if (volume) task.reason = volumeTaskProblem(task.input, settings);
        if (volume && task.reason.empty() && task.output != kStandardStream && !isVolumePath(task.output))
            task.reason = task.input + ": a volume's output must be a volume file (" + volumeExtensionNames() + "), not " +
                          task.output;
        if (!volume && settings.axis_scales[0] > 0.0)
            task.reason = task.input + ": --scale with three factors applies to volumes only";
        if (!volume && task.input != kStandardStream && isVolumePath(task.output))
            task.reason = task.input + ": an image's output must be an image file, not " + task.output;
        if (!task.reason.empty()) task.state = ImageTask::State::Refused;
    }
}

// Refuses outputs that are an input, or that another input already writes; skips finished ones.
void decideStates(std::vector<ImageTask>& tasks, bool skip_existing) {
    std::map<std::string, const ImageTask*> writers;  // canonical output -> first task writing it
    for (ImageTask& task : tasks) {
        if (task.output == kStandardStream || task.state != ImageTask::State::Ready) continue;
        std::error_code error;
        const std::string key = fs::weakly_canonical(task.output, error).string();
        if (task.input != kStandardStream && sameFile(task.input, task.output)) {
            task.state = ImageTask::State::Refused;
            task.reason = task.output + ": output is the input file; refusing to overwrite it";
        } else if (auto [first, inserted] = writers.emplace(key, &task); !inserted) {
            task.state = ImageTask::State::Refused;
            task.reason = task.input + ": its output " + task.output + " is also the output of " + first->second->input +
                          "; rename one of them or choose another --format";
        } else if (skip_existing && fs::exists(task.output, error)) {
            task.state = ImageTask::State::Skipped;
            task.reason = "output exists";
        }
    }
}

}  // namespace

std::string volumeTaskProblem(const std::string& input, const Settings& settings) {
    if (!settings.image_only_options.empty())
        return input + ": " + settings.image_only_options.front() + " does not apply to volumes";
    if (settings.cost == "sederberg")
        return input + ": --cost sederberg is an edge cost of images; volumes take variance or face-scf";
    return "";
}

bool sameFile(const std::string& a, const std::string& b) {
    std::error_code error;
    if (fs::exists(a, error) && fs::exists(b, error)) return fs::equivalent(a, b, error);
    return fs::weakly_canonical(a, error) == fs::weakly_canonical(b, error);
}

std::vector<ImageTask> planBatch(const Settings& settings) {
    std::vector<ImageTask> tasks;
    std::vector<fs::path> relatives;  // each input's path relative to the input folder, or its name
    if (!settings.mask_folder.empty() && !fs::is_directory(settings.mask_folder))
        throw UserError(settings.mask_folder + ": --mask-dir needs a folder of masks" +
                        (fs::exists(settings.mask_folder) ? "" : "; it does not exist"));
    if (settings.singleForm()) {
        tasks.push_back(readyTask(settings.inputs.front(), settings.output));
        relatives.push_back(fs::path(settings.inputs.front()).filename());
    } else {
        const fs::path output_folder = settings.output_folder;
        prepareOutputFolder(output_folder);
        if (!settings.input_folder.empty()) {
            const fs::path input_folder = settings.input_folder;
            std::vector<fs::path> skip = {output_folder};
            if (!settings.mask_folder.empty()) skip.push_back(settings.mask_folder);
            for (const fs::path& relative : imagesIn(input_folder, settings.recursive, skip)) {
                tasks.push_back(readyTask((input_folder / relative).string(), outputPathFor(output_folder, relative, settings.format)));
                relatives.push_back(relative);
            }
        } else {
            for (const std::string& input : settings.inputs) {
                tasks.push_back(readyTask(input, outputPathFor(output_folder, fs::path(input).filename(), settings.format)));
                relatives.push_back(fs::path(input).filename());
            }
        }
    }
    // A batch's meshes go beside their outputs, named like them.
    if (!settings.mesh.empty())
        for (ImageTask& task : tasks)
            task.mesh = settings.singleForm() ? settings.mesh
                                              : fs::path(task.output).replace_extension(meshExtension(settings.mesh)).string();
    if (settings.stack)
        for (ImageTask& task : tasks) task.volume = true;
    refuseMismatchedKinds(tasks, settings);
    assignMasks(tasks, relatives, settings);
    decideStates(tasks, settings.skip_existing);
    return tasks;
}

}  // namespace ddt
