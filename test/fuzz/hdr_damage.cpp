// Radiance HDR (RGBE): text header lines, a blank line, the resolution line ("-Y H +X W"),
// then scanlines, run-length encoded (2 2 hi lo, then each component's runs) or flat.
#include <algorithm>

#include "bytes.h"
#include "formats.h"
#include "interesting.h"

namespace fuzz {

namespace {

struct Layout {
    size_t header_end = std::string::npos;  // the blank line ending the header
    size_t resolution = std::string::npos;  // the resolution line
    size_t data = std::string::npos;        // the first scanline
};

Layout layoutOf(const std::string& file) {
    Layout layout;
    layout.header_end = file.find("\n\n");
    if (layout.header_end == std::string::npos) return layout;
    layout.resolution = layout.header_end + 2;
    const size_t end = file.find('\n', layout.resolution);
    if (end != std::string::npos) layout.data = end + 1;
    return layout;
}

// The resolution line's four words: sign+axis, number, sign+axis, number.
std::vector<std::pair<size_t, size_t>> resolutionWords(const std::string& file, const Layout& layout) {
    std::vector<std::pair<size_t, size_t>> words;
    if (layout.data == std::string::npos) return words;
    for (size_t at = layout.resolution; at < layout.data - 1;) {
        while (at < layout.data - 1 && file[at] == ' ') ++at;
        const size_t begin = at;
        while (at < layout.data - 1 && file[at] != ' ') ++at;
        if (at > begin) words.push_back({begin, at - begin});
    }
    return words;
}

std::string damageSize(std::string& file, Random& random) {
    const Layout layout = layoutOf(file);
    const auto words = resolutionWords(file, layout);
    if (words.size() != 4) return "no resolution line";
    const auto [at, length] = words[random.percent(50) ? 1 : 3];
    const std::string old = file.substr(at, length);
    const std::string text = badNumberText(random, std::strtoull(old.c_str(), nullptr, 10));
    file.replace(at, length, text);
    return "resolution " + old + " -> '" + text.substr(0, 24) + "'";
}

std::string damagePixelFormat(std::string& file, Random& random) {
    const Layout layout = layoutOf(file);
    if (layout.data == std::string::npos) return "no resolution line";
    if (random.percent(40)) {
        const char* lines[] = {"-Y 8 -X 8", "+Y 8 +X 8", "+X 8 -Y 8", "-X 8 +Y 8", "-Y 8 +Y 8",
                               "Y 8 X 8",   "-Y8+X8",    "-Y 8",      ""};
        const std::string line = lines[random.below(std::size(lines))];
        file.replace(layout.resolution, layout.data - 1 - layout.resolution, line);
        return "resolution line -> '" + line + "'";
    }
    // Header lines: another format, exposure and gamma values that divide or overflow.
    const char* lines[] = {"FORMAT=32-bit_rle_xyze",
                           "FORMAT=",
                           "FORMAT=16-bit_rle_rgbe",
                           "EXPOSURE=0",
                           "EXPOSURE=-1",
                           "EXPOSURE=nan",
                           "EXPOSURE=1e40",
                           "GAMMA=0",
                           "GAMMA=-2.2",
                           "PRIMARIES=0 0 0 0 0 0 0 0",
                           "FORMAT=32-bit_rle_rgbe"};
    const std::string line = lines[random.below(std::size(lines))];
    const size_t format = file.find("FORMAT=");
    if (format != std::string::npos && format < layout.header_end && random.percent(50)) {
        file.replace(format, file.find('\n', format) - format, line);
        return "FORMAT line -> '" + line + "'";
    }
    file.insert(layout.header_end + 1, line + "\n");
    return "header line '" + line + "' added";
}

std::string damageStructure(std::string& file, Random& random) {
    const Layout layout = layoutOf(file);
    switch (random.below(5)) {
        case 0: {
            const char* signatures[] = {"#?RGBE\n", "#?\n", "#?RADIANCE", "#?RADIANCE\r\n", "#!RADIANCE\n"};
            const size_t end = file.find('\n');
            const std::string signature = signatures[random.below(std::size(signatures))];
            file.replace(0, end == std::string::npos ? 0 : end + 1, signature);
            return "signature line -> " + std::to_string(signature.size()) + " bytes";
        }
        case 1: {
            const size_t length = random.percent(50) ? 200000 : random.between(120, 600);
            file.insert(file.find('\n') + 1, "SOFTWARE=" + std::string(length, 'x') + (random.percent(50) ? "\n" : ""));
            return "header line of " + std::to_string(length) + " characters";
        }
        case 2:
            if (layout.header_end == std::string::npos) return "no blank line";
            file.erase(layout.header_end, 1);
            return "blank line after the header removed";
        case 3:
            if (layout.data == std::string::npos) return "no resolution line";
            file.erase(layout.resolution, layout.data - layout.resolution);
            return "resolution line removed";
        default: {
            if (layout.data == std::string::npos) return "no resolution line";
            file.replace(layout.data - 1, 1, random.percent(50) ? "\r\n" : " ");
            return "resolution line ending changed";
        }
    }
}

std::string damageStream(std::string& file, Random& random) {
    const Layout layout = layoutOf(file);
    if (layout.data == std::string::npos || layout.data + 4 >= file.size()) return "no scanlines";
    const size_t at = layout.data + random.below(file.size() - layout.data);
    switch (random.below(4)) {
        case 0: {
            // A scanline header: 2 2 and the width, which may disagree with the resolution.
            const size_t header = layout.data + (random.percent(50) ? 0 : (at - layout.data) / 4 * 4);
            const std::string headers[] = {
                std::string("\2\2\0\0", 4),   std::string("\2\2\xFF\xFF", 4),
                std::string("\2\2\x80\0", 4), std::string("\2\2\0\x07", 4),
                std::string("\1\1\1\xFF", 4), std::string("\2\2\0", 3) + char(random.byte())};
            file.replace(header, 4, headers[random.below(std::size(headers))]);
            return "scanline header at " + std::to_string(header) + " replaced";
        }
        case 1: {
            // A run count: runs (over 128) longer than the scanline, or empty.
            const uint8_t counts[] = {0, 128, 129, 255, 127};
            file[at] = char(counts[random.below(std::size(counts))]);
            return "run count at " + std::to_string(at) + " -> " + std::to_string(uint8_t(file[at]));
        }
        case 2: file.resize(at); return "scanlines cut at " + std::to_string(at);
        default: {
            const size_t count = std::min<size_t>(file.size() - at, random.between(1, 16));
            file.replace(at, count, random.bytes(count));
            return std::to_string(count) + " random scanline bytes at " + std::to_string(at);
        }
    }
}

}  // namespace

std::string damageHdr(std::string& file, DamageKind kind, Random& random) {
    switch (kind) {
        case DamageKind::Size: return damageSize(file, random);
        case DamageKind::PixelFormat: return damagePixelFormat(file, random);
        case DamageKind::Structure: return damageStructure(file, random);
        default: return damageStream(file, random);
    }
}

}  // namespace fuzz
