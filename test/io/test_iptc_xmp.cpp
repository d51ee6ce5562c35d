// ddtup's IPTC and XMP encoders (core/io/iptc.h, xmp.h) against OpenImageIO 2.4's
// encode_iptc_iim and encode_xmp(spec, minimal = true), the reference they replace (linked into
// the tests): the same bytes from the same attributes — every name either table knows, as
// strings, ints, floats, bools, ';' lists, dates, rationals and the other types, redundant
// properties alone, mixed-case names, XML's special characters, empty and 70 000-byte strings,
// every order — and from the attributes OpenImageIO reads from the test images and photographs.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>
#include <OpenImageIO/tiffutils.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "iptc.h"
#include "oiio_metadata.h"
#include "xmp.h"

using ddt::AttributeType;
using ddt::ImageAttribute;
using ddt::ImageAttributes;
using Base = AttributeType::Base;
using Meaning = AttributeType::Meaning;

namespace {

std::string oiioIptc(const ImageAttributes& attributes) {
    OIIO::ImageSpec spec;
    ddt::addAttributes(attributes, spec);
    std::vector<char> block;
    OIIO::encode_iptc_iim(spec, block);
    return std::string(block.begin(), block.end());
}

std::string oiioXmp(const ImageAttributes& attributes) {
    OIIO::ImageSpec spec;
    ddt::addAttributes(attributes, spec);
    return OIIO::encode_xmp(spec, true);
}

// Both encoders give OpenImageIO's bytes for the attributes.
void checkSame(const ImageAttributes& attributes) {
    CHECK(ddt::encodeIptc(attributes) == oiioIptc(attributes));
    CHECK(ddt::encodeXmp(attributes) == oiioXmp(attributes));
}

// Every name of OpenImageIO 2.4.7's XMP table (xmp.cpp's xmptag), its XMP names and the
// attribute names beside them; the IPTC table's names are read back from OpenImageIO below.
const char* const kXmpTableNames = R"(
photoshop:AuthorsPosition IPTC:AuthorsPosition photoshop:CaptionWriter IPTC:CaptionWriter
photoshop:Category IPTC:Category photoshop:City IPTC:City photoshop:Country IPTC:Country photoshop:Credit
IPTC:Provider photoshop:DateCreated DateTime photoshop:Headline IPTC:Headline photoshop:History
ImageHistory photoshop:Instructions IPTC:Instructions photoshop:Source IPTC:Source photoshop:State
IPTC:State photoshop:SupplementalCategories IPTC:SupplementalCategories photoshop:TransmissionReference
IPTC:TransmissionReference photoshop:Urgency tiff:Compression tiff:PlanarConfiguration
tiff:PhotometricInterpretation tiff:subfiletype tiff:Orientation Orientation tiff:XResolution XResolution
tiff:YResolution YResolution tiff:ResolutionUnit ResolutionUnit tiff:Artist Artist tiff:Copyright Copyright
tiff:DateTime tiff:ImageDescription ImageDescription tiff:Make Make tiff:Model Model tiff:Software Software
exif:ColorSpace Exif:ColorSpace exif:PixelXDimension exif:PixelYDimension exifEX:PhotographicSensitivity
Exif:ISOSpeedRatings xmp:CreateDate xmp:CreatorTool xmp:Label IPTC:Label xmp:MetadataDate IPTC:MetadataDate
xmp:ModifyDate IPTC:ModifyDate xmp:Rating IPTC:Rating xmpMM:DocumentID IPTC:DocumentID xmpMM:History
xmpMM:InstanceID IPTC:InstanceID xmpMM:OriginalDocumentID IPTC:OriginalDocumentID xmpRights:Marked
IPTC:CopyrightStatus xmpRights:WebStatement IPTC:CopyrightInfoURL xmpRights:UsageTerms
IPTC:RightsUsageTerms dc:format dc:Description dc:Creator dc:Rights dc:title IPTC:ObjectName dc:subject
Keywords dc:keywords Iptc4xmpCore:IntellectualGenre IPTC:IntellectualGenre Iptc4xmpCore:CountryCode
IPTC:CountryCode Iptc4xmpCore:CreatorContactInfo IPTC:CreatorContactInfo Iptc4xmpCore:ContactInfoDetails
IPTC:Contact Iptc4xmpCore:CiAdrExtadr IPTC:ContactInfoAddress Iptc4xmpCore:CiAdrCity IPTC:ContactInfoCity
Iptc4xmpCore:CiAdrRegion IPTC:ContactInfoState Iptc4xmpCore:CiAdrPcode IPTC:ContactInfoPostalCode
Iptc4xmpCore:CiAdrCtry IPTC:ContactInfoCountry Iptc4xmpCore:CiEmailWork IPTC:ContactInfoEmail
Iptc4xmpCore:CiTelWork IPTC:ContactInfoPhone Iptc4xmpCore:CiUrlWork IPTC:ContactInfoURL
Iptc4xmpCore:Location IPTC:Sublocation Iptc4xmpCore:SubjectCode IPTC:SubjectCode Iptc4xmpCore:Scene
IPTC:SceneCode Iptc4xmpExt:PersonInImage IPTC:PersonInImage aux:Firmware crs:AutoBrightness
crs:AutoContrast crs:AutoExposure crs:AutoShadows crs:BlueHue crs:BlueSaturation crs:Brightness
crs:CameraProfile crs:ChromaticAberrationB crs:ChromaticAberrationR crs:ColorNoiseReduction crs:Contrast
crs:CropTop crs:CropLeft crs:CropBottom crs:CropRight crs:CropAngle crs:CropWidth crs:CropHeight
crs:CropUnits crs:Exposure crs:GreenHue crs:GreenSaturation crs:HasCrop crs:HasSettings
crs:LuminanceSmoothing crs:RawFileName crs:RedHue crs:RedSaturation crs:Saturation crs:Shadows
crs:ShadowTint crs:Sharpness crs:Temperature crs:Tint crs:ToneCurve crs:ToneCurveName crs:Version
crs:VignetteAmount crs:VignetteMidpoint crs:WhiteBalance GPano:UsePanoramaViewer GPano:CaptureSoftware
GPano:StitchingSoftware GPano:ProjectionType GPano:PoseHeadingDegrees GPano:PosePitchDegrees
GPano:PoseRollDegrees GPano:InitialViewHeadingDegrees GPano:InitialViewPitchDegrees
GPano:InitialViewRollDegrees GPano:InitialHorizontalFOVDegrees GPano:FirstPhotoDate GPano:LastPhotoDate
GPano:SourcePhotosCount GPano:ExposureLockUsed GPano:CroppedAreaImageWidthPixels
GPano:CroppedAreaImageHeightPixels GPano:FullPanoWidthPixels GPano:FullPanoHeightPixels
GPano:CroppedAreaLeftPixels GPano:CroppedAreaTopPixels GPano:InitialCameraDolly
GPano:LargestValidInteriorRectWidth GPano:LargestValidInteriorRectHeight GPano:LargestValidInteriorRectTop
GPano:LargestValidInteriorRectLeft rdf:li
)";

