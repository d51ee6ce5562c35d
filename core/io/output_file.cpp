#include "output_file.h"

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <system_error>

#include "image.h"

namespace ddt {

namespace fs = std::filesystem;

void checkOutputPath(const std::string& path) {
    std::error_code ec;
    const fs::path target(path);
    const fs::file_status status = fs::status(target, ec);  // through symlinks
    if (fs::is_directory(status)) throw UserError(path + ": is a folder");
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw UserError(path + ": not a regular file; refusing to replace it");
    if (fs::exists(status) && ::access(path.c_str(), W_OK) != 0)
        throw UserError(path + ": the file is read-only; refusing to replace it");
    const fs::path folder = target.parent_path();
    if (folder.empty() || fs::is_directory(folder, ec)) return;
    if (fs::exists(folder, ec)) throw UserError(path + ": " + folder.string() + " is not a folder");
    throw UserError(path + ": folder " + folder.string() + " does not exist");
}

std::unique_ptr<TempFile> createTempFile(const std::string& path) {
    const bool to_stdout = path == kStandardStream;
    const fs::path target(path);
    const std::string folder = to_stdout ? tempFolder()
                               : target.parent_path().empty() ? std::string(".")
                                                              : target.parent_path().string();
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, its bug 105329) about "." + name + ".ddtup".
    std::string prefix = to_stdout ? "ddtup-stdout" : ".";
    if (!to_stdout) prefix.append(target.filename().string()).append(".ddtup");
    try {
        return std::make_unique<TempFile>(folder, prefix);
    } catch (const std::system_error& error) {
        throw UserError(outputName(path) + ": cannot write in folder " + folder + " (" + std::strerror(error.code().value()) + ")");
    }
}

void moveIntoPlace(TempFile& temp, const std::string& path, const std::string& name) {
    std::error_code ec;
    fs::rename(temp.path(), path, ec);
    if (ec) throw UserError(name + ": cannot replace the file (" + ec.message() + ")");
    temp.release();
}

}  // namespace ddt
