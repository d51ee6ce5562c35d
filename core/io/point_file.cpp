// Point files: the format by extension, the file read whole, and the checks both parsers share.
#include "point_file.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace ddt {

namespace fs = std::filesystem;

namespace {

std::string lowercaseExtension(const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

// "" when `path` is a file the parsers may read, else the reason (as volume_file.cpp words it).
std::string inputFileProblem(const std::string& path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) return "no such file";
    if (fs::is_directory(status)) return "is a folder, not a point file";
    // Devices and pipes can feed a reader forever (/dev/zero) or block it.
    if (!fs::is_regular_file(status)) return "not a regular file";
    if (::access(path.c_str(), R_OK) != 0) return std::string("cannot open (") + std::strerror(errno) + ")";
    if (fs::file_size(path, ec) == 0 && !ec) return "empty file (0 bytes)";
    return "";
}

// The whole file. Both formats are parsed from memory: the PLY reader walks binary data by
// offset, and a file of kMaxPoints points is of the order of the arrays it fills.
std::string readWholeFile(const std::string& path) {
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) throw UserError(path + ": cannot open (" + std::strerror(errno) + ")");
    std::error_code ec;
    const uintmax_t expected = fs::file_size(path, ec);
    // Read straight into the string, to the size the file had, then on for a file that grew.
    std::string bytes(ec ? 0 : size_t(expected), '\0');
    size_t held = std::fread(bytes.data(), 1, bytes.size(), file.get());
    if (held == bytes.size() && !std::ferror(file.get())) {
        char piece[1 << 16];
        size_t read;
        while ((read = std::fread(piece, 1, sizeof(piece), file.get())) > 0) bytes.append(piece, read), held += read;
    }
    if (std::ferror(file.get())) throw UserError(path + ": cannot read (" + std::strerror(errno) + ")");
    bytes.resize(held);
    return bytes;
}

std::string numberText(double value) {
    char digits[32];
    const auto [end, error] = std::to_chars(digits, digits + sizeof(digits), value);
    return std::string(digits, end);
}

}  // namespace

bool isPointFilePath(const std::string& path) {
    const std::string extension = lowercaseExtension(path);
    return extension == ".csv" || extension == ".ply";
}

PointSamples readPointFile(const std::string& path) {
    if (!isPointFilePath(path)) throw UserError(path + ": not a point file (the extension must be .csv or .ply)");
    if (std::string problem = inputFileProblem(path); !problem.empty()) throw UserError(path + ": " + problem);
    const std::string bytes = readWholeFile(path);
    if (bytes.empty()) throw UserError(path + ": empty file (0 bytes)");
    return lowercaseExtension(path) == ".csv" ? parseCsvPoints(path, bytes) : parsePlyPoints(path, bytes);
}

std::string coordinateProblem(double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return "a coordinate is not finite (NaN or infinity)";
    // Points lie in the frame that starts at pixel centre 0 (the app checks the far sides).
    if (x < 0) return "negative coordinate x = " + numberText(x) + " (points must lie at x >= 0 and y >= 0)";
    if (y < 0) return "negative coordinate y = " + numberText(y) + " (points must lie at x >= 0 and y >= 0)";
    return "";
}

std::string colourProblem(double value, double largest) {
    if (!std::isfinite(value)) return "a colour value is not finite (NaN or infinity)";
    if (value < 0) return "negative colour value " + numberText(value);
    if (value > largest) return "colour value " + numberText(value) + " is above " + numberText(largest);
    return "";
}

}  // namespace ddt
