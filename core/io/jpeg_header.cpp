#include "jpeg_header.h"

#include <cstring>
#include <string_view>

#include "icc_attributes.h"

namespace ddt {

namespace {

std::string_view dataOf(const jpeg_marker_struct& marker) {
    return {reinterpret_cast<const char*>(marker.data), marker.data_length};
}

// Whether the marker's data starts with `name` and its NUL (OpenImageIO's strcmp).
bool named(const jpeg_marker_struct& marker, std::string_view name) {
    const std::string_view data = dataOf(marker);
    return data.size() > name.size() && data.substr(0, name.size()) == name && data[name.size()] == '\0';
}

// "4:2:0" and the like from the first three components' sampling factors; "" for any other.
std::string subsampling(const jpeg_decompress_struct& info) {
    if (info.num_components < 3) return "";  // OpenImageIO reads past a grey file's one component here
    const jpeg_component_info* c = info.comp_info;
    if (c[1].h_samp_factor != 1 || c[1].v_samp_factor != 1 || c[2].h_samp_factor != 1 || c[2].v_samp_factor != 1) return "";
    const int h = c[0].h_samp_factor, v = c[0].v_samp_factor;
    if (h == 1 && v == 1) return "4:4:4";
    if (h == 2 && v == 1) return "4:2:2";
    if (h == 2 && v == 2) return "4:2:0";
    if (h == 4 && v == 1) return "4:1:1";
    return "";
}

// APP2 "ICC_PROFILE" chunks (a sequence number from 1 and the chunk count after the name)
// joined in sequence order; nothing if any is missing, repeated or disagrees on the count.
std::vector<uint8_t> iccProfile(const jpeg_decompress_struct& info) {
    const size_t kChunkHeader = 14;  // "ICC_PROFILE\0", sequence number, count
    std::vector<const jpeg_marker_struct*> chunks;
    int count = 0;
    for (jpeg_saved_marker_ptr m = info.marker_list; m; m = m->next) {
        if (m->marker != JPEG_APP0 + 2 || !named(*m, "ICC_PROFILE") || m->data_length < kChunkHeader) continue;
        if (count == 0) {
            count = m->data[13];
            chunks.assign(size_t(count) + 1, nullptr);
        } else if (count != m->data[13]) {
            return {};
        }
        const int number = m->data[12];
        if (number <= 0 || number > count || chunks[size_t(number)]) return {};
        chunks[size_t(number)] = m;
    }
    std::vector<uint8_t> profile;
    for (int number = 1; number <= count; ++number) {
        if (!chunks[size_t(number)]) return {};
        const jpeg_marker_struct& chunk = *chunks[size_t(number)];
        profile.insert(profile.end(), chunk.data + kChunkHeader, chunk.data + chunk.data_length);
    }
    return profile;
}

// JFIF's density: a resolution when both exceed 1 (1 and 1 only give the pixel aspect, and
// leave an EXIF resolution as it is); the aspect and the unit follow whichever resolution
// there is. OpenImageIO writes the aspect as x/y, as Nuke and Photoshop do.
void addDensity(const jpeg_decompress_struct& info, ImageAttributes& attributes) {
    float x = attributes.getFloat("XResolution", 0.0f), y = attributes.getFloat("YResolution", 0.0f);
    if (info.X_density && info.Y_density) {
        x = float(info.X_density);
        y = float(info.Y_density);
        if (x > 1 && y > 1) {
            attributes.set("XResolution", x);
            attributes.set("YResolution", y);
        }
    }
    if (x == 0.0f || y == 0.0f) return;
    if (x / y != 1.0f) attributes.set("PixelAspectRatio", x / y);
    if (!attributes.find("XResolution")) return;
    const char* units[] = {"none", "in", "cm"};
    if (info.density_unit <= 2) attributes.set("ResolutionUnit", std::string(units[info.density_unit]));
}

}  // namespace

void keepMetadataMarkers(j_decompress_ptr info) {
    for (int app = 0; app < 16; ++app) jpeg_save_markers(info, JPEG_APP0 + app, 0xFFFF);
    jpeg_save_markers(info, JPEG_COM, 0xFFFF);
}

std::optional<ImageAttributes> jpegAttributes(const jpeg_decompress_struct& info, const DecodeExif& decode_exif) {
    ImageAttributes attributes;
    // sRGB unless EXIF says otherwise.
    attributes.set("oiio:ColorSpace", std::string("sRGB"));
    if (std::string sampling = subsampling(info); !sampling.empty()) attributes.set("jpeg:subsampling", sampling);
    for (jpeg_saved_marker_ptr m = info.marker_list; m; m = m->next) {
        const size_t kExifHeader = 6;  // "Exif\0\0"
        if (m->marker == JPEG_APP0 + 1 && named(*m, "Exif") && m->data_length >= kExifHeader) {
            decode_exif(m->data + kExifHeader, m->data_length - kExifHeader, attributes);
        } else if (m->marker == JPEG_APP0 + 1 && named(*m, "http://ns.adobe.com/xap/1.0/")) {
            return std::nullopt;  // XMP
        } else if (m->marker == JPEG_APP0 + 13 && named(*m, "Photoshop 3.0")) {
            return std::nullopt;  // IPTC
        } else if (m->marker == JPEG_COM) {
            // The first comment, unless EXIF gave a description.
            const ImageAttribute* description = attributes.find("ImageDescription");
            if (!description || description->type.base != AttributeType::Base::String || !description->type.isScalar())
                attributes.set("ImageDescription", std::string(dataOf(*m)).c_str());  // to its first NUL, as there
        }
    }
    addDensity(info, attributes);
    if (std::vector<uint8_t> profile = iccProfile(info); !profile.empty()) {
        const uint32_t length = uint32_t(profile.size());
        attributes.set({"ICCProfile", {AttributeType::Base::UInt8, 1, AttributeType::Meaning::None, length}, profile, {}});
        addIccAttributes(profile, attributes);
    }
    return attributes;
}

}  // namespace ddt
