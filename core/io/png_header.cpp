#include "png_header.h"

#include <png.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <strings.h>

#include "icc_attributes.h"
#include "user_error.h"

namespace ddt {

namespace {

// libpng's first error, kept for the message; warnings are dropped, as OpenImageIO does.
struct Errors {
    char message[256] = "";
};

// Jumps back itself: libpng's default handler, which a handler that returns falls through
// to, would print the message.
[[noreturn]] void keepError(png_structp png, png_const_charp text) {
    auto* errors = static_cast<Errors*>(png_get_error_ptr(png));
    if (!errors->message[0] && text) std::snprintf(errors->message, sizeof errors->message, "%s", text);
    png_longjmp(png, 1);
}

void dropWarning(png_structp, png_const_charp) {}

// Frees libpng's structures and closes the file on every way out.
struct Reader {
    std::FILE* file = nullptr;
    png_structp png = nullptr;
    png_infop info = nullptr;
    Errors errors;
    ~Reader() {
        if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
        if (file) std::fclose(file);
    }
};

// The chunks up to the image data, with OpenImageIO's transformations set (palettes to RGB,
// low depths to 8 bits, tRNS to alpha, 16 bits in host order). Nothing here has a destructor:
// libpng's errors longjmp back.
bool readInfo(png_structp png, png_infop info) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_info(png, info);
    png_set_expand(png);
    png_set_swap(png);  // for little-endian hosts, as OpenImageIO asks there
    png_read_update_info(png, info);
    return true;
}

int hexValue(char c) { return c <= '9' ? c - '0' : std::tolower(c) - 'a' + 10; }

// ImageMagick's way of putting EXIF in PNG, a "Raw profile type exif" text: "exif", the byte
// count, then the bytes in hex. OpenImageIO decodes it only when it starts "Exif".
void decodeTextExif(std::string_view raw, ImageAttributes& attributes, const DecodeExif& decode_exif) {
    while (!raw.empty() && std::isspace(uint8_t(raw.front()))) raw.remove_prefix(1);
    if (raw.substr(0, 4) != "exif") return;
    raw.remove_prefix(4);
    const std::string rest(raw);
    char* end = nullptr;
    const long count = std::strtol(rest.c_str(), &end, 10);
    if (end == rest.c_str() || count == 0) return;
    raw.remove_prefix(size_t(end - rest.c_str()));
    std::string bytes;
    while (raw.size() >= 2) {
        if (!std::isxdigit(uint8_t(raw.front()))) {
            raw.remove_prefix(1);
            continue;
        }
        bytes += char(hexValue(raw[0]) << 4 | hexValue(raw[1]));
        raw.remove_prefix(2);
    }
    if (bytes.size() >= 4 && strncasecmp(bytes.c_str(), "exif", 4) == 0)
        decode_exif(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), attributes);
}

// gAMA as OpenImageIO reports it: 1/gamma rounded to hundredths.
void addColourSpace(png_structp png, png_infop info, ImageAttributes& attributes) {
    int intent = 0;
    double gamma = 0.0;
    if (png_get_sRGB(png, info, &intent)) {
        attributes.set("oiio:ColorSpace", std::string("sRGB"));
    } else if (png_get_gAMA(png, info, &gamma) && gamma > 0.0) {
        const float g = std::round(100.0f * float(1.0 / gamma)) / 100.0f;
        attributes.set("oiio:Gamma", g);
        char name[32];
        std::snprintf(name, sizeof name, "Gamma%.2g", double(g));
        attributes.set("oiio:ColorSpace", g == 1.0f ? std::string("linear") : std::string(name));
    } else {
        attributes.set("oiio:ColorSpace", std::string("sRGB"));  // no colour information: sRGB assumed
    }
}

void addProfile(png_structp png, png_infop info, ImageAttributes& attributes) {
    if (!png_get_valid(png, info, PNG_INFO_iCCP)) return;
    png_charp profile_name = nullptr;
    png_bytep data = nullptr;
    png_uint_32 length = 0;
    int compression = 0;
    png_get_iCCP(png, info, &profile_name, &compression, &data, &length);
    if (!length || !data) return;
    std::vector<uint8_t> profile(data, data + length);
    ImageAttribute attribute{"ICCProfile", {AttributeType::Base::UInt8, 1, AttributeType::Meaning::None, length}, profile, {}};
    attributes.set(std::move(attribute));
    addIccAttributes(profile, attributes);
}

