#include "handmade_seeds.h"

#include <cmath>
#include <cstring>
#include <functional>

#include "bytes.h"

namespace fuzz {

namespace {

// A sample of the pattern as an integer of `max` levels.
uint32_t level(int x, int y, int channel, int channels, uint32_t max) {
    return uint32_t(std::lround(std::min(1.0f, patternSample(x, y, channel, channels, 1.0f)) * float(max)));
}

// A palette index: stripes and the diagonal edge, so runs and changes both occur.
uint32_t paletteIndex(int x, int y, uint32_t colours) {
    return (uint32_t(x * 2 > y * 3) * colours / 2 + uint32_t(x / 3 + y)) % colours;
}

// ---- PNG

std::string pngChunk(const std::string& type, const std::string& data) {
    return be(4, data.size()) + type + data + be(4, crc32Of(type + data));
}

struct PngLayout {
    int width, height, depth, colour_type;
    bool interlaced;
    std::function<uint32_t(int x, int y, int channel)> sample;
};

int pngChannels(int colour_type) {
    switch (colour_type) {
        case 2: return 3;
        case 4: return 2;
        case 6: return 4;
        default: return 1;
    }
}

uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// Filters `row` against `prior` with `type` (0-4, PNG's five filters).
std::string filterRow(const std::string& row, const std::string& prior, int type, size_t bpp) {
    std::string out(1, char(type));
    for (size_t i = 0; i < row.size(); ++i) {
        const int raw = uint8_t(row[i]), left = i >= bpp ? uint8_t(row[i - bpp]) : 0, up = uint8_t(prior[i]);
        const int upleft = i >= bpp ? uint8_t(prior[i - bpp]) : 0;
        const int predictor = type == 1   ? left
                              : type == 2 ? up
                              : type == 3 ? (left + up) / 2
                              : type == 4 ? paeth(left, up, upleft)
                                          : 0;
        out += char(uint8_t(raw - predictor));
    }
    return out;
}

// The filtered scanlines of the image (of each Adam7 pass when interlaced), every filter type used.
std::string pngScanlines(const PngLayout& png) {
    struct Pass {
        int x0, y0, dx, dy;
    };
    const Pass adam7[] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                          {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
    const Pass whole[] = {{0, 0, 1, 1}};
    const int channels = pngChannels(png.colour_type);
    const size_t bits_per_pixel = size_t(png.depth) * channels;
    const size_t bpp = std::max<size_t>(1, bits_per_pixel / 8);
    std::string out;
    int filter = 0;
    for (const Pass& pass : png.interlaced ? std::vector<Pass>(std::begin(adam7), std::end(adam7))
                                           : std::vector<Pass>(std::begin(whole), std::end(whole))) {
        const int pass_width = (png.width - pass.x0 + pass.dx - 1) / pass.dx;
        if (pass_width <= 0 || pass.y0 >= png.height) continue;
        const size_t row_bytes = (size_t(pass_width) * bits_per_pixel + 7) / 8;
        std::string prior(row_bytes, '\0');
        for (int y = pass.y0; y < png.height; y += pass.dy) {
            std::string row(row_bytes, '\0');
            size_t bit = 0;
            for (int x = pass.x0; x < png.width; x += pass.dx)
                for (int c = 0; c < channels; ++c, bit += png.depth) {
                    const uint32_t value = png.sample(x, y, c);
                    for (int b = png.depth - 1; b >= 0; --b) {
                        const size_t at = bit + size_t(png.depth - 1 - b);
                        if ((value >> b) & 1) row[at / 8] = char(uint8_t(row[at / 8]) | (0x80 >> (at % 8)));
                    }
                }
            out += filterRow(row, prior, filter++ % 5, bpp);
            prior = row;
        }
    }
    return out;
}

std::string pngFile(const PngLayout& png, const std::string& palette_chunks) {
    const std::string header = be(4, png.width) + be(4, png.height) + char(png.depth) + char(png.colour_type) + '\0' +
                               '\0' + char(png.interlaced ? 1 : 0);
    return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", header) + palette_chunks +
           pngChunk("IDAT", zlibCompress(pngScanlines(png))) + pngChunk("IEND", "");
}

// PLTE with `colours` entries along the pattern, and tRNS for the first `transparent` of them.
std::string pngPalette(uint32_t colours, uint32_t transparent) {
    std::string plte, trns;
    for (uint32_t i = 0; i < colours; ++i) {
        for (int c = 0; c < 3; ++c) plte += char(level(int(i), int(i * (c + 1)), c, 3, 255));
        if (i < transparent) trns += char(i * 255 / std::max<uint32_t>(1, transparent));
    }
    return pngChunk("PLTE", plte) + (transparent ? pngChunk("tRNS", trns) : "");
}

// ---- BMP

struct BmpLayout {
    int width, height, bits;
    uint32_t compression = 0;  // 0 none, 1 RLE8, 2 RLE4, 3 bit fields
    bool top_down = false;
    uint32_t header_size = 40;
};

std::string bmpPixelRows(const BmpLayout& bmp, uint32_t colours) {
    std::string out;
    for (int row = 0; row < bmp.height; ++row) {
        const int y = bmp.top_down ? row : bmp.height - 1 - row;
        std::string line;
        if (bmp.bits <= 8) {
            uint32_t accumulator = 0;
            int filled = 0;
            for (int x = 0; x < bmp.width; ++x) {
                accumulator = (accumulator << bmp.bits) | paletteIndex(x, y, colours);
                if ((filled += bmp.bits) == 8) line += char(accumulator), accumulator = 0, filled = 0;
            }
            if (filled) line += char(accumulator << (8 - filled));
        } else if (bmp.bits == 16) {  // 5-6-5
            for (int x = 0; x < bmp.width; ++x)
                line += le(2, level(x, y, 0, 3, 31) << 11 | level(x, y, 1, 3, 63) << 5 | level(x, y, 2, 3, 31));
        } else {
            for (int x = 0; x < bmp.width; ++x)
                for (int c = 2; c >= 0; --c) line += char(level(x, y, c, 3, 255));
        }
        line.resize((line.size() + 3) / 4 * 4, '\0');
        out += line;
    }
    return out;
}

// Runs of equal indices, row by row from the bottom: (count, index) pairs, RLE4 with the index
// in both nibbles; each row but the last ends with 0 0, the bitmap with 0 1 (OIIO 2.4 takes
// an end of line after the last row for a move past the image).
std::string bmpRle(const BmpLayout& bmp, uint32_t colours) {
    std::string out;
    for (int y = bmp.height - 1; y >= 0; --y) {
        for (int x = 0; x < bmp.width;) {
            const uint32_t index = paletteIndex(x, y, colours);
            int run = 1;
            while (x + run < bmp.width && run < 255 && paletteIndex(x + run, y, colours) == index) ++run;
            out += char(run);
            out += char(bmp.compression == 2 ? (index << 4 | index) : index);
            x += run;
        }
        if (y > 0) out += std::string("\0\0", 2);
    }
    return out + std::string("\0\1", 2);
}

std::string bmpFile(const BmpLayout& bmp) {
    const uint32_t colours = bmp.bits <= 8 ? (1u << bmp.bits) : 0;
    std::string palette;
    for (uint32_t i = 0; i < colours; ++i) palette += std::string{char(i * 37), char(i * 91), char(i * 13), '\0'};
    const std::string masks = bmp.compression == 3 ? le(4, 0xF800) + le(4, 0x07E0) + le(4, 0x001F) : "";
    const std::string pixels =
        bmp.compression == 1 || bmp.compression == 2 ? bmpRle(bmp, colours) : bmpPixelRows(bmp, colours);
    std::string header = le(4, bmp.header_size) + le(4, bmp.width) +
                         le(4, uint32_t(bmp.top_down ? -bmp.height : bmp.height)) + le(2, 1) + le(2, bmp.bits) +
                         le(4, bmp.compression) + le(4, pixels.size()) + le(4, 2835) + le(4, 2835) + le(4, colours) +
                         le(4, 0);
    if (bmp.header_size > 40) {
        // V4/V5: the masks inside the header, "sRGB" colour space, the rest zero.
        header += bmp.compression == 3 ? masks : le(4, 0) + le(4, 0) + le(4, 0);
        header += le(4, 0) + "BGRs";
        header.resize(bmp.header_size, '\0');
    } else {
        header += masks;
    }
    const uint32_t offset = 14 + uint32_t(header.size() + palette.size());
    return "BM" + le(4, offset + pixels.size()) + le(4, 0) + le(4, offset) + header + palette + pixels;
}

// ---- Targa

// Packets along each row: a run of 2-128 equal pixels, else raw packets of up to 128.
std::string targaRle(int width, int height, const std::function<std::string(int x, int y)>& pixel) {
    std::string out;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width;) {
            int run = 1;
            while (x + run < width && run < 128 && pixel(x + run, y) == pixel(x, y)) ++run;
            if (run > 1) {
                out += char(0x80 | (run - 1));
                out += pixel(x, y);
                x += run;
                continue;
            }
            int raw = 1;
            while (x + raw < width && raw < 128 && pixel(x + raw, y) != pixel(x + raw - 1, y)) ++raw;
            out += char(raw - 1);
            for (int i = 0; i < raw; ++i) out += pixel(x + i, y);
            x += raw;
        }
    }
    return out;
}

// Colour-mapped (type 1, or 9 with RLE): 8-bit indices into 24-bit entries, top-left origin.
std::string targaColourMapped(int width, int height, bool rle) {
    const uint32_t colours = 32;
    std::string header = std::string{'\0', '\1', char(rle ? 9 : 1)} + le(2, 0) + le(2, colours) + char(24) + le(2, 0) +
                         le(2, 0) + le(2, width) + le(2, height) + char(8) + char(0x20);
    std::string map;
    for (uint32_t i = 0; i < colours; ++i) map += std::string{char(i * 7), char(i * 5), char(255 - i * 3)};
    auto pixel = [&](int x, int y) { return std::string(1, char(paletteIndex(x, y, colours))); };
    std::string pixels;
    if (rle)
        pixels = targaRle(width, height, pixel);
    else
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) pixels += pixel(x, y);
    return header + map + pixels;
}

