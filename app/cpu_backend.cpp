// The serial reference backend: core's mesh, Lawson sweeps and rasteriser on the host.
#include <optional>

#include "backend.h"

namespace ddt {

namespace {

class CpuBackend final : public Backend {
public:
    void prepare(const Image& image) override {
        image_ = &image;
        field_ = costFieldOf(image);
        mesh_ = buildGridMesh(image.width, image.height);
        renderer_.reset();
    }

    OptimizeStats optimize() override {
        renderer_.reset();
        return optimizeSerial(mesh_, field_);
    }

    void renderRows(OutputSize out, uint32_t y_begin, uint32_t y_end, float* rows) override {
        if (!renderer_ || renderer_size_.width != out.width || renderer_size_.height != out.height) {
            renderer_.emplace(mesh_, *image_, out);
            renderer_size_ = out;
        }
        renderer_->renderRows(y_begin, y_end, rows);
    }

    Mesh mesh() override { return mesh_; }

private:
    const Image* image_ = nullptr;
    CostField field_;
    Mesh mesh_;
    std::optional<MeshRenderer> renderer_;
    OutputSize renderer_size_;
};

}  // namespace

std::unique_ptr<Backend> makeCpuBackend() { return std::make_unique<CpuBackend>(); }

}  // namespace ddt
