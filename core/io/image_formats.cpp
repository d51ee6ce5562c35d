#include "image_formats.h"

#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

namespace ddt {

namespace {

// Each format's signature: the bytes its files start with (OpenImageIO's readers check the same).
struct Signature {
    const char* oiio_name;
    size_t offset;
    std::string bytes;
};

const Signature kSignatures[] = {
    {"png", 0, std::string("\x89PNG\r\n\x1a\n", 8)},
    {"jpeg", 0, "\xff\xd8\xff"},
    {"tiff", 0, std::string("II*\0", 4)},  // little-endian TIFF
    {"tiff", 0, std::string("MM\0*", 4)},  // big-endian TIFF
    {"tiff", 0, std::string("II+\0", 4)},  // BigTIFF, little-endian
    {"tiff", 0, std::string("MM\0+", 4)},  // BigTIFF, big-endian
    {"openexr", 0, "\x76\x2f\x31\x01"},
    {"webp", 8, "WEBP"},  // after "RIFF" and the file size, checked below
    {"bmp", 0, "BM"},
    {"gif", 0, "GIF87a"},
    {"gif", 0, "GIF89a"},
    {"hdr", 0, "#?RADIANCE"},
    {"hdr", 0, "#?RGBE"},
};

// PNM: "P1" to "P6", or "Pf"/"PF" (PFM), then white space.
bool isPnm(const std::string& head) {
    return head.size() >= 3 && head[0] == 'P' && std::string_view("123456fF").find(head[1]) != std::string_view::npos &&
           std::string_view(" \t\r\n").find(head[2]) != std::string_view::npos;
}

const ImageFormat* formatNamed(const std::string& oiio_name) {
    for (const ImageFormat& format : imageFormats())
        if (oiio_name == format.oiio_name) return &format;
    return nullptr;
}

}  // namespace

const std::vector<ImageFormat>& imageFormats() {
    static const std::vector<ImageFormat> formats = {
        {"png", "PNG", " png"},
        {"jpeg", "JPEG", " jpg jpe jpeg jif jfif jfi"},
        {"tiff", "TIFF", " tif tiff tx env sm vsm"},
        {"openexr", "OpenEXR", " exr sxr mxr"},
        {"webp", "WebP", " webp"},
        {"bmp", "BMP", " bmp dib"},
        {"gif", "GIF", " gif"},
        {"targa", "Targa", " tga tpic"},
        {"pnm", "PNM", " ppm pgm pbm pnm pfm"},
        {"hdr", "Radiance HDR", " hdr rgbe"},
    };
    return formats;
}

std::string imageFormatTitles() {
    std::string titles;
    for (const ImageFormat& format : imageFormats()) titles += (titles.empty() ? "" : ", ") + std::string(format.title);
    return titles;
}

const ImageFormat* formatOfExtension(const std::string& extension) {
    std::string wanted = extension.starts_with(".") ? extension.substr(1) : extension;
    if (wanted.empty()) return nullptr;
    for (char& c : wanted) c = char(std::tolower(uint8_t(c)));
    for (const ImageFormat& format : imageFormats()) {
        std::string_view rest = format.extensions;
        while (!rest.empty()) {
            rest.remove_prefix(1);  // the space before each
            const std::string_view candidate = rest.substr(0, rest.find(' '));
            if (candidate == wanted) return &format;
            rest.remove_prefix(candidate.size());
        }
    }
    return nullptr;
}

const ImageFormat* formatOfContent(const std::string& path, const std::string& name) {
    std::ifstream file(path, std::ios::binary);
    std::string head(16, '\0');
    file.read(head.data(), std::streamsize(head.size()));
    head.resize(size_t(file.gcount()));
    for (const Signature& signature : kSignatures)
        if (head.compare(std::min(signature.offset, head.size()), signature.bytes.size(), signature.bytes) == 0 &&
            (std::strcmp(signature.oiio_name, "webp") != 0 || head.starts_with("RIFF")))
            return formatNamed(signature.oiio_name);
    if (isPnm(head)) return formatNamed("pnm");
    const ImageFormat* by_extension = formatOfExtension(std::filesystem::path(name).extension().string());
    if (by_extension && std::strcmp(by_extension->oiio_name, "targa") == 0) return by_extension;
    return nullptr;
}

}  // namespace ddt
