// The backend the settings ask for, created once per run: the Vulkan device, its pipelines
// and buffers are reused by every image of a batch.
//
// --backend auto (the default) takes Vulkan on a GPU (discrete, integrated or virtual) and
// the CPU backend where the only Vulkan devices are CPU implementations (lavapipe,
// SwiftShader) or there is none: on a CPU the serial C++ optimizer is 3-4 times faster than
// the same flips run through a software Vulkan driver (docs/USAGE.md, "Backends"). A machine
// without a GPU device node is not asked at all (backend_factory.cpp says why). --device
// names a Vulkan device, and so asks for Vulkan.
#pragma once

#include <memory>
#include <string>

#include "backend.h"
#include "context.h"
#include "volume_magnify.h"
#include "reporter.h"
#include "settings.h"

namespace ddt {

struct ChosenBackend {
    std::unique_ptr<Backend> backend;
    BackendChoice choice;
};

// Throws UserError when Vulkan was asked for and no usable device exists (the message says
// how to get one).
ChosenBackend makeBackend(const Settings& settings);

// What --backend auto does without --device: the index of the GPU to use, or -1 and why the
// CPU serves instead (no GPU device node, no usable device, or only CPU implementations).
struct AutomaticDevice {
    int index = -1;
    std::string cpu_reason;
};
AutomaticDevice automaticDevice();

// What flips and resamples the volumes of a run (app/volume/): the serial generalized Lawson
// and core's resampling on the CPU, or the parallel rule (compute/volume/tet_device.h) and the
// resampling kernel (compute/volume/tet_resample_device.h) on a Vulkan device, chosen by
// --backend as for images. Throws UserError when Vulkan was asked for and no usable device exists.
struct VolumeEngine {
    BackendChoice choice;
    std::shared_ptr<VulkanContext> context;  // the device's, held by `optimize` and `resample` too
    TetOptimizer optimize;                   // empty: the serial generalized Lawson
    TetResampler resample;                   // empty: core's resampleTetsInto
};
VolumeEngine makeVolumeEngine(const Settings& settings);

}  // namespace ddt
