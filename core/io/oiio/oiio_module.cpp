// The entry of ddtup-oiio.so: OpenImageIO's codecs behind codec_module.h's CodecModule.
#include <OpenImageIO/imageio.h>

#include <cstring>

#include "codec_module.h"
#include "oiio_codec.h"
#include "oiio_input.h"
#include "oiio_output.h"

namespace ddt {

namespace {

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

    void setThreads(unsigned count) override { OIIO::attribute("threads", int(count)); }
};

}  // namespace

}  // namespace ddt

// What codec_module.cpp looks up after loading the module: the module, if `interface` is the
// hash of the interface headers it was built with (CMakeLists.txt), else null.
extern "C" __attribute__((visibility("default"))) ddt::CodecModule* ddtupCodecModule(const char* interface) {
    if (std::strcmp(interface, DDTUP_CODEC_INTERFACE) != 0) return nullptr;
    static ddt::OiioCodecModule module;
    return &module;
}
