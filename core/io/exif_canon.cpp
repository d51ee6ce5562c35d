#include "exif_canon.h"

namespace ddt::exif {

namespace {

using enum FieldType;

const NamedIndex kCameraSettings[] = {
    {1, "Canon:MacroMode"},         {2, "Canon:SelfTimer"},          {3, "Canon:Quality"},
    {4, "Canon:FlashMode"},         {5, "Canon:ContinuousDrive"},    {7, "Canon:FocusMode"},
    {9, "Canon:RecordMode"},        {10, "Canon:ImageSize"},         {11, "Canon:EasyMode"},
    {12, "Canon:DigitalZoom"},      {13, "Canon:Contrast"},          {14, "Canon:Saturation"},
    {15, "Canon:Sharpness"},        {16, "Canon:CameraISO"},         {17, "Canon:MeteringMode"},
    {18, "Canon:FocusRange"},       {19, "Canon:AFPoint"},           {20, "Canon:ExposureMode"},
    {22, "Canon:LensType"},         {23, "Canon:MaxFocalLength"},    {24, "Canon:MinFocalLength"},
    {25, "Canon:FocalUnits"},       {26, "Canon:MaxAperture"},       {27, "Canon:MinAperture"},
    {28, "Canon:FlashActivity"},    {29, "Canon:FlashBits"},         {32, "Canon:FocusContinuous"},
    {33, "Canon:AESetting"},        {34, "Canon:ImageStabilization"}, {35, "Canon:DisplayAperture"},
    {36, "Canon:ZoomSourceWidth"},  {37, "Canon:ZoomTargetWidth"},   {39, "Canon:SpotMeteringMode"},
    {40, "Canon:PhotoEffect"},      {41, "Canon:ManualFlashOutput"}, {42, "Canon:ColorTone"},
    {46, "Canon:SRAWQuality"},
};
const NamedIndex kFocalLength[] = {
    {0, "Canon:FocalType"}, {1, "Canon:FocalLength"}, {2, "Canon:FocalPlaneXSize"}, {3, "Canon:FocalPlaneYSize"},
};
const NamedIndex kShotInfo[] = {
    {1, "Canon:AutoISO"},              {2, "Canon:BaseISO"},            {3, "Canon:MeasuredEV"},
    {4, "Canon:TargetAperture"},       {5, "Canon:TargetExposureTime"}, {6, "Canon:ExposureCompensation"},
    {7, "Canon:WhiteBalance"},         {8, "Canon:SlowShutter"},        {9, "Canon:SequenceNumber"},
    {10, "Canon:OpticalZoomCode"},     {12, "Canon:CameraTemperature"}, {13, "Canon:FlashGuideNumber"},
    {14, "Canon:AFPointsInFocus"},     {15, "Canon:ExposureComp"},      {16, "Canon:FlashExposureComp"},
    {17, "Canon:AutoExposureBracketing"}, {18, "Canon:AEBBracketValue"}, {19, "Canon:ControlMode"},
    {20, "Canon:FocusDistanceUpper"},  {21, "Canon:FocusDistanceLower"}, {22, "Canon:FNumber"},
    {23, "Canon:ExposureTime"},        {24, "Canon:MeasuredEV2"},       {25, "Canon:BulbDuration"},
    {26, "Canon:CameraType"},          {27, "Canon:AutoRotate"},        {28, "Canon:NDFilter"},
    {29, "Canon:SelfTimer2"},          {33, "Canon:FlashOutput"},
};
const NamedIndex kPanorama[] = {{2, "Canon:PanoramaFrameNumber"}, {5, "Canon:PanoramaDirection"}};
const NamedIndex kSensorInfo[] = {
    {1, "Canon:SensorWidth"},         {2, "Canon:SensorHeight"},         {5, "Canon:SensorLeftBorder"},
    {6, "Canon:SensorTopBorder"},     {7, "Canon:SensorRightBorder"},    {8, "Canon:SensorBottomBorder"},
    {9, "Canon:BlackMaskLeftBorder"}, {10, "Canon:BlackMaskTopBorder"},  {11, "Canon:BlackMaskRightBorder"},
    {12, "Canon:BlackMaskBottomBorder"},
};

const CanonArray kCameraSettingsArray{0x0001, SShort, true, true, kCameraSettings};
const CanonArray kFocalLengthArray{0x0002, Short, false, false, kFocalLength};
const CanonArray kShotInfoArray{0x0004, SShort, true, false, kShotInfo};
const CanonArray kPanoramaArray{0x0005, SShort, true, false, kPanorama};
const CanonArray kSensorInfoArray{0x00E0, Short, false, false, kSensorInfo};  // read, never written

const Tag kCanonTags[] = {
    {0x0001, "Canon:CameraSettings", Short, 0, Reading::Indexed},
    {0x0002, "Canon:FocalLength", Short, 0, Reading::Indexed},
    {0x0004, "Canon:ShotInfo", Short, 0, Reading::Indexed},
    {0x0005, "Canon:Panorama", Short, 0, Reading::Indexed},
    {0x0006, "Canon:ImageType", Ascii, 0},
    {0x0007, "Canon:FirmwareVersion", Ascii, 1},
    {0x0008, "Canon:FileNumber", Long, 1},
    {0x0009, "Canon:OwnerName", Ascii, 0},
    {0x000C, "Canon:SerialNumber", Long, 1},
    {0x0010, "Canon:ModelID", Long, 1},
    {0x0013, "Canon:ThumbnailImageValidArea", Long, 4},
    {0x0015, "Canon:SerialNumberFormat", Long, 1},
    {0x001A, "Canon:SuperMacro", Short, 1},
    {0x001C, "Canon:DateStampMode", Short, 1},
    {0x001E, "Canon:FirmwareRevision", Long, 1},
    {0x0023, "Canon:Categories", Long, 2},
    {0x0028, "Canon:ImageUniqueID", Byte, 1},  // 16 bytes in the camera's note: OpenImageIO keeps none
    {0x0095, "Canon:LensModel", Ascii, 1},
    {0x0098, "Canon:CropInfo", Short, 4},
    {0x00AE, "Canon:ColorTemperature", Short, 1},
    {0x00E0, "Canon:SensorInfo", Short, 17, Reading::Indexed},
    {0x4010, "Canon:CustomPictureStyleFileName", Ascii, 1},
};

const CanonArray* const kWritten[] = {&kCameraSettingsArray, &kFocalLengthArray, &kShotInfoArray, &kShotInfoArray,
                                      &kPanoramaArray};

}  // namespace

std::span<const Tag> canonTags() { return kCanonTags; }

const CanonArray* findCanonArray(uint16_t number) {
    for (const CanonArray* array : {&kCameraSettingsArray, &kFocalLengthArray, &kShotInfoArray, &kPanoramaArray, &kSensorInfoArray})
        if (array->number == number) return array;
    return nullptr;
}

std::span<const CanonArray* const> canonArraysWritten() { return kWritten; }

}  // namespace ddt::exif
