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

}  // namespace bench
