#include "codec_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <optional>
#include <stdexcept>

namespace ddt {

namespace {

namespace fs = std::filesystem;

const char kModuleFile[] = "ddtup-oiio.so";

std::mutex module_mutex;
CodecModule* loaded_module = nullptr;
std::optional<unsigned> codec_threads;

// Where the module may be: beside the program (the build folder), one folder up (the tests'
// and benches' programs in build/test and build/bench) and where `make install` puts it.
std::vector<fs::path> modulePlaces() {
    std::error_code error;
    const fs::path program = fs::read_symlink("/proc/self/exe", error);
    if (error) return {};
    const fs::path folder = program.parent_path();
    return {folder / kModuleFile, folder.parent_path() / kModuleFile, folder.parent_path() / "lib" / "ddtup" / kModuleFile};
}

CodecModule* load() {
    std::string tried;
    for (const fs::path& place : modulePlaces()) {
        std::error_code error;
        if (!fs::exists(place, error)) {
            tried += (tried.empty() ? "" : ", ") + place.string();
            continue;
        }
        // Never closed: the codecs' libraries keep threads and state until the process ends.
        void* handle = ::dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) throw std::runtime_error(std::string("cannot load OpenImageIO's codecs: ") + ::dlerror());
        auto entry = reinterpret_cast<CodecModule* (*)(const char*)>(::dlsym(handle, "ddtupCodecModule"));
        if (!entry) throw std::runtime_error(place.string() + " is not ddtup's codec module");
        CodecModule* module = entry(DDTUP_CODEC_INTERFACE);
        if (!module) throw std::runtime_error(place.string() + " was built from another version of ddtup");
        return module;
    }
    throw std::runtime_error("OpenImageIO's codecs (" + std::string(kModuleFile) + ") are not installed; looked in " + tried);
}

}  // namespace

CodecModule& codecModule() {
    std::lock_guard lock(module_mutex);
    if (!loaded_module) {
        loaded_module = load();
        if (codec_threads) loaded_module->setThreads(*codec_threads);
    }
    return *loaded_module;
}

void setCodecThreads(unsigned count) {
    std::lock_guard lock(module_mutex);
    codec_threads = count;
    if (loaded_module) loaded_module->setThreads(count);
}

}  // namespace ddt
