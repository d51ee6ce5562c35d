#include "image_sets.h"

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <filesystem>

#include "user_error.h"

namespace bench {

namespace {

namespace fs = std::filesystem;

bool hasImageExtension(const fs::path& path) {
    const std::string ext = OIIO::Strutil::lower(path.extension().string());
    for (const char* known :
         {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".exr", ".ppm", ".pgm", ".pnm", ".webp", ".tga"})
        if (ext == known) return true;
    return false;
}

std::string setNameOf(const std::string& dir) {
    fs::path path = fs::path(dir).lexically_normal();
    if (path.filename().empty()) path = path.parent_path();
    std::string name = path.filename().string();
    return name.empty() || name == "." ? "set" : name;
}

}  // namespace

std::vector<ImageSet> findImageSets(const std::vector<std::string>& dirs) {
    std::vector<ImageSet> sets;
    for (const std::string& dir : dirs) {
        ImageSet set;
        set.name = setNameOf(dir);
        // Two folders of the same name (a/real, b/real) still need distinct table rows.
        for (int suffix = 2;
             std::any_of(sets.begin(), sets.end(), [&](const ImageSet& s) { return s.name == set.name; }); ++suffix)
            set.name = setNameOf(dir) + "-" + std::to_string(suffix);
        std::error_code ec;
        for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec))
            if (entry.is_regular_file() && hasImageExtension(entry.path())) set.paths.push_back(entry.path().string());
        if (ec) throw ddt::UserError(dir + ": cannot list the folder (" + ec.message() + ")");
        if (set.paths.empty()) throw ddt::UserError(dir + ": no images in this folder");
        std::sort(set.paths.begin(), set.paths.end());
        sets.push_back(std::move(set));
    }
    return sets;
}

ImageSize imageSize(const std::string& path) {
    auto input = OIIO::ImageInput::open(path);
    if (!input) throw ddt::UserError(path + ": not a readable image (" + OIIO::geterror() + ")");
    return {uint32_t(input->spec().width), uint32_t(input->spec().height)};
}

std::string imageName(const std::string& path) { return fs::path(path).stem().string(); }

}  // namespace bench
