#include "seeds.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>

#include "handmade_seeds.h"

namespace fuzz {

namespace {

using OIIO::TypeDesc;

// One file OpenImageIO writes: its size, layout and the writer's settings.
struct Variant {
    std::string name;
    std::string extension;
    int width, height, channels;
    TypeDesc type;
    std::function<void(OIIO::ImageSpec&)> configure = [](OIIO::ImageSpec&) {};
    int tile = 0;       // tile side, 0 for scanlines
    int subimages = 1;  // pages or frames
};

auto compression(const std::string& name) {
    return [name](OIIO::ImageSpec& spec) { spec.attribute("compression", name); };
}

// EXIF and an ICC profile, so that the readers' metadata parsers get damaged input too.
void metadata(OIIO::ImageSpec& spec) {
    spec.attribute("Make", "ddtup fuzz");
    spec.attribute("Exif:DateTimeOriginal", "2024:01:02 03:04:05");
    spec.attribute("Exif:ExposureTime", 0.01f);
    spec.attribute("XResolution", 72.0f);
    spec.attribute("YResolution", 72.0f);
    spec.attribute("ResolutionUnit", "in");
    // An ICC profile without tags: the header libpng checks (size, signature, classes, D50).
    std::string icc(132, '\0');
    icc[3] = char(132);
    icc.replace(8, 4, std::string("\x02\x10\0\0", 4));
    icc.replace(12, 12, "mntrRGB XYZ ");
    icc.replace(36, 4, "acsp");
    icc.replace(68, 12, std::string("\0\0\xF6\xD6\0\1\0\0\0\0\xD3\x2D", 12));
    spec.attribute("ICCProfile", OIIO::TypeDesc(OIIO::TypeDesc::UINT8, int(icc.size())), icc.data());
}

const TypeDesc kU8 = TypeDesc::UINT8, kU16 = TypeDesc::UINT16, kHalf = TypeDesc::HALF, kFloat = TypeDesc::FLOAT;

std::vector<Variant> variantsOf(const std::string& format) {
    if (format == "png")
        return {{"grey8", ".png", 17, 11, 1, kU8},
                {"grey-alpha8", ".png", 12, 12, 2, kU8},
                {"rgb8-metadata", ".png", 19, 13, 3, kU8, metadata},
                {"rgba16", ".png", 16, 9, 4, kU16},
                {"rgb16", ".png", 10, 21, 3, kU16}};
    if (format == "jpeg")
        return {{"grey", ".jpg", 17, 11, 1, kU8},
                {"rgb-420", ".jpg", 24, 16, 3, kU8},
                {"rgb-444", ".jpg", 19, 13, 3, kU8, [](auto& s) { s.attribute("jpeg:subsampling", "4:4:4"); }},
                {"rgb-422", ".jpg", 32, 8, 3, kU8, [](auto& s) { s.attribute("jpeg:subsampling", "4:2:2"); }},
                {"rgb-progressive", ".jpg", 33, 17, 3, kU8, [](auto& s) { s.attribute("jpeg:progressive", 1); }},
                {"grey-progressive", ".jpg", 16, 16, 1, kU8, [](auto& s) { s.attribute("jpeg:progressive", 1); }},
                {"rgb-metadata", ".jpg", 20, 20, 3, kU8, metadata}};
    if (format == "tiff")
        return {{"rgb8-none", ".tif", 19, 13, 3, kU8, compression("none")},
                {"rgb8-lzw-strips", ".tif", 16, 24, 3, kU8,
                 [](auto& s) { s.attribute("compression", "lzw"), s.attribute("tiff:RowsPerStrip", 5); }},
                {"grey16-zip", ".tif", 12, 10, 1, kU16, compression("zip")},
                {"rgba8-packbits", ".tif", 14, 14, 4, kU8, compression("packbits")},
                {"rgb-float-zip", ".tif", 9, 9, 3, kFloat, compression("zip")},
                {"grey8-tiled-lzw", ".tif", 40, 24, 1, kU8, compression("lzw"), 16},
                {"rgb16-tiled-none", ".tif", 20, 20, 3, kU16, compression("none"), 16},
                {"rgb8-planar-lzw", ".tif", 13, 11, 3, kU8,
                 [](auto& s) { s.attribute("compression", "lzw"), s.attribute("tiff:planarconfig", "separate"); }},
                {"rgb8-jpeg", ".tif", 24, 16, 3, kU8, compression("jpeg")},
                {"rgb8-metadata", ".tif", 10, 10, 3, kU8, metadata},
                {"rgb8-two-pages", ".tif", 10, 8, 3, kU8, compression("lzw"), 0, 2},
                {"rgb8-bigtiff-lzw", ".tif", 14, 12, 3, kU8,
                 [](auto& s) { s.attribute("compression", "lzw"), s.attribute("tiff:bigtiff", 1); }}};
    if (format == "openexr")
        return {{"rgb-half-none", ".exr", 13, 11, 3, kHalf, compression("none")},
                {"rgb-half-zip", ".exr", 24, 40, 3, kHalf, compression("zip")},
                {"rgba-half-piz", ".exr", 17, 9, 4, kHalf, compression("piz")},
                {"grey-float-rle", ".exr", 12, 12, 1, kFloat, compression("rle")},
                {"rgb-half-zips", ".exr", 10, 8, 3, kHalf, compression("zips")},
                {"rgb-float-pxr24", ".exr", 9, 14, 3, kFloat, compression("pxr24")},
                {"rgb-half-b44", ".exr", 16, 16, 3, kHalf, compression("b44")},
                {"rgb-half-dwaa", ".exr", 20, 36, 3, kHalf, compression("dwaa")},
                {"rgba-half-tiled-zip", ".exr", 40, 20, 4, kHalf, compression("zip"), 16},
                {"grey-half-tiled-none", ".exr", 18, 18, 1, kHalf, compression("none"), 8}};
    if (format == "webp")
        return {{"rgb-lossy", ".webp", 24, 16, 3, kU8},
                {"rgba-lossy", ".webp", 19, 13, 4, kU8},
                {"rgb-lossless", ".webp", 16, 16, 3, kU8, compression("lossless")},
                {"rgba-lossless", ".webp", 13, 21, 4, kU8, compression("lossless")}};
    if (format == "bmp")
        return {{"rgb24", ".bmp", 19, 13, 3, kU8},
                {"rgba32", ".bmp", 12, 10, 4, kU8},
                {"grey8-palette", ".bmp", 17, 9, 1, kU8}};
    if (format == "gif")
        return {{"rgb", ".gif", 19, 13, 3, kU8},
                {"rgba", ".gif", 16, 16, 4, kU8},
                {"rgb-interlaced", ".gif", 20, 12, 3, kU8, [](auto& s) { s.attribute("gif:Interlacing", 1); }},
                {"rgb-two-frames", ".gif", 10, 10, 3, kU8, [](auto&) {}, 0, 2}};
    if (format == "targa")
        return {{"rgb", ".tga", 19, 13, 3, kU8, compression("none")},
                {"rgba", ".tga", 12, 16, 4, kU8, compression("none")},
                {"grey", ".tga", 9, 9, 1, kU8, compression("none")},
                {"grey-rle", ".tga", 14, 9, 1, kU8, compression("rle")},
                {"rgb-rle", ".tga", 24, 10, 3, kU8, compression("rle")},
                {"rgba-rle", ".tga", 16, 12, 4, kU8, compression("rle")}};
    if (format == "pnm")
        return {{"p5-grey8", ".pgm", 17, 11, 1, kU8},
                {"p6-rgb8", ".ppm", 13, 9, 3, kU8},
                {"p6-rgb16", ".ppm", 10, 10, 3, kU16},
                {"p2-grey-ascii", ".pgm", 9, 8, 1, kU8, [](auto& s) { s.attribute("pnm:binary", 0); }},
                {"p3-rgb-ascii", ".ppm", 8, 10, 3, kU8, [](auto& s) { s.attribute("pnm:binary", 0); }},
                {"p4-bitmap", ".pbm", 21, 9, 1, kU8, [](auto& s) { s.attribute("oiio:BitsPerSample", 1); }},
                {"p1-bitmap-ascii", ".pbm", 10, 10, 1, kU8,
                 [](auto& s) { s.attribute("oiio:BitsPerSample", 1), s.attribute("pnm:binary", 0); }}};
    if (format == "hdr")
        // The writer run-length encodes scanlines 8 to 32767 wide and writes narrower ones flat.
        return {{"rgb-rle", ".hdr", 19, 13, 3, kFloat},
                {"rgb-flat", ".hdr", 6, 11, 3, kFloat},
                {"rgb-rle-wide", ".hdr", 40, 8, 3, kFloat}};
    throw std::logic_error("no seeds for format " + format);
}

std::vector<std::string> channelNames(int channels) {
    switch (channels) {
        case 1: return {"Y"};
        case 2: return {"Y", "A"};
        case 3: return {"R", "G", "B"};
        default: return {"R", "G", "B", "A"};
    }
}

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string writeWithOiio(const Variant& v, const std::string& folder) {
    const std::string path = folder + "/seed-" + v.name + v.extension;
    auto fail = [&](const std::string& why) { return std::runtime_error("writing seed " + path + ": " + why); };
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path);
    if (!output) throw fail(OIIO::geterror());
    OIIO::ImageSpec spec(v.width, v.height, v.channels, v.type);
    spec.channelnames = channelNames(v.channels);
    spec.alpha_channel = v.channels % 2 == 0 ? v.channels - 1 : -1;
    if (v.tile) spec.tile_width = spec.tile_height = v.tile;
    v.configure(spec);
    const bool is_float = v.type == kHalf || v.type == kFloat;
    std::vector<float> pixels(size_t(v.width) * v.height * v.channels);
    const std::vector<OIIO::ImageSpec> specs(size_t(v.subimages), spec);
    if (!output->open(path, v.subimages, specs.data())) throw fail(output->geterror());
    for (int s = 0; s < v.subimages; ++s) {
        if (s > 0 && !output->open(path, spec, OIIO::ImageOutput::AppendSubimage)) throw fail(output->geterror());
        for (int y = 0; y < v.height; ++y)
            for (int x = 0; x < v.width; ++x)
                for (int c = 0; c < v.channels; ++c)
                    pixels[(size_t(y) * v.width + x) * v.channels + c] =
                        patternSample(x + s * 3, y, c, v.channels, is_float ? 4.0f : 1.0f);
        if (!output->write_image(TypeDesc::FLOAT, pixels.data())) throw fail(output->geterror());
    }
    if (!output->close()) throw fail(output->geterror());
    return readAll(path);
}

}  // namespace

float patternSample(int x, int y, int channel, int channels, float range) {
    const bool alpha = channels % 2 == 0 && channel == channels - 1;
    if (alpha) return x == 0 ? 0.0f : std::min(1.0f, float(x + y) / 16.0f);
    const float edge = x * 2 > y * 3 ? 0.8f : 0.15f;
    const float stripes = float((x / 3 + channel) % 3) * 0.05f;
    const float noise = float((x * 73 + y * 151 + channel * 29) % 13) / 130.0f;
    return range * (edge + stripes + noise);
}

std::vector<Seed> makeSeeds(const std::string& format, const std::string& folder) {
    std::vector<Seed> seeds;
    for (const Variant& variant : variantsOf(format))
        seeds.push_back({variant.name, variant.extension, writeWithOiio(variant, folder)});
    std::vector<Seed> handmade = format == "png"     ? handmadePngSeeds()
                                 : format == "bmp"   ? handmadeBmpSeeds()
                                 : format == "targa" ? handmadeTargaSeeds()
                                 : format == "pnm"   ? handmadePnmSeeds()
                                                     : std::vector<Seed>();
    seeds.insert(seeds.end(), handmade.begin(), handmade.end());
    return seeds;
}

}  // namespace fuzz
