#include "exif_tags.h"

#include "image_attributes.h"

namespace ddt::exif {

namespace {

using enum FieldType;

// Names and types as OpenImageIO 2.4 gives them, so that a block ddtup reads holds the
// attributes OpenImageIO's reader made, and one it writes the tags OpenImageIO's writer wrote.
// Some of its choices differ from the standard; they are kept and marked.
const Tag kMainTags[] = {
    // TIFF tags the image's own header says better: passed over.
    {256, "Exif:ImageWidth", None, 1},
    {257, "Exif:ImageLength", None, 1},
    {258, "Exif:BitsPerSample", None, 0},
    {259, "Exif:Compression", None, 1},
    {262, "Exif:Photometric", None, 1},
    {277, "Exif:SamplesPerPixel", None, 1},
    {284, "Exif:PlanarConfig", None, 1},
    {530, "Exif:YCbCrSubsampling", Short, 1},
    {531, "Exif:YCbCrPositioning", Short, 1},
    // TIFF tags of the first directory.
    {274, "Orientation", Short, 1},
    {282, "XResolution", Rational, 1},
    {283, "YResolution", Rational, 1},
    {296, "ResolutionUnit", Short, 1},
    {270, "ImageDescription", Ascii, 0},
    {271, "Make", Ascii, 0},
    {272, "Model", Ascii, 0},
    {305, "Software", Ascii, 0},
    {315, "Artist", Ascii, 0},
    {33432, "Copyright", Ascii, 0},
    {306, "DateTime", Ascii, 0},
    {kExifDirectoryTag, "Exif:ExifIFD", None, 1},
    {kInteroperabilityDirectoryTag, "Exif:InteroperabilityIFD", None, 1},
    {kGpsDirectoryTag, "Exif:GPSIFD", None, 1},
    // EXIF tags. The first two carry no "Exif:" prefix in OpenImageIO.
    {33434, "ExposureTime", Rational, 1},
    {33437, "FNumber", Rational, 1},
    {34850, "Exif:ExposureProgram", Short, 1},
    {34852, "Exif:SpectralSensitivity", Ascii, 0},
    {34855, "Exif:ISOSpeedRatings", Short, 1},  // EXIF 2.2's name; 2.3's comes later and wins on reading
    {34856, "Exif:OECF", None, 1},
    {36864, "Exif:ExifVersion", Undefined, 1, Reading::FourCharacters},
    {36867, "Exif:DateTimeOriginal", Ascii, 0},
    {36868, "Exif:DateTimeDigitized", Ascii, 0},
    {36880, "Exif:OffsetTime", Ascii, 0},
    {36881, "Exif:OffsetTimeOriginal", Ascii, 0},
    {36882, "Exif:OffsetTimeDigitized", Ascii, 0},
    {37121, "Exif:ComponentsConfiguration", Undefined, 1},
    {37122, "Exif:CompressedBitsPerPixel", Rational, 1},
    {37377, "Exif:ShutterSpeedValue", SRational, 1},
    {37378, "Exif:ApertureValue", Rational, 1},
    {37379, "Exif:BrightnessValue", SRational, 1},
    {37380, "Exif:ExposureBiasValue", SRational, 1},
    {37381, "Exif:MaxApertureValue", Rational, 1},
    {37382, "Exif:SubjectDistance", Rational, 1},
    {37383, "Exif:MeteringMode", Short, 1},
    {37384, "Exif:LightSource", Short, 1},
    {37385, "Exif:Flash", Short, 1},
    {37386, "Exif:FocalLength", Rational, 1},
    {37394, "Exif:SecurityClassification", Ascii, 1},
    {37395, "Exif:ImageHistory", Ascii, 1},
    {37396, "Exif:SubjectArea", None, 1},
    {37500, "Exif:MakerNote", Byte, 0, Reading::MakerNote},    // UNDEFINED in EXIF
    {37510, "Exif:UserComment", Byte, 0},                      // UNDEFINED in EXIF
    {37520, "Exif:SubsecTime", Ascii, 0},
    {37521, "Exif:SubsecTimeOriginal", Ascii, 0},
    {37522, "Exif:SubsecTimeDigitized", Ascii, 0},
    {40960, "Exif:FlashPixVersion", Undefined, 1, Reading::FourCharacters},
    {40961, "Exif:ColorSpace", Short, 1},
    {40962, "Exif:PixelXDimension", Long, 1},
    {40963, "Exif:PixelYDimension", Long, 1},
    {40964, "Exif:RelatedSoundFile", Ascii, 0},
    {41483, "Exif:FlashEnergy", Rational, 1},
    {41484, "Exif:SpatialFrequencyResponse", None, 1},
    {41486, "Exif:FocalPlaneXResolution", Rational, 1},
    {41487, "Exif:FocalPlaneYResolution", Rational, 1},
    {41488, "Exif:FocalPlaneResolutionUnit", Short, 1},
    {41492, "Exif:SubjectLocation", Short, 2},
    {41493, "Exif:ExposureIndex", Rational, 1},
    {41495, "Exif:SensingMethod", Short, 1},
    {41728, "Exif:FileSource", Undefined, 1},
    {41729, "Exif:SceneType", Undefined, 1},
    {41730, "Exif:CFAPattern", None, 1},
    {41985, "Exif:CustomRendered", Short, 1},
    {41986, "Exif:ExposureMode", Short, 1},
    {41987, "Exif:WhiteBalance", Short, 1},
    {41988, "Exif:DigitalZoomRatio", Rational, 1},
    {41989, "Exif:FocalLengthIn35mmFilm", Short, 1},
    {41990, "Exif:SceneCaptureType", Short, 1},
    {41991, "Exif:GainControl", Rational, 1},  // SHORT in EXIF
    {41992, "Exif:Contrast", Short, 1},
    {41993, "Exif:Saturation", Short, 1},
    {41994, "Exif:Sharpness", Short, 1},
    {41995, "Exif:DeviceSettingDescription", None, 1},
    {41996, "Exif:SubjectDistanceRange", Short, 1},
    {42016, "Exif:ImageUniqueID", Ascii, 0},
    {34855, "Exif:PhotographicSensitivity", Short, 1},
    {34864, "Exif:SensitivityType", Short, 1},
    {34865, "Exif:StandardOutputSensitivity", Long, 1},
    {34866, "Exif:RecommendedExposureIndex", Long, 1},
    {34867, "Exif:ISOSpeed", Long, 1},
    {34868, "Exif:ISOSpeedLatitudeyyy", Long, 1},
    {34869, "Exif:ISOSpeedLatitudezzz", Long, 1},
    {37888, "Exif:Temperature", SRational, 1},
    {37889, "Exif:Humidity", Rational, 1},
    {37890, "Exif:Pressure", Rational, 1},
    {37891, "Exif:WaterDepth", SRational, 1},
    {37892, "Exif:Acceleration", Rational, 1},
    {37893, "Exif:CameraElevationAngle", SRational, 1},
    {42032, "Exif:CameraOwnerName", Ascii, 0},
    {42033, "Exif:BodySerialNumber", Ascii, 0},
    {42034, "Exif:LensSpecification", Rational, 4},
    {42035, "Exif:LensMake", Ascii, 0},
    {42036, "Exif:LensModel", Ascii, 0},
    {42037, "Exif:LensSerialNumber", Ascii, 0},
    {42240, "Exif:Gamma", Rational, 0},  // written with no value: OpenImageIO's count is 0
};

const Tag kGpsTags[] = {
    {0, "GPS:VersionID", Byte, 4, Reading::FourBytes},
    {1, "GPS:LatitudeRef", Ascii, 2},
    {2, "GPS:Latitude", Rational, 3},  // degrees, minutes, seconds
    {3, "GPS:LongitudeRef", Ascii, 2},
    {4, "GPS:Longitude", Rational, 3},
    {5, "GPS:AltitudeRef", Byte, 1},
    {6, "GPS:Altitude", Rational, 1},
    {7, "GPS:TimeStamp", Rational, 3},  // hours, minutes, seconds
    {8, "GPS:Satellites", Ascii, 0},
    {9, "GPS:Status", Ascii, 2},
    {10, "GPS:MeasureMode", Ascii, 2},
    {11, "GPS:DOP", Rational, 1},
    {12, "GPS:SpeedRef", Ascii, 2},
    {13, "GPS:Speed", Rational, 1},
    {14, "GPS:TrackRef", Ascii, 2},
    {15, "GPS:Track", Rational, 1},
    {16, "GPS:ImgDirectionRef", Ascii, 2},
    {17, "GPS:ImgDirection", Rational, 1},
    {18, "GPS:MapDatum", Ascii, 0},
    {19, "GPS:DestLatitudeRef", Ascii, 2},
    {20, "GPS:DestLatitude", Rational, 3},
    {21, "GPS:DestLongitudeRef", Ascii, 2},
    {22, "GPS:DestLongitude", Rational, 3},
    {23, "GPS:DestBearingRef", Ascii, 2},
    {24, "GPS:DestBearing", Rational, 1},
    {25, "GPS:DestDistanceRef", Ascii, 2},
    {26, "GPS:DestDistance", Rational, 1},
    {27, "GPS:ProcessingMethod", Undefined, 1},
    {28, "GPS:AreaInformation", Undefined, 1},
    {29, "GPS:DateStamp", Ascii, 0},
    {30, "GPS:Differential", Short, 1},
    {31, "GPS:HPositioningError", Rational, 1},
};

}  // namespace

size_t fieldTypeBytes(uint16_t type) {
    static const size_t kBytes[] = {0, 1, 1, 2, 4, 8, 1, 1, 2, 4, 8, 4, 8, 4};
    return type < std::size(kBytes) ? kBytes[type] : SIZE_MAX;
}

std::span<const Tag> mainTags() { return kMainTags; }
std::span<const Tag> gpsTags() { return kGpsTags; }

const Tag* findTag(std::span<const Tag> table, uint16_t number) {
    const Tag* found = nullptr;
    for (const Tag& tag : table)
        if (tag.number == number) found = &tag;
    return found;
}

const Tag* findTag(std::span<const Tag> table, std::string_view name) {
    const Tag* found = nullptr;
    for (const Tag& tag : table)
        if (sameName(tag.name, name)) found = &tag;
    return found;
}

}  // namespace ddt::exif
