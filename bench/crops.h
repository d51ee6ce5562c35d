// Side-by-side crops like the paper's Figs. 11 and 12: the same part of the original and of
// each reconstruction, enlarged, for the eye.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"

namespace bench {

// The strips' crops: a 128-pixel square of the original, shown 2×.
constexpr uint32_t kCropSide = 128;
constexpr uint32_t kCropZoom = 2;

struct CropPanel {
    std::string label;
    const ddt::Image* image;  // at the original's size; null: the method is not available
};

struct CropWindow {
    uint32_t x = 0, y = 0, side = 0;
};

// The square of `side` pixels (less for smaller images) where the original has the most
// detail (sum of absolute luma differences to the right and below neighbours).
CropWindow busiestWindow(const ddt::Image& original, uint32_t side);

// Writes the panels' crops side by side as an 8-bit RGB PNG, each enlarged by `zoom` with
// nearest-neighbour so that single pixels stay visible, labelled underneath. Returns false
// if no font could be found for the labels (the PNG is written without them).
bool writeCropStrip(const std::string& path, const std::vector<CropPanel>& panels, CropWindow window, uint32_t zoom);

}  // namespace bench
