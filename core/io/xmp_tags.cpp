#include "xmp_tags.h"

namespace ddt {

namespace {

const XmpTag kTags[] = {
    {"photoshop:Urgency", 0},
    {"crs:AutoBrightness", XmpTag::kTrueFalse},
    {"crs:AutoContrast", XmpTag::kTrueFalse},
    {"crs:AutoExposure", XmpTag::kTrueFalse},
    {"crs:AutoShadows", XmpTag::kTrueFalse},
    {"crs:BlueHue", 0},
    {"crs:BlueSaturation", 0},
    {"crs:Brightness", 0},
    {"crs:CameraProfile", 0},
    {"crs:ChromaticAberrationB", 0},
    {"crs:ChromaticAberrationR", 0},
    {"crs:ColorNoiseReduction", 0},
    {"crs:Contrast", 0},
    {"crs:CropTop", 0},
    {"crs:CropLeft", 0},
    {"crs:CropBottom", 0},
    {"crs:CropRight", 0},
    {"crs:CropAngle", 0},
    {"crs:CropWidth", 0},
    {"crs:CropHeight", 0},
    {"crs:CropUnits", 0},
    {"crs:Exposure", 0},
    {"crs:GreenHue", 0},
    {"crs:GreenSaturation", 0},
    {"crs:HasCrop", XmpTag::kTrueFalse},
    {"crs:HasSettings", XmpTag::kTrueFalse},
    {"crs:LuminanceSmoothing", 0},
    {"crs:RawFileName", 0},
    {"crs:RedHue", 0},
    {"crs:RedSaturation", 0},
    {"crs:Saturation", 0},
    {"crs:Shadows", 0},
    {"crs:ShadowTint", 0},
    {"crs:Sharpness", 0},
    {"crs:Temperature", 0},
    {"crs:Tint", 0},
    {"crs:ToneCurve", 0},
    {"crs:ToneCurveName", 0},
    {"crs:Version", 0},
    {"crs:VignetteAmount", 0},
    {"crs:VignetteMidpoint", 0},
    {"crs:WhiteBalance", 0},
    {"GPano:UsePanoramaViewer", XmpTag::kTrueFalse},
    {"GPano:CaptureSoftware", 0},
    {"GPano:StitchingSoftware", 0},
    {"GPano:ProjectionType", 0},
    {"GPano:PoseHeadingDegrees", 0},
    {"GPano:PosePitchDegrees", 0},
    {"GPano:PoseRollDegrees", 0},
    {"GPano:InitialViewHeadingDegrees", 0},
    {"GPano:InitialViewPitchDegrees", 0},
    {"GPano:InitialViewRollDegrees", 0},
    {"GPano:InitialHorizontalFOVDegrees", 0},
    {"GPano:FirstPhotoDate", 0},
    {"GPano:LastPhotoDate", 0},
    {"GPano:SourcePhotosCount", 0},
    {"GPano:ExposureLockUsed", XmpTag::kTrueFalse},
    {"GPano:CroppedAreaImageWidthPixels", 0},
    {"GPano:CroppedAreaImageHeightPixels", 0},
    {"GPano:FullPanoWidthPixels", 0},
    {"GPano:FullPanoHeightPixels", 0},
    {"GPano:CroppedAreaLeftPixels", 0},
    {"GPano:CroppedAreaTopPixels", 0},
    {"GPano:InitialCameraDolly", 0},
    {"GPano:LargestValidInteriorRectWidth", 0},
    {"GPano:LargestValidInteriorRectHeight", 0},
    {"GPano:LargestValidInteriorRectTop", 0},
    {"GPano:LargestValidInteriorRectLeft", 0},
};

// photoshop: first, then GPano: and crs:, as OpenImageIO orders the namespaces it writes
// (those between them never have a property here).
const XmpNamespace kNamespaces[] = {
    {"photoshop", "http://ns.adobe.com/photoshop/1.0/"},
    {"GPano", "http://ns.google.com/photos/1.0/panorama/"},
    {"crs", "http://ns.adobe.com/camera-raw-settings/1.0/"},
};

}  // namespace

std::span<const XmpTag> xmpTags() { return kTags; }

std::span<const XmpNamespace> xmpNamespaces() { return kNamespaces; }

}  // namespace ddt