std::vector<std::string> xmpTableNames() {
    std::vector<std::string> names;
    for (std::string_view name : OIIO::Strutil::splitsv(kXmpTableNames))
        if (!name.empty()) names.emplace_back(name);
    return names;
}

// Every attribute name OpenImageIO's IPTC table has: the names its decoder gives datasets
// 0..255 of record 2.
std::vector<std::string> iptcTableNames() {
    std::string block;
    for (int dataset = 0; dataset < 256; ++dataset) block += std::string("\x1C\x02", 2) + char(dataset) + std::string("\0\x01x", 3);
    OIIO::ImageSpec spec;
    OIIO::decode_iptc_iim(block.data(), int(block.size()), spec);
    std::vector<std::string> names;
    for (const OIIO::ParamValue& p : spec.extra_attribs) names.push_back(p.name().string());
    return names;
}

std::vector<std::string> allTableNames() {
    std::vector<std::string> names = iptcTableNames();
    for (std::string& name : xmpTableNames()) names.push_back(std::move(name));
    return names;
}

ImageAttribute text(const std::string& name, std::string value) {
    ImageAttribute a{name, {}, {}, {value}};
    a.type.base = Base::String;
    return a;
}

template <class T>
ImageAttribute numbers(const std::string& name, Base base, std::vector<T> values, uint8_t aggregate = 1,
                       Meaning meaning = Meaning::None, bool array = false) {
    ImageAttribute a{name, {}, {}, {}};
    a.type.base = base;
    a.type.aggregate = aggregate;
    a.type.meaning = meaning;
    a.type.array_length = array ? uint32_t(values.size() / aggregate) : 0;
    const auto* bytes = reinterpret_cast<const uint8_t*>(values.data());
    a.bytes.assign(bytes, bytes + values.size() * sizeof(T));
    return a;
}

ImageAttribute intValue(const std::string& name, int32_t value) { return numbers<int32_t>(name, Base::Int32, {value}); }
ImageAttribute floatValue(const std::string& name, float value) { return numbers<float>(name, Base::Float, {value}); }

