#include "vips_nohalo.h"

#include <vips/vips.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bench {

namespace {

void initialiseVips() {
    static const bool ok = vips_init("ddtup-bench") == 0;
    if (!ok) throw std::runtime_error(std::string("libvips: cannot initialise: ") + vips_error_buffer());
}

std::runtime_error vipsError(const char* what) {
    std::string message = std::string("libvips ") + what + ": " + vips_error_buffer();
    vips_error_clear();
    return std::runtime_error(message);
}

// A ramp of slope 1 per input pixel along x (or y), so a value is the coordinate it samples.
ddt::Image ramp(uint32_t side, bool along_x) {
    ddt::Image image;
    image.width = image.height = side;
    image.channels = 1;
    image.pixels.resize(size_t(side) * side);
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) image.pixels[size_t(y) * side + x] = float(along_x ? x : y);
    return image;
}

}  // namespace

ddt::Image magnifyWithNohalo(const ddt::Image& input, uint32_t width, uint32_t height) {
    initialiseVips();
    const double sx = double(width) / input.width, sy = double(height) / input.height;
    VipsImage* in = vips_image_new_from_memory(input.pixels.data(), input.pixels.size() * sizeof(float),
                                               int(input.width), int(input.height), int(input.channels),
                                               VIPS_FORMAT_FLOAT);
    if (!in) throw vipsError("cannot wrap the input");
    VipsInterpolate* nohalo = vips_interpolate_new("nohalo");
    VipsArrayInt* area = vips_array_int_newv(4, 0, 0, int(width), int(height));
    VipsImage* out = nullptr;
    const int failed = vips_affine(in, &out, sx, 0.0, 0.0, sy, "interpolate", nohalo, "oarea", area, "idx",
                                   0.5 - 0.5 / sx, "idy", 0.5 - 0.5 / sy, "extend", VIPS_EXTEND_COPY, nullptr);
    size_t bytes = 0;
    float* pixels = failed ? nullptr : static_cast<float*>(vips_image_write_to_memory(out, &bytes));
    vips_area_unref(VIPS_AREA(area));
    g_object_unref(nohalo);
    g_object_unref(in);
    if (out) g_object_unref(out);
    if (!pixels) throw vipsError("nohalo affine");

    ddt::Image result;
    result.width = width;
    result.height = height;
    result.channels = input.channels;
    result.sample_type = input.sample_type;
    result.pixels.assign(pixels, pixels + bytes / sizeof(float));
    g_free(pixels);
    if (result.pixels.size() != size_t(width) * height * input.channels)
        throw std::runtime_error("libvips nohalo: unexpected output size");
    return result;
}

double nohaloMisalignment() {
    const uint32_t side = 32, margin = 4;  // input pixels kept away from the clamped borders
    double worst = 0.0;
    for (double scale : {2.0, 2.5, 4.0})
        for (bool along_x : {true, false}) {
            const uint32_t out_side = uint32_t(side * scale);
            const ddt::Image out = magnifyWithNohalo(ramp(side, along_x), out_side, out_side);
            for (uint32_t y = 0; y < out_side; ++y)
                for (uint32_t x = 0; x < out_side; ++x) {
                    const double expected = ((along_x ? x : y) + 0.5) / scale - 0.5;
                    if (expected < margin || expected > side - 1 - margin) continue;
                    worst = std::max(worst, std::fabs(out.pixels[size_t(y) * out_side + x] - expected));
                }
        }
    return worst;
}

}  // namespace bench
