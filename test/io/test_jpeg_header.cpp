// JpegDecoder::attributes (jpeg_header.h) against OpenImageIO's JPEG reader: every attribute,
// entry by entry, for photographs and for files written here with libjpeg with each marker
// OpenImageIO reads (JFIF densities, EXIF orientations and resolutions, COM, ICC).
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

// jpeglib.h needs FILE and size_t declared before it.
#include <cstdio>
#include <jpeglib.h>

#include <filesystem>
#include <string>
#include <vector>

#include "header_checks.h"
#include "image_file.h"
#include "image_metadata.h"
#include "jpeg_decoder.h"
#include "exif.h"
#include "oiio_metadata.h"
#include "temp_folder.h"

namespace {

namespace fs = std::filesystem;
using ddt::JpegDecoder;

struct JpegSettings {
    int channels = 3;
    int h_sampling = 2, v_sampling = 2;  // the first component's; the others' are 1
    bool jfif = true;
    int density_unit = 0, x_density = 1, y_density = 1;
    std::vector<std::pair<int, std::string>> markers;  // written after the JFIF marker, in order
};

// A 16×8 gradient written by libjpeg with `settings`.
void writeJpeg(const std::string& path, const JpegSettings& settings) {
    jpeg_compress_struct info{};
    jpeg_error_mgr errors{};
    info.err = jpeg_std_error(&errors);
    jpeg_create_compress(&info);
    std::FILE* file = std::fopen(path.c_str(), "wb");
    REQUIRE(file);
    jpeg_stdio_dest(&info, file);
    info.image_width = 16;
    info.image_height = 8;
    info.input_components = settings.channels;
    info.in_color_space = settings.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_set_defaults(&info);
    info.write_JFIF_header = settings.jfif;
    info.density_unit = UINT8(settings.density_unit);
    info.X_density = UINT16(settings.x_density);
    info.Y_density = UINT16(settings.y_density);
    if (settings.channels == 3) {
        info.comp_info[0].h_samp_factor = settings.h_sampling;
        info.comp_info[0].v_samp_factor = settings.v_sampling;
    }
    jpeg_start_compress(&info, TRUE);
    for (const auto& [marker, data] : settings.markers)
        jpeg_write_marker(&info, marker, reinterpret_cast<const JOCTET*>(data.data()), unsigned(data.size()));
    std::vector<uint8_t> row(16 * size_t(settings.channels));
    for (size_t i = 0; i < row.size(); ++i) row[i] = uint8_t(i * 5);
    while (info.next_scanline < info.image_height) {
        JSAMPROW rows[] = {row.data()};
        jpeg_write_scanlines(&info, rows, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    std::fclose(file);
}

std::string exifMarker(int orientation, bool resolution) {
    ddt::ImageAttributes attributes;
    attributes.set("Orientation", int32_t(orientation));
    if (resolution) {
        attributes.set("XResolution", 300.0f);
        attributes.set("YResolution", 200.0f);
        attributes.set("ResolutionUnit", std::string("cm"));
    }
    attributes.set("ImageDescription", std::string("from EXIF"));
    attributes.set("Exif:ColorSpace", int32_t(65535));  // uncalibrated: no sRGB from EXIF
    attributes.set("Exif:ExposureTime", 0.01f);
    return std::string("Exif\0\0", 6) + ddt::encodeExif(attributes);
}

// The profile in APP2 chunks of `chunk_bytes`, numbered from 1.
std::vector<std::pair<int, std::string>> iccMarkers(const std::string& profile, size_t chunk_bytes) {
    std::vector<std::pair<int, std::string>> markers;
    const size_t count = (profile.size() + chunk_bytes - 1) / chunk_bytes;
    for (size_t i = 0; i < count; ++i)
        markers.push_back({JPEG_APP0 + 2, std::string("ICC_PROFILE") + '\0' + char(i + 1) + char(count) +
                                              profile.substr(i * chunk_bytes, chunk_bytes)});
    return markers;
}

void requireSameAsOpenImageIO(const std::string& path) {
    INFO(path);
    const JpegDecoder decoder(path, path);
    REQUIRE(decoder.decodable());
    const std::optional<ddt::ImageAttributes> ours = decoder.attributes(ddt::test::decodeExifByOpenImageIO);
    REQUIRE(ours);
    ddt::test::requireSameAttributes(*ours, ddt::test::attributesByOpenImageIO(path));
    // With the EXIF decoder the reader passes.
    const std::optional<ddt::ImageAttributes> reader_s = decoder.attributes(ddt::test::decodeExifByDdtup);
    REQUIRE(reader_s);
    ddt::test::requireSameAttributes(*reader_s, ddt::test::attributesByOpenImageIO(path));
}

}  // namespace

TEST_CASE("jpeg header: photographs read as OpenImageIO reads them", "[io]") {
    std::vector<std::string> files;
    for (const char* folder : {"/tmp/photos", "/work/shared/data/images"})
        if (fs::is_directory(folder))
            for (const auto& entry : fs::recursive_directory_iterator(folder))
                if (entry.path().extension() == ".jpg" || entry.path().extension() == ".jpeg") files.push_back(entry.path());
    if (files.empty()) WARN("no photographs on this machine: nothing compared");
    for (const std::string& file : files) requireSameAsOpenImageIO(file);
}

TEST_CASE("jpeg header: each marker OpenImageIO reads gives its attributes, names, types and order", "[io]") {
    TempFolder folder;
    const std::string icc = ddt::test::iccProfileWithTexts("RGB ");
    struct Case {
        std::string name;
        JpegSettings settings;
    };
    std::vector<Case> cases = {
        {"plain", {}},
        {"grey", {.channels = 1}},
        {"s444", {.h_sampling = 1, .v_sampling = 1}},
        {"s422", {.h_sampling = 2, .v_sampling = 1}},
        {"s411", {.h_sampling = 4, .v_sampling = 1}},
        {"s_other", {.h_sampling = 1, .v_sampling = 2}},
        {"no_jfif", {.jfif = false}},
        {"density_none", {.density_unit = 0, .x_density = 3, .y_density = 2}},
        {"density_inch", {.density_unit = 1, .x_density = 300, .y_density = 300}},
        {"density_cm", {.density_unit = 2, .x_density = 118, .y_density = 59}},
        {"density_aspect", {.density_unit = 0, .x_density = 1, .y_density = 2}},
        {"comment", {.markers = {{JPEG_COM, "first comment"}, {JPEG_COM, "second comment"}}}},
        {"comment_nul", {.markers = {{JPEG_COM, std::string("before\0after", 12)}}}},
        {"icc", {.markers = iccMarkers(icc, 60000)}},
        {"icc_chunks", {.markers = iccMarkers(icc, 100)}},
        {"icc_missing_chunk", {.markers = {iccMarkers(icc, 100)[0], iccMarkers(icc, 100)[2]}}},
        {"exif_then_comment", {.markers = {{JPEG_APP0 + 1, exifMarker(6, true)}, {JPEG_COM, "comment"}}}},
        {"comment_then_exif", {.markers = {{JPEG_COM, "comment"}, {JPEG_APP0 + 1, exifMarker(3, false)}}}},
        {"exif_density_inch", {.density_unit = 1, .x_density = 72, .y_density = 72, .markers = {{JPEG_APP0 + 1, exifMarker(1, true)}}}},
        {"exif_density_one", {.density_unit = 2, .markers = {{JPEG_APP0 + 1, exifMarker(5, true)}}}},
        {"exif_no_jfif", {.jfif = false, .markers = {{JPEG_APP0 + 1, exifMarker(7, true)}, {JPEG_APP0 + 2, iccMarkers(icc, 60000)[0].second}}}},
    };
    for (int orientation = 1; orientation <= 8; ++orientation)
        cases.push_back({"orientation" + std::to_string(orientation), {.markers = {{JPEG_APP0 + 1, exifMarker(orientation, orientation % 2 == 0)}}}});
    for (const Case& c : cases) {
        const std::string path = folder / (c.name + ".jpg");
        writeJpeg(path, c.settings);
        requireSameAsOpenImageIO(path);
    }
}

TEST_CASE("jpeg header: XMP and IPTC are left to OpenImageIO, and the reader then gives its attributes", "[io]") {
    TempFolder folder;
    const std::string xmp = std::string("http://ns.adobe.com/xap/1.0/") + '\0' +
                            "<x:xmpmeta xmlns:x='adobe:ns:meta/'><rdf:RDF xmlns:rdf='http://www.w3.org/1999/02/22-rdf-syntax-ns#'>"
                            "<rdf:Description xmlns:tiff='http://ns.adobe.com/tiff/1.0/' tiff:Make='ddtup'/></rdf:RDF></x:xmpmeta>";
    // An IPTC record 2 caption (2:120) in a Photoshop image resource block (8BIM 0x0404).
    const std::string iptc_record = std::string("\x1c\x02\x78\x00\x07", 5) + "caption";
    const std::string iptc = std::string("Photoshop 3.0") + '\0' + "8BIM" + std::string("\x04\x04\0\0", 4) +
                             std::string("\0\0\0", 3) + char(iptc_record.size()) + iptc_record + '\0';
    for (const auto& [name, marker] : {std::pair{std::string("xmp.jpg"), std::pair{JPEG_APP0 + 1, xmp}},
                                       std::pair{std::string("iptc.jpg"), std::pair{JPEG_APP0 + 13, iptc}}}) {
        INFO(name);
        const std::string path = folder / name;
        writeJpeg(path, {.markers = {marker}});
        CHECK(!JpegDecoder(path, path).attributes(ddt::test::decodeExifByOpenImageIO));
        const ddt::ImageReader reader(path);
        ddt::test::requireSameAttributes(reader.header().metadata->attributes, ddt::test::attributesByOpenImageIO(path));
    }
}
