// ddtup's own image attributes: found and converted as OpenImageIO's ImageSpec finds and
// converts them (OpenImageIO is the reference here), and carried through PNG and JPEG files.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <memory>
#include <string>
#include <vector>

#include "image_file.h"
#include "image_metadata.h"
#include "oiio_metadata.h"
#include "png_bytes.h"
#include "temp_folder.h"

namespace {

// Every extra attribute of a spec as "name type value", in order.
std::vector<std::string> describe(const OIIO::ImageSpec& spec) {
    std::vector<std::string> lines;
    for (const OIIO::ParamValue& p : spec.extra_attribs)
        lines.push_back(p.name().string() + " " + p.type().c_str() + " " + p.get_string(1000));
    return lines;
}

ddt::ImageAttribute bytesAttribute(const std::string& name, const std::string& bytes) {
    ddt::ImageAttribute attribute{name, {ddt::AttributeType::Base::UInt8, 1, ddt::AttributeType::Meaning::None, uint32_t(bytes.size())},
                                  std::vector<uint8_t>(bytes.begin(), bytes.end()), {}};
    return attribute;
}

}  // namespace

TEST_CASE("metadata: attributes are found, set, erased and converted as OpenImageIO's ImageSpec does it") {
    OIIO::ImageSpec spec(4, 4, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("XResolution", 300.0f);
    spec.attribute("yresolution", 72);
    const int aspect[2] = {3, 2};
    spec.attribute("PixelAspectRatio", OIIO::TypeRational, aspect);
    spec.attribute("oiio:Gamma", "2.5");
    spec.attribute("Numberish", "12 ");
    spec.attribute("Wordy", "12 apples");
    const double exposure = 0.004;
    spec.attribute("Exif:ExposureTime", OIIO::TypeDesc::DOUBLE, &exposure);
    spec.attribute("Description", "a test card");
    const float latitude[3] = {50.0f, 52.0f, 44.5f};
    spec.attribute("GPS:Latitude", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 3), latitude);
    const uint16_t shorts[2] = {7, 9};
    spec.attribute("Shorts", OIIO::TypeDesc(OIIO::TypeDesc::UINT16, 2), shorts);
    const uint16_t half_seven_and_a_half = 0x4780;
    spec.attribute("Half", OIIO::TypeDesc::HALF, &half_seven_and_a_half);
    const uint64_t big = 0x100000007ull;
    spec.attribute("Big", OIIO::TypeDesc::UINT64, &big);
    spec.attribute("Vector", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::VEC3), latitude);
    spec.attribute("Spaced", " 12");
    spec.attribute("Fraction", "1.5");
    const std::vector<std::string> names = {"XResolution", "xresolution", "YResolution", "PixelAspectRatio", "oiio:gamma",
                                            "Numberish", "Wordy", "Exif:ExposureTime", "description", "GPS:Latitude",
                                            "Shorts", "Half", "Big", "Vector", "Spaced", "Fraction", "missing"};

    ddt::ImageAttributes ours = ddt::attributesOf(spec);
    auto compare = [&] {
        for (const std::string& name : names) {
            INFO(name);
            CHECK(ours.getFloat(name, -1.0f) == spec.get_float_attribute(name, -1.0f));
            CHECK(ours.getInt(name, -1) == spec.get_int_attribute(name, -1));
            CHECK(ours.getString(name, "none") == spec.get_string_attribute(name, "none"));
        }
        OIIO::ImageSpec back(4, 4, 3, OIIO::TypeDesc::UINT8);
        ddt::addAttributes(ours, back);
        CHECK(describe(back) == describe(spec));
    };
    compare();

    // Set in place under the new name's spelling, appended when new, erased whatever the case.
    ours.set("XRESOLUTION", 150.0f);
    spec.attribute("XRESOLUTION", 150.0f);
    ours.set("Software", std::string("ddtup"));
    spec.attribute("Software", "ddtup");
    ours.set("description", 3);
    spec.attribute("description", 3);
    ours.erase("numberISH");
    spec.erase_attribute("numberISH");
    compare();
}

// The attributes ddtup makes, written by ImageWriter, read back by OpenImageIO (the
// reference) and by ImageReader (the round trip).
TEST_CASE("metadata: ddtup's attributes survive a PNG and a JPEG file") {
    TempFolder folder;
    const std::string profile = ddt::test::iccProfile("RGB ");
    auto metadata = std::make_shared<ddt::ImageMetadata>();
    metadata->format_name = "tiff";
    metadata->alpha_storage = ddt::AlphaStorage::Straight;
    ddt::ImageAttributes& attributes = metadata->attributes;
    attributes.append(bytesAttribute("ICCProfile", profile));
    attributes.set("XResolution", 300.0f);
    attributes.set("YResolution", 150.0f);
    attributes.set("ResolutionUnit", std::string("in"));
    attributes.set("Exif:FocalLength", 35.0f);
    attributes.set("Exif:Flash", 16);
    attributes.set("Exif:LensModel", std::string("a lens"));
    attributes.set("ImageDescription", std::string("a test card"));
    attributes.set("DateTime", std::string("2022:03:04 05:06:07"));

    ddt::Image image;
    image.width = 8;
    image.height = 6;
    image.channels = 3;
    image.sample_type = ddt::SampleType::UInt8;
    image.pixels.assign(8 * 6 * 3, 0.5f);
    image.metadata = metadata;

    for (const char* name : {"out.png", "out.jpg"}) {
        INFO(name);
        CHECK(ddt::writeImage(folder / name, image).empty());
        auto input = OIIO::ImageInput::open(folder / name);
        REQUIRE(input);
        const OIIO::ImageSpec& spec = input->spec();
        const OIIO::ParamValue* icc = spec.find_attribute("ICCProfile");
        REQUIRE(icc);
        CHECK(std::string(static_cast<const char*>(icc->data()), icc->type().size()) == profile);
        // PNG holds whole pixels per metre (11811 for 300 dpi is 299.9994 dpi), JPEG whole dots
        // per inch: a thousandth allows for that.
        CHECK(spec.get_float_attribute("XResolution") == Approx(300.0f).epsilon(1e-3));
        CHECK(spec.get_float_attribute("YResolution") == Approx(150.0f).epsilon(1e-3));
        CHECK(spec.get_float_attribute("Exif:FocalLength") == 35.0f);
        CHECK(spec.get_int_attribute("Exif:Flash") == 16);
        CHECK(spec.get_string_attribute("Exif:LensModel") == "a lens");
        CHECK(spec.get_string_attribute("ImageDescription") == "a test card");
        CHECK(spec.get_string_attribute("DateTime") == "2022:03:04 05:06:07");

        ddt::ImageReader reader(folder / name);
        const ddt::ImageAttributes& read = reader.header().metadata->attributes;
        const ddt::ImageAttribute* read_icc = read.find("ICCProfile");
        REQUIRE(read_icc);
        CHECK(std::string(read_icc->bytes.begin(), read_icc->bytes.end()) == profile);
        CHECK(read.getFloat("XResolution") == Approx(300.0f).epsilon(1e-3));
        CHECK(read.getFloat("Exif:FocalLength") == 35.0f);
        CHECK(read.getInt("Exif:Flash") == 16);
        CHECK(read.getString("ImageDescription") == "a test card");
        CHECK(read.getString("DateTime") == "2022:03:04 05:06:07");
    }
}
