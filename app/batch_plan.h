// Which images and volumes a run magnifies and where each result goes: the inputs on the command line or
// found in an input folder, mapped to output paths, with the ones to skip or refuse decided
// before any pixel is read.
#pragma once

#include <string>
#include <vector>

#include "settings.h"

namespace ddt {

struct ImageTask {
    std::string input;   // as given, or found under the input folder; "-": standard input
    std::string output;  // "-": standard output
    std::string mesh;    // where the optimised mesh goes (--mesh); "" = nowhere
    std::string mask;    // the image marking the input's known pixels (--mask, --mask-dir); "" = all known
    bool volume = false; // a volume file (core/io/volume_file.h), magnified by app/volume/
    enum class State { Ready, Skipped, Refused } state = State::Ready;
    std::string reason;  // why skipped or refused; a refusal names the file first
};

// Whether two paths name the same file, however spelled (links, "..", symlinks), or would once made.
bool sameFile(const std::string& a, const std::string& b);

// "" if the settings can magnify the volume `input`, else the message, naming it: options that
// mean nothing for volumes.
std::string volumeTaskProblem(const std::string& input, const Settings& settings);

// Throws UserError when the input folder cannot be listed or the output folder cannot be
// created or written. Inputs are in command-line order, or sorted for a folder.
std::vector<ImageTask> planBatch(const Settings& settings);

}  // namespace ddt
