#include "volume_slices.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "image_file.h"

namespace ddt {

namespace {

struct Window {
    float min = 0, max = 0;
    uint8_t level(float value) const {
        if (!(max > min)) return 0;
        return uint8_t(std::lround(std::clamp((double(value) - min) / (double(max) - min), 0.0, 1.0) * 255.0));
    }
};

// One 8-bit grey image, through ddtup's PNG writer.
void writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& levels) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = 1;
    image.sample_type = SampleType::UInt8;
    image.pixels.resize(levels.size());
    for (size_t i = 0; i < levels.size(); ++i) image.pixels[i] = float(levels[i]) / 255.0f;
    writeImage(path, image);
}

}  // namespace

std::vector<std::string> writeMiddleSlices(const Volume& volume, const std::string& folder, const std::string& stem) {
    const auto [lowest, highest] = std::minmax_element(volume.values.begin(), volume.values.end());
    const Window window{volume.values.empty() ? 0.0f : *lowest, volume.values.empty() ? 0.0f : *highest};
    const uint32_t nx = volume.size[0], ny = volume.size[1], nz = volume.size[2];
    const uint32_t mx = nx / 2, my = ny / 2, mz = nz / 2;

    // Each plane: its width, height and the voxel at pixel (column, row).
    struct Plane {
        const char* name;
        uint32_t width, height;
        std::array<uint32_t, 3> (*voxel)(uint32_t column, uint32_t row, const std::array<uint32_t, 3>& middle,
                                         const std::array<uint32_t, 3>& size);
    };
    const Plane planes[3] = {
        {"axial", nx, ny, [](uint32_t c, uint32_t r, const auto& m, const auto&) { return std::array<uint32_t, 3>{c, r, m[2]}; }},
        {"coronal", nx, nz,
         [](uint32_t c, uint32_t r, const auto& m, const auto& n) { return std::array<uint32_t, 3>{c, m[1], n[2] - 1 - r}; }},
        {"sagittal", ny, nz,
         [](uint32_t c, uint32_t r, const auto& m, const auto& n) { return std::array<uint32_t, 3>{m[0], c, n[2] - 1 - r}; }},
    };
    const std::array<uint32_t, 3> middle{mx, my, mz};
    std::vector<std::string> paths;
    for (const Plane& plane : planes) {
        std::vector<uint8_t> pixels(size_t(plane.width) * plane.height);
        for (uint32_t r = 0; r < plane.height; ++r)
            for (uint32_t c = 0; c < plane.width; ++c) {
                const std::array<uint32_t, 3> v = plane.voxel(c, r, middle, volume.size);
                pixels[size_t(r) * plane.width + c] = window.level(volume.at(v[0], v[1], v[2]));
            }
        const std::string path = (std::filesystem::path(folder) / (stem + "-" + plane.name + ".png")).string();
        writePng(path, plane.width, plane.height, pixels);
        paths.push_back(path);
    }
    return paths;
}

}  // namespace ddt
