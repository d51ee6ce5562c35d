#include "crops.h"
#include "image_file.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>

namespace bench {

namespace {

const uint32_t kGap = 8;           // white between panels
const uint32_t kLabelHeight = 30;  // white band under the panels for the labels
const int kFontSize = 16;
const char* const kFont = "DejaVuSans";  // Debian's fonts-dejavu-core; OIIO searches /usr/share/fonts
const float kMissingGrey = 0.8f;

float lumaAt(const ddt::Image& image, uint32_t x, uint32_t y) {
    const float* p = image.row(y) + size_t(x) * image.channels;
    return image.channels >= 3 ? 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2] : p[0];
}

float byteValue(float v) { return float(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)) / 255.0f; }

}  // namespace

CropWindow busiestWindow(const ddt::Image& original, uint32_t side) {
    side = std::min({side, original.width, original.height});
    const uint32_t w = original.width, h = original.height;
    // Summed-area table of the detail measure, so each candidate window costs four lookups.
    std::vector<double> table(size_t(w + 1) * (h + 1), 0.0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float here = lumaAt(original, x, y);
            double detail = 0.0;
            if (x + 1 < w) detail += std::fabs(lumaAt(original, x + 1, y) - here);
            if (y + 1 < h) detail += std::fabs(lumaAt(original, x, y + 1) - here);
            table[size_t(y + 1) * (w + 1) + x + 1] = detail + table[size_t(y) * (w + 1) + x + 1] +
                                                     table[size_t(y + 1) * (w + 1) + x] -
                                                     table[size_t(y) * (w + 1) + x];
        }
    auto sum = [&](uint32_t x, uint32_t y) {
        return table[size_t(y + side) * (w + 1) + x + side] - table[size_t(y) * (w + 1) + x + side] -
               table[size_t(y + side) * (w + 1) + x] + table[size_t(y) * (w + 1) + x];
    };
    CropWindow best{0, 0, side};
    double best_sum = -1.0;
    const uint32_t step = std::max(1u, side / 8);
    for (uint32_t y = 0; y + side <= h; y += step)
        for (uint32_t x = 0; x + side <= w; x += step)
            if (double s = sum(x, y); s > best_sum) best_sum = s, best = {x, y, side};
    return best;
}

bool writeCropStrip(const std::string& path, const std::vector<CropPanel>& panels, CropWindow window, uint32_t zoom) {
    const uint32_t tile = window.side * zoom;
    ddt::Image strip;
    strip.width = uint32_t(panels.size()) * (tile + kGap) - kGap;
    strip.height = tile + kLabelHeight;
    strip.channels = 3;
    strip.pixels.assign(size_t(strip.width) * strip.height * 3, 1.0f);
    for (size_t i = 0; i < panels.size(); ++i) {
        const ddt::Image* image = panels[i].image;
        const uint32_t left = uint32_t(i) * (tile + kGap);
        for (uint32_t y = 0; y < tile; ++y)
            for (uint32_t x = 0; x < tile; ++x) {
                float* out = strip.row(y) + size_t(left + x) * 3;
                if (!image) {
                    std::fill(out, out + 3, kMissingGrey);
                    continue;
                }
                const float* in = image->row(window.y + y / zoom) + size_t(window.x + x / zoom) * image->channels;
                for (uint32_t c = 0; c < 3; ++c) out[c] = byteValue(in[image->channels >= 3 ? c : 0]);
            }
    }
    OIIO::ImageBuf canvas(OIIO::ImageSpec(int(strip.width), int(strip.height), 3, OIIO::TypeDesc::FLOAT),
                          strip.pixels.data());
    const float black[3] = {0.0f, 0.0f, 0.0f};
    bool labelled = true;
    for (size_t i = 0; i < panels.size() && labelled; ++i) {
        const int centre = int(i * (tile + kGap) + tile / 2);
        const std::string label = panels[i].image ? panels[i].label : panels[i].label + " (n/a)";
        labelled = OIIO::ImageBufAlgo::render_text(canvas, centre, int(tile + kLabelHeight - 9), label, kFontSize,
                                                   kFont, black, OIIO::ImageBufAlgo::TextAlignX::Center);
    }
    // Clear OIIO's pending error; the caller reports the missing font, once.
    if (!labelled) (void)canvas.geterror();
    ddt::writeImage(path, strip);
    return labelled;
}

}  // namespace bench
