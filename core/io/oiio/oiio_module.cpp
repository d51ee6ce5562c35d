// The entry of ddtup-oiio.so: OpenImageIO's codecs behind codec_module.h's CodecModule.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "codec_module.h"
#include "oiio_codec.h"
#include "oiio_input.h"
#include "oiio_metadata.h"
#include "oiio_output.h"

namespace ddt {

namespace {

// The float the codec makes of each code of `Code` (its conversion when asked for floats), so
// that unpacked codes equal a float read bit for bit.
template <class Code>
std::vector<float> valuesOf(OIIO::TypeDesc type) {
    std::vector<Code> codes(size_t(1) << (8 * sizeof(Code)));
    for (size_t code = 0; code < codes.size(); ++code) codes[code] = Code(code);
    std::vector<float> values(codes.size());
    OIIO::convert_pixel_values(type, codes.data(), OIIO::TypeDesc::FLOAT, values.data(), int(codes.size()));
    return values;
}

class OiioCodecModule final : public CodecModule {
public:
    std::unique_ptr<CodecInput> openInput(const std::string& file, const std::string& name,
                                          const ImageFormat& format) override {
        return openOiioInput(file, name, format);
    }

    bool writesAlpha(const ImageFormat& format) override { return oiioWritesAlpha(format); }

    std::unique_ptr<CodecOutput> openOutput(const OutputRequest& request, OutputLayout& layout) override {
        return openOiioOutput(request, layout);
    }

    std::vector<float> valuesOfCodes(SampleType codes) override {
        return codes == SampleType::UInt8 ? valuesOf<uint8_t>(OIIO::TypeDesc::UINT8) : valuesOf<uint16_t>(OIIO::TypeDesc::UINT16);
    }

    // Not ImageBufAlgo::reorient: OIIO 2.4 swaps 5 and 7 there (OpenImageIO issue #4661).
    void makeUpright(void* samples, SampleType type, uint32_t upright_width, uint32_t upright_height, uint32_t channels,
                     int orientation) override {
        namespace iba = OIIO::ImageBufAlgo;
        const bool swapped = orientation >= 5 && orientation <= 8;
        const OIIO::TypeDesc type_desc = typeDescOf(type);
        const OIIO::ImageSpec stored_spec(int(swapped ? upright_height : upright_width),
                                          int(swapped ? upright_width : upright_height), int(channels), type_desc);
        const OIIO::ImageBuf stored(stored_spec, samples);
        OIIO::ImageBuf upright, half_turned;
        bool ok = false;
        switch (orientation) {
            case 2: ok = iba::flop(upright, stored); break;        // mirrored left to right
            case 3: ok = iba::rotate180(upright, stored); break;
            case 4: ok = iba::flip(upright, stored); break;        // mirrored top to bottom
            case 5: ok = iba::transpose(upright, stored); break;   // mirrored across the main diagonal
            case 6: ok = iba::rotate90(upright, stored); break;    // clockwise
            case 7: ok = iba::rotate180(half_turned, stored) && iba::transpose(upright, half_turned); break;
            case 8: ok = iba::rotate270(upright, stored); break;
        }
        if (!ok) throw std::runtime_error("orienting the image: " + upright.geterror());
        upright.get_pixels(OIIO::ROI::All(), type_desc, samples);
    }

    void setThreads(unsigned count) override { OIIO::attribute("threads", int(count)); }
};

}  // namespace

}  // namespace ddt

// What codec_module.cpp looks up after loading the module.
extern "C" __attribute__((visibility("default"))) ddt::CodecModule* ddtupCodecModule() {
    static ddt::OiioCodecModule module;
    return &module;
}
