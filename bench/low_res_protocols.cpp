#include "low_res_protocols.h"

#include <OpenImageIO/filter.h>

#include "area_average.h"
#include "camera_model.h"
#include "jpeg_roundtrip.h"
#include "protocol.h"

namespace bench {

namespace {

const Magnification kTwo{2, 1}, kTwoAndAHalf{5, 2}, kFour{4, 1}, kEight{8, 1};

}  // namespace

std::vector<Protocol> benchProtocols(const std::string& held_back_filter, bool quick) {
    const std::vector<Magnification> all = quick ? std::vector<Magnification>{kTwoAndAHalf, kFour}
                                                 : std::vector<Magnification>{kTwo, kTwoAndAHalf, kFour, kEight};
    const std::vector<Magnification> jpeg = quick ? std::vector<Magnification>{kFour}
                                                  : std::vector<Magnification>{kTwo, kFour, kEight};
    std::vector<Protocol> protocols = {
        {"A", "bilinear halvings, the paper's", ProtocolKind::Halvings, "", all},
        {"B", "exact area averaging", ProtocolKind::AreaAverage, "", all},
        {"A+JPEG85", "A, then JPEG quality 85", ProtocolKind::Jpeg, "", jpeg},
        {"bicubic", "one bicubic (Catmull-Rom) resize", ProtocolKind::OiioResize, "catmull-rom", jpeg},
        {"camera", "Gaussian blur 0.4·f, sampling, noise 1/255", ProtocolKind::Camera, "", jpeg},
    };
    if (!held_back_filter.empty())
        protocols.push_back({"C", "one OIIO " + held_back_filter + " resize, held back",
                             ProtocolKind::OiioResize, held_back_filter, all});
    return protocols;
}

std::string describeProtocol(const Protocol& p) {
    switch (p.kind) {
    case ProtocolKind::Halvings:
        return "log2(f) halvings with OIIO `triangle` in float (×2.5: one `triangle` resize by 1/2.5), rounded to "
               "8 bits once";
    case ProtocolKind::AreaAverage:
        return "each low-resolution pixel is the mean of the f × f original pixels of its footprint (×2.5: "
               "pixels the 2.5 × 2.5 footprint cuts count with the covered fraction), in double, rounded to 8 bits "
               "once";
    case ProtocolKind::Jpeg:
        return "protocol A's 8-bit image stored as JPEG of quality " + std::to_string(kProtocolJpegQuality) +
               " (core's writer through OIIO and libjpeg, their default chroma subsampling) and read back";
    case ProtocolKind::Camera:
        return "a Gaussian blur of σ = 0.4·f original pixels sampled at each low-resolution pixel's centre, then "
               "Gaussian noise of σ = 1/255 (fixed seed), in double, rounded to 8 bits once";
    case ProtocolKind::OiioResize:
        return "one OIIO `" + p.filter + "` resize by 1/f at the filter's default width, in float, rounded to 8 "
               "bits once";
    }
    return "";
}

ddt::Image cropForFactor(const ddt::Image& original, Magnification factor) {
    return cropToMultiple(original, factor.numerator);
}

ddt::Image protocolLowRes(const Protocol& protocol, const ddt::Image& cropped, Magnification factor) {
    const uint32_t low_w = factor.lowSide(cropped.width), low_h = factor.lowSide(cropped.height);
    switch (protocol.kind) {
    case ProtocolKind::Halvings:
        if (factor.integral()) return makeLowRes(cropped, factor.numerator);
        return roundedTo8Bit(resizeWithFilter(cropped, "triangle", low_w, low_h));
    case ProtocolKind::AreaAverage:
        return roundedTo8Bit(areaAverage(cropped, factor));
    case ProtocolKind::Jpeg: {
        Protocol halvings = protocol;
        halvings.kind = ProtocolKind::Halvings;
        return jpegRoundTrip(protocolLowRes(halvings, cropped, factor), kProtocolJpegQuality);
    }
    case ProtocolKind::OiioResize:
        return roundedTo8Bit(resizeWithFilter(cropped, protocol.filter, low_w, low_h));
    case ProtocolKind::Camera:
        return roundedTo8Bit(cameraCapture(cropped, factor));
    }
    return {};
}

bool isOiioFilter(const std::string& name) {
    for (int i = 0; i < OIIO::Filter2D::num_filters(); ++i)
        if (name == OIIO::Filter2D::get_filterdesc(i).name) return true;
    return false;
}

}  // namespace bench
