// A DDT backend runs the three stages the paper times: prepare (build the initial mesh,
// upload), optimize, render. The serial CPU reference and the Vulkan backend implement it
// with the same step names.
#pragma once

#include <memory>
#include <string>

#include "cost.h"
#include "image.h"
#include "lawson.h"
#include "mesh.h"
#include "render.h"

namespace ddt {

class Backend {
public:
    virtual ~Backend() = default;
    // Builds the initial triangulation of `image` (which must outlive the backend's use).
    virtual void prepare(const Image& image) = 0;
    virtual OptimizeStats optimize() = 0;
    // Renders output rows [y_begin, y_end) at `out` (out.width × channels floats per row).
    virtual void renderRows(OutputSize out, uint32_t y_begin, uint32_t y_end, float* rows) = 0;
    // The current mesh (for tests and checks).
    virtual Mesh mesh() = 0;
};

std::unique_ptr<Backend> makeCpuBackend();

}  // namespace ddt
