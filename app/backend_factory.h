// The backend the settings ask for, created once per run: the Vulkan device, its pipelines
// and buffers are reused by every image of a batch.
#pragma once

#include <memory>
#include <string>

#include "backend.h"
#include "settings.h"

namespace ddt {

struct ChosenBackend {
    std::unique_ptr<Backend> backend;
    std::string device_name;  // "" for the CPU backend
    std::string device_type;  // "discrete", "integrated", "virtual", "cpu" or "other"
};

// Throws UserError when no usable Vulkan device exists (the message says how to get one).
ChosenBackend makeBackend(const Settings& settings);

}  // namespace ddt