// True colour in 16 bits (5-5-5 and an attribute bit), bottom-left origin.
std::string targaRgb15(int width, int height) {
    std::string header = std::string{'\0', '\0', '\2'} + le(2, 0) + le(2, 0) + char(0) + le(2, 0) + le(2, 0) +
                         le(2, width) + le(2, height) + char(16) + char(0x01);
    std::string pixels;
    for (int y = height - 1; y >= 0; --y)
        for (int x = 0; x < width; ++x)
            pixels += le(2, 0x8000 | level(x, y, 0, 3, 31) << 10 | level(x, y, 1, 3, 31) << 5 | level(x, y, 2, 3, 31));
    return header + pixels;
}

// ---- PFM

std::string pfmFile(int width, int height, int channels, bool big_endian) {
    std::string out = std::string(channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(width) + " " +
                      std::to_string(height) + "\n" + (big_endian ? "1.0" : "-1.0") + "\n";
    for (int y = height - 1; y >= 0; --y)  // bottom row first
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c) {
                const float value = patternSample(x, y, c, channels, 4.0f);
                uint32_t bits;
                std::memcpy(&bits, &value, 4);
                out += big_endian ? be(4, bits) : le(4, bits);
            }
    return out;
}

}  // namespace

std::vector<Seed> handmadePngSeeds() {
    auto indexed = [](int colours) {
        return [colours](int x, int y, int) { return paletteIndex(x, y, uint32_t(colours)); };
    };
    auto levels = [](int depth, int channels) {
        return [depth, channels](int x, int y, int c) { return level(x, y, c, channels, (1u << depth) - 1); };
    };
    return {{"palette8-trns", ".png", pngFile({16, 12, 8, 3, false, indexed(40)}, pngPalette(40, 20))},
            {"palette4-interlaced", ".png", pngFile({19, 13, 4, 3, true, indexed(16)}, pngPalette(16, 0))},
            {"grey1", ".png", pngFile({21, 9, 1, 0, false, levels(1, 1)}, "")},
            {"grey2-trns", ".png", pngFile({14, 10, 2, 0, false, levels(2, 1)}, pngChunk("tRNS", be(2, 1)))},
            {"rgb8-interlaced", ".png", pngFile({17, 11, 8, 2, true, levels(8, 3)}, "")},
            {"rgba8-interlaced", ".png", pngFile({9, 9, 8, 6, true, levels(8, 4)}, "")}};
}

