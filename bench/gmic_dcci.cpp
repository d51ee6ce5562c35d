#include "gmic_dcci.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "temp_files.h"

namespace bench {

namespace {

namespace fs = std::filesystem;

// A private folder for one run's files, removed with them.
class TempFolder {
public:
    TempFolder() {
        std::string pattern = ddt::tempFolder() + "/ddtup-bench-gmic-XXXXXX";
        if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder for gmic");
        path_ = pattern;
    }
    ~TempFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    std::string file(const char* name) const { return path_ + "/" + name; }

private:
    std::string path_;
};

// For the shell: the paths are our temporary folder's, which hold no single quote unless $TMPDIR does.
std::string quoted(const std::string& path) { return "'" + path + "'"; }

bool runQuietly(const std::string& command) { return std::system((command + " >/dev/null 2>&1").c_str()) == 0; }

ddt::Image horizontalRamp(uint32_t side) {
    ddt::Image image;
    image.width = image.height = side;
    image.channels = 1;
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) image.pixels.push_back(float(8 * x) / 255.0f);  // 8 levels a pixel
    return image;
}

}  // namespace

std::string dcciUnavailableReason() {
    if (!runQuietly("command -v gmic")) return "G'MIC's `gmic` command is not installed";
    if (!runQuietly("gmic 8,8,1,3 dcci2x")) return "this G'MIC has no `dcci2x` command (Debian 12's 2.9.4 has none)";
    return "";
}

ddt::Image magnifyWithDcci(const ddt::Image& input) {
    const TempFolder folder;
    const std::string in = folder.file("in.png"), out = folder.file("out.png");
    ddt::writeImage(in, input);
    if (!runQuietly("gmic " + quoted(in) + " dcci2x cut 0,255 o " + quoted(out)))
        throw std::runtime_error("gmic dcci2x failed on " + in);
    ddt::Image result = ddt::readImage(out);
    if (result.width != 2 * input.width || result.height != 2 * input.height || result.channels != input.channels)
        throw std::runtime_error("gmic dcci2x: unexpected output size or channels");
    return result;
}

double dcciMisalignment() {
    const uint32_t side = 32, margin = 4;
    const ddt::Image out = magnifyWithDcci(horizontalRamp(side));
    double total = 0.0;
    uint32_t count = 0;
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            const double expected = (x + 0.5) / 2.0 - 0.5;
            if (expected < margin || expected > side - 1 - margin) continue;
            total += out.pixels[size_t(y) * out.width + x] * 255.0 / 8.0 - expected;
            ++count;
        }
    return total / count;
}

}  // namespace bench
