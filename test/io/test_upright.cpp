// The reader's own EXIF turn (upright.h) and code values (code_values.h) against what
// OpenImageIO made before: ImageBufAlgo's flips and turns (5 and 7 composed as the reader
// composed them, since OpenImageIO 2.4's reorient swaps the two) and convert_pixel_values.
#include <catch2/catch.hpp>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <cstring>
#include <random>
#include <vector>

#include "code_values.h"
#include "image_file.h"
#include "image_metadata.h"
#include "temp_folder.h"
#include "upright.h"

namespace {

// The reader's orientation before upright.h, kept here as the reference.
template <class Sample>
std::vector<Sample> uprightByOpenImageIO(const std::vector<Sample>& stored, int width, int height, int channels, int orientation) {
    namespace iba = OIIO::ImageBufAlgo;
    const OIIO::TypeDesc type = OIIO::BaseTypeFromC<Sample>::value;
    const OIIO::ImageBuf in(OIIO::ImageSpec(width, height, channels, type), const_cast<Sample*>(stored.data()));
    OIIO::ImageBuf out, half;
    bool ok = true;
    switch (orientation) {
        case 1: ok = iba::copy(out, in); break;
        case 2: ok = iba::flop(out, in); break;
        case 3: ok = iba::rotate180(out, in); break;
        case 4: ok = iba::flip(out, in); break;
        case 5: ok = iba::transpose(out, in); break;
        case 6: ok = iba::rotate90(out, in); break;
        case 7: ok = iba::rotate180(half, in) && iba::transpose(out, half); break;
        case 8: ok = iba::rotate270(out, in); break;
    }
    REQUIRE(ok);
    std::vector<Sample> result(stored.size());
    REQUIRE(out.get_pixels(OIIO::ROI::All(), type, result.data()));
    return result;
}

template <class Sample>
void checkEveryOrientation(int channels) {
    std::mt19937 rng(7);
    const int width = 5, height = 3;
    std::vector<Sample> stored(size_t(width) * height * channels);
    for (Sample& s : stored) s = Sample(rng() % 60000);
    for (int orientation = 1; orientation <= 8; ++orientation) {
        INFO("orientation " << orientation << ", " << sizeof(Sample) << "-byte samples, " << channels << " channels");
        std::vector<Sample> ours = stored;
        ddt::makeUpright(ours.data(), sizeof(Sample) * channels, width, height, orientation);
        CHECK(std::memcmp(ours.data(), uprightByOpenImageIO(stored, width, height, channels, orientation).data(),
                          stored.size() * sizeof(Sample)) == 0);
    }
}

template <class Code>
void checkEveryCode(uint32_t bits) {
    std::vector<Code> codes(size_t(1) << bits);
    for (size_t code = 0; code < codes.size(); ++code) codes[code] = Code(code);
    std::vector<float> theirs(codes.size());
    REQUIRE(OIIO::convert_pixel_values(OIIO::BaseTypeFromC<Code>::value, codes.data(), OIIO::TypeDesc::FLOAT, theirs.data(),
                                       int(codes.size())));
    const std::vector<float> ours = ddt::valuesOfCodes(bits);
    REQUIRE(ours.size() == theirs.size());
    size_t differing = 0;
    for (size_t code = 0; code < ours.size(); ++code) differing += std::memcmp(&ours[code], &theirs[code], sizeof(float)) != 0;
    CHECK(differing == 0);  // bit for bit: the reader's codes must unpack to what a float read gives
}

}  // namespace

TEST_CASE("upright: EXIF orientations 1..8 turn samples as the reader did through OpenImageIO", "[io]") {
    checkEveryOrientation<uint8_t>(3);
    checkEveryOrientation<uint16_t>(2);
    checkEveryOrientation<float>(4);
    checkEveryOrientation<uint8_t>(1);
}

TEST_CASE("code values: every 8- and 16-bit code is OpenImageIO's float", "[io]") {
    checkEveryCode<uint8_t>(8);
    checkEveryCode<uint16_t>(16);
}

TEST_CASE("upright: a JPEG with each EXIF orientation reads upright, as OpenImageIO's pixels turned", "[io]") {
    TempFolder folder;
    const int width = 7, height = 4;
    std::vector<uint8_t> codes(size_t(width) * height * 3);
    for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint8_t(i * 37 % 251);
    for (int orientation = 1; orientation <= 8; ++orientation) {
        INFO("orientation " << orientation);
        std::string name = "o";  // appended, not `+`: GCC 12 warns falsely about the temporaries
        name += std::to_string(orientation);
        name += ".jpg";
        const std::string path = folder / name;
        OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("Orientation", orientation);
        spec.attribute("jpeg:subsampling", "4:4:4");
        auto output = OIIO::ImageOutput::create(path);
        REQUIRE(output);
        REQUIRE(output->open(path, spec));
        REQUIRE(output->write_image(OIIO::TypeDesc::UINT8, codes.data()));
        REQUIRE(output->close());
        // OpenImageIO's decoding of the stored pixels, as floats, turned by the reference.
        auto input = OIIO::ImageInput::open(path);
        REQUIRE(input);
        REQUIRE(input->spec().get_int_attribute("Orientation") == orientation);
        std::vector<float> stored(codes.size());
        REQUIRE(input->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, stored.data()));
        const std::vector<float> expected = uprightByOpenImageIO(stored, width, height, 3, orientation);

        ddt::ImageReader reader(path);
        const bool swapped = orientation >= 5;
        CHECK(reader.header().width == uint32_t(swapped ? height : width));
        CHECK(reader.header().height == uint32_t(swapped ? width : height));
        CHECK(!reader.header().metadata->attributes.find("Orientation"));
        const ddt::Image image = reader.read();
        CHECK(image.pixels == expected);
    }
}