std::vector<Seed> handmadeBmpSeeds() {
    BmpLayout rgb565{16, 8, 16, 3};
    BmpLayout top_down{11, 7, 24};
    top_down.top_down = true;
    top_down.header_size = 124;
    return {{"palette1", ".bmp", bmpFile({21, 9, 1})},     {"palette4", ".bmp", bmpFile({13, 11, 4})},
            {"rle8", ".bmp", bmpFile({17, 12, 8, 1})},     {"rle4", ".bmp", bmpFile({15, 10, 4, 2})},
            {"rgb565-bitfields", ".bmp", bmpFile(rgb565)}, {"rgb24-top-down-v5", ".bmp", bmpFile(top_down)}};
}

std::vector<Seed> handmadeTargaSeeds() {
    return {{"colour-mapped", ".tga", targaColourMapped(16, 10, false)},
            {"colour-mapped-rle", ".tga", targaColourMapped(20, 12, true)},
            {"rgb15", ".tga", targaRgb15(13, 9)}};
}

std::vector<Seed> handmadePnmSeeds() {
    return {{"pfm-rgb", ".pfm", pfmFile(12, 9, 3, false)},
            {"pfm-grey", ".pfm", pfmFile(10, 10, 1, false)},
            {"pfm-rgb-big-endian", ".pfm", pfmFile(9, 8, 3, true)}};
}

}  // namespace fuzz