// Values of every kind OpenImageIO turns into text its own way, under `name`.
std::vector<ImageAttribute> everyKind(const std::string& name) {
    ImageAttribute strings{name, {}, {}, {"a \"quoted\"\\ one", "tab\tand\nnewline", ""}};
    strings.type.base = Base::String;
    strings.type.array_length = 3;
    return {
        text(name, "plain text"),
        text(name, "a; list ;; of; ;parts ; "),
        text(name, "  \t"),
        text(name, std::string("before\0after", 12)),
        text(name, "Tom & Jerry <tom@example.org> said \"hi\" 'there'"),
        text(name, "2024:05:06 07:08:09"),
        intValue(name, 0),
        intValue(name, 1),
        intValue(name, -42),
        floatValue(name, 0.0f),
        floatValue(name, 1.5f),
        floatValue(name, 72.0f),
        floatValue(name, 1.0f / 3.0f),
        floatValue(name, -2.5e-7f),
        floatValue(name, 1.0e20f),
        numbers<uint8_t>(name, Base::UInt8, {200}),
        numbers<int8_t>(name, Base::Int8, {-100}),
        numbers<uint16_t>(name, Base::UInt16, {60000}),
        numbers<int16_t>(name, Base::Int16, {-30000}),
        numbers<uint32_t>(name, Base::UInt32, {4000000000u}),
        numbers<uint64_t>(name, Base::UInt64, {123456789012345ull}),
        numbers<int64_t>(name, Base::Int64, {-123456789012345ll}),
        numbers<uint16_t>(name, Base::Half, {0x3C00}),  // 1.0
        numbers<double>(name, Base::Double, {3.141592653589793}),
        numbers<int32_t>(name, Base::Int32, {1, 2, 3}, 1, Meaning::None, true),
        numbers<float>(name, Base::Float, {0.25f, 0.5f, 1.0f}, 3, Meaning::Colour),
        numbers<float>(name, Base::Float, {1, 0, 0, 0, 1, 0, 0, 0, 1}, 9),
        numbers<int32_t>(name, Base::Int32, {300, 1}, 2, Meaning::Rational),
        numbers<int32_t>(name, Base::Int32, {1, 3, -2, 7}, 2, Meaning::Rational, true),
        numbers<uint32_t>(name, Base::UInt32, {72, 1}, 2, Meaning::Rational),
        numbers<uint32_t>(name, Base::UInt32, {0x12345678u, 0}, 1, Meaning::Timecode, true),
        numbers<uint32_t>(name, Base::UInt32, {0x01020304u, 5}, 1, Meaning::Keycode, true),
        strings,
    };
}

}  // namespace

TEST_CASE("iptc xmp: nothing gives no block", "[io]") {
    CHECK(ddt::encodeIptc({}).empty());
    CHECK(ddt::encodeXmp({}).empty());
    checkSame({});
}

TEST_CASE("iptc xmp: every name of either table alone, with values of every kind", "[io]") {
    const std::vector<std::string> names = allTableNames();
    REQUIRE(names.size() > 100);  // the IPTC decoder and the XMP list both gave their names
    for (const std::string& name : names)
        for (const ImageAttribute& attribute : everyKind(name)) {
            ImageAttributes attributes;
            attributes.append(attribute);
            INFO(name << " of base " << int(attribute.type.base) << " x" << int(attribute.type.aggregate) << " ["
                      << attribute.type.array_length << "]");
            checkSame(attributes);
        }
}

TEST_CASE("iptc xmp: every name at once, in several orders, spelt in other cases", "[io]") {
    std::vector<ImageAttribute> all;
    int i = 0;
    for (const std::string& name : allTableNames()) {
        all.push_back(text(name, "value " + std::to_string(i) + "; second"));
        all.push_back(intValue(name, i % 3));
        all.push_back(floatValue(name, float(i) * 0.75f));
        ++i;
    }
    std::mt19937 random(33);
    for (int round = 0; round < 6; ++round) {
        INFO("round " << round);
        std::shuffle(all.begin(), all.end(), random);
        ImageAttributes attributes;
        for (ImageAttribute attribute : all) {
            // Rounds 2 and up: names in upper or lower case, which both match regardless of case.
            if (round >= 2)
                for (char& c : attribute.name) c = char(round % 2 ? std::toupper(c) : std::tolower(c));
            attributes.append(attribute);
        }
        checkSame(attributes);
    }
}

