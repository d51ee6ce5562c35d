// The bench's inputs: each folder given is one set (the paper's "real" and "artificial").
#pragma once

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

// The file name without folder and extension ("real/baboon.png" -> "baboon").
std::string imageName(const std::string& path);

}  // namespace bench
