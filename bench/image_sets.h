// The bench's inputs: each folder given is one set (the paper's "real" and "artificial").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct ImageSet {
    std::string name;                // the folder's name, made unique
    std::vector<std::string> paths;  // its images, sorted by file name
};

// The images of each folder (by extension: PNG, JPEG, TIFF, BMP, EXR, PNM, WebP, TGA;
// subfolders are not searched). Throws UserError for a folder without images.
std::vector<ImageSet> findImageSets(const std::vector<std::string>& dirs);

struct ImageSize {
    uint32_t width = 0;
    uint32_t height = 0;
};

// The size in the image's header, without reading its pixels. Throws UserError if the file
// is not a readable image.
ImageSize imageSize(const std::string& path);

// The file name without folder and extension ("real/baboon.png" -> "baboon").
std::string imageName(const std::string& path);

}  // namespace bench