TEST_CASE("iptc xmp: XMP properties are written, escaped or not, as OpenImageIO writes them", "[io]") {
    ImageAttributes attributes;
    attributes.append(text("GPano:ProjectionType", "equirectangular & <\"cylindrical\">"));
    attributes.append(intValue("crs:HasCrop", 1));
    attributes.append(intValue("crs:AutoExposure", 0));
    attributes.append(floatValue("crs:Exposure", -0.35f));
    attributes.append(intValue("photoshop:Urgency", 5));
    attributes.append(text("GPano:FirstPhotoDate", "2024-05-06T07:08:09"));
    attributes.append(text("crs:RawFileName", ""));  // empty: no property
    const std::string packet = ddt::encodeXmp(attributes);
    // An independent look at what must be there, beside the byte comparison.
    CHECK(packet.find("crs:HasCrop=\"True\"") != std::string::npos);
    CHECK(packet.find("crs:AutoExposure=\"False\"") != std::string::npos);
    CHECK(packet.find("GPano:ProjectionType=\"equirectangular & <\"cylindrical\">\"") != std::string::npos);
    CHECK(packet.find("RawFileName") == std::string::npos);
    checkSame(attributes);
}

TEST_CASE("iptc xmp: properties redundant with TIFF or EXIF alone give no packet", "[io]") {
    ImageAttributes redundant;
    redundant.append(intValue("tiff:Compression", 7));
    redundant.append(intValue("tiff:PhotometricInterpretation", 2));
    redundant.append(intValue("tiff:PlanarConfiguration", 1));
    redundant.append(intValue("tiff:subfiletype", 0));
    redundant.append(intValue("Exif:ColorSpace", 1));
    redundant.append(floatValue("XResolution", 300.0f));
    redundant.append(text("Software", "ddtup"));
    redundant.append(text("DateTime", "2024:05:06 07:08:09"));
    CHECK(ddt::encodeXmp(redundant).empty());
    checkSame(redundant);
    ImageAttributes with_other = redundant;
    with_other.append(intValue("crs:Tint", 3));
    checkSame(with_other);
}

TEST_CASE("iptc xmp: IPTC lists, empty values and a 70 000-byte value", "[io]") {
    ImageAttributes attributes;
    attributes.append(text("Keywords", "sun; sea ;;  ; sand;"));
    attributes.append(text("IPTC:Creator", "  one ; two"));
    attributes.append(text("Artist", "Someone; Else"));  // the other name: one record, not split
    attributes.append(text("IPTC:Caption", std::string(70000, 'c')));
    attributes.append(text("ImageDescription", std::string(65534, 'd').append("cut")));
    attributes.append(text("Copyright", "(c) 2024 <A & B>"));
    const std::string records = ddt::encodeIptc(attributes);
    // Independently: the Keywords dataset (25) comes as three records "sun", "sea", "sand".
    CHECK(records.find(std::string("\x1C\x02\x19\x00\x03sun", 8)) != std::string::npos);
    CHECK(records.find(std::string("\x1C\x02\x19\x00\x04sand", 9)) != std::string::npos);
    // The long caption is cut to 65 534 bytes (0xFFFE), its size field says so.
    CHECK(records.find(std::string("\x1C\x02\x78\xFF\xFE", 5)) != std::string::npos);
    checkSame(attributes);
}

// The OpenImageIO linked here asserts that a value is not empty (a debug check, on in its
// build): its release build writes a record with no size field, which is what is checked here.
TEST_CASE("iptc xmp: an empty value is an IPTC record with no size, and no XMP property", "[io]") {
    for (const std::string& name : allTableNames()) {
        INFO(name);
        ImageAttributes attributes;
        attributes.append(text(name, ""));
        CHECK(ddt::encodeXmp(attributes) == oiioXmp(attributes));
        CHECK(ddt::encodeXmp(attributes).empty());
    }
    ImageAttributes attributes;
    attributes.append(text("IPTC:City", ""));          // dataset 90
    attributes.append(text("Keywords", ""));           // a list: no part, no record
    attributes.append(text("ImageDescription", ""));   // dataset 120, by its other name
    CHECK(ddt::encodeIptc(attributes) == std::string("\x1C\x02\x5A\x1C\x02\x78", 6));
}

TEST_CASE("iptc xmp: the attributes of the test images and photographs", "[io]") {
    int read = 0;
    for (const char* folder : {"/tmp/photos", DDTUP_TEST_DATA}) {
        std::error_code error;
        for (const auto& entry : std::filesystem::recursive_directory_iterator(folder, error)) {
            auto input = OIIO::ImageInput::open(entry.path().string());
            if (!input) continue;
            INFO(entry.path());
            const ImageAttributes attributes = ddt::attributesOf(input->spec());
            checkSame(attributes);
            ++read;
        }
    }
    CHECK(read >= 5);  // the test images at least
}