// Text chunks in the file's order; OpenImageIO renames three keys to its own names.
// Returns false for XMP.
bool addTexts(png_structp png, png_infop info, ImageAttributes& attributes, const DecodeExif& decode_exif) {
    png_textp texts = nullptr;
    const int count = png_get_text(png, info, &texts, nullptr);
    for (int i = 0; i < count; ++i) {
        const char* key = texts[i].key;
        const std::string text = texts[i].text ? texts[i].text : "";
        if (strcasecmp(key, "Description") == 0) attributes.set("ImageDescription", text);
        else if (strcasecmp(key, "Author") == 0) attributes.set("Artist", text);
        else if (strcasecmp(key, "Title") == 0) attributes.set("DocumentName", text);
        else if (strcasecmp(key, "XML:com.adobe.xmp") == 0) return false;
        else if (strcasecmp(key, "Raw profile type exif") == 0) decodeTextExif(text, attributes, decode_exif);
        else attributes.set(key, text);
    }
    return true;
}

// pHYs in pixels per inch when the unit is the metre, as OpenImageIO converts.
void addResolution(png_structp png, png_infop info, ImageAttributes& attributes) {
    png_uint_32 x = 0, y = 0;
    int unit = 0;
    if (png_get_pHYs(png, info, &x, &y, &unit)) {
        float scale = 1.0f;
        if (unit == PNG_RESOLUTION_METER) {
            scale = float(2.54 / 100.0);
            attributes.set("ResolutionUnit", std::string("inch"));
        } else {
            attributes.set("ResolutionUnit", std::string("none"));
        }
        attributes.set("XResolution", float(x) * scale);
        attributes.set("YResolution", float(y) * scale);
    }
    const float aspect = png_get_pixel_aspect_ratio(png, info);
    if (aspect != 0.0f && aspect != 1.0f) attributes.set("PixelAspectRatio", aspect);
}

}  // namespace

std::optional<PngHeader> readPngHeader(const std::string& path, const std::string& name, const DecodeExif& decode_exif) {
    Reader r;
    r.file = std::fopen(path.c_str(), "rb");
    if (!r.file) throw UserError(name + ": cannot open (" + std::strerror(errno) + ")");
    r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r.errors, keepError, dropWarning);
    if (!r.png) throw std::bad_alloc();
    r.info = png_create_info_struct(r.png);
    if (!r.info) throw std::bad_alloc();
    png_init_io(r.png, r.file);
    if (!readInfo(r.png, r.info)) {
        const std::string reason = r.errors.message[0] ? std::string("PNG read error: ") + r.errors.message : "Could not read info from file";
        throw UserError(name + ": not a readable PNG image (" + reason + ")");
    }
    PngHeader header;
    int bit_depth = 0, colour_type = 0;
    png_get_IHDR(r.png, r.info, &header.width, &header.height, &bit_depth, &colour_type, nullptr, nullptr, nullptr);
    header.channels = png_get_channels(r.png, r.info);
    header.bits = bit_depth == 16 ? 16 : 8;

    ImageAttributes& attributes = header.attributes;
    addColourSpace(r.png, r.info, attributes);
    addProfile(r.png, r.info, attributes);
    png_timep time = nullptr;
    if (png_get_tIME(r.png, r.info, &time)) {
        char date[64];
        std::snprintf(date, sizeof date, "%4d:%02d:%02d %02d:%02d:%02d", time->year, time->month, time->day, time->hour,
                      time->minute, time->second);
        attributes.set("DateTime", std::string(date));
    }
    if (!addTexts(r.png, r.info, attributes, decode_exif)) return std::nullopt;
    addResolution(r.png, r.info, attributes);
    png_uint_32 exif_size = 0;
    png_bytep exif = nullptr;
    if (png_get_eXIf_1(r.png, r.info, &exif_size, &exif)) decode_exif(exif, exif_size, attributes);
    // ddtup asks every reader for straight alpha as stored (image_reader.cpp).
    attributes.set("oiio:UnassociatedAlpha", int32_t(1));
    return header;
}

}  // namespace ddt
