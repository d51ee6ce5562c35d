#include "volume_stack.h"

#include <algorithm>
#include <filesystem>

#include "codec_module.h"
#include "image_file.h"
#include "image_formats.h"
#include "user_error.h"

namespace ddt {

namespace {

namespace fs = std::filesystem;

// The value scale of a slice's samples: integer levels for 8 and 16 bits (read as [0, 1]).
float levelsOf(SampleType type) {
    return type == SampleType::UInt8 ? 255.0f : type == SampleType::UInt16 ? 65535.0f : 1.0f;
}

VoxelType voxelTypeOf(SampleType type) {
    return type == SampleType::UInt8 ? VoxelType::u8 : type == SampleType::UInt16 ? VoxelType::u16 : VoxelType::f32;
}

// Appends a slice's values, checking it against the first.
void addSlice(Volume& volume, SampleType& first_type, const std::string& name, uint32_t width, uint32_t height,
              uint32_t channels, SampleType type, const std::vector<float>& pixels) {
    if (channels != 1) throw UserError(name + ": has " + std::to_string(channels) + " channels; a volume's slices must be grey");
    if (volume.values.empty()) {
        volume.size = {width, height, 0};
        first_type = type;
    } else if (width != volume.size[0] || height != volume.size[1]) {
        throw UserError(name + ": is " + std::to_string(width) + "×" + std::to_string(height) + ", the first slice " +
                        std::to_string(volume.size[0]) + "×" + std::to_string(volume.size[1]));
    } else if (type != first_type) {
        throw UserError(name + ": has " + sampleTypeName(type) + " samples, the first slice " + sampleTypeName(first_type));
    }
    const float scale = levelsOf(type);
    for (float v : pixels) volume.values.push_back(v * scale);
    ++volume.size[2];
}

// The pages of a multi-page TIFF, through OpenImageIO's TIFF reader.
void readTiffPages(const std::string& path, Volume& volume) {
    const std::unique_ptr<CodecInput> input = codecModule().openInput(path, path, *formatOfExtension("tif"));
    SampleType first_type = SampleType::UInt8;
    for (uint32_t page = 0; page == 0 || input->seekImage(page); ++page) {
        const StoredImage& stored = input->stored();
        const std::string name = path + " page " + std::to_string(page + 1);
        if (uint64_t(stored.width) * stored.height * (page + 1) > kMaxVolumeVoxels)
            throw UserError(path + ": more than " + std::to_string(kMaxVolumeVoxels) + " voxels");
        std::vector<float> pixels(size_t(stored.width) * stored.height * stored.channels);
        input->decode(SampleType::Float, pixels.data());
        addSlice(volume, first_type, name, stored.width, stored.height, stored.channels, stored.sample_type, pixels);
    }
    volume.type = voxelTypeOf(first_type);
}

void readFolder(const std::string& path, Volume& volume) {
    std::vector<fs::path> files;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(path, error)) {
        const fs::path& file = entry.path();
        if (!file.filename().string().starts_with(".") && entry.is_regular_file(error) &&
            formatOfExtension(file.extension().string()))
            files.push_back(file);
    }
    if (error) throw UserError(path + ": cannot list the folder: " + error.message());
    std::sort(files.begin(), files.end());
    SampleType first_type = SampleType::UInt8;
    for (const fs::path& file : files) {
        if (uint64_t(volume.size[0]) * volume.size[1] * (volume.size[2] + 1) > kMaxVolumeVoxels)
            throw UserError(path + ": more than " + std::to_string(kMaxVolumeVoxels) + " voxels");
        const Image slice = readImage(file.string());
        addSlice(volume, first_type, file.string(), slice.width, slice.height, slice.channels, slice.sample_type,
                 slice.pixels);
    }
    volume.type = voxelTypeOf(first_type);
}

}  // namespace

Volume readImageStack(const std::string& path) {
    Volume volume;
    std::error_code error;
    if (fs::is_directory(path, error)) {
        readFolder(path, volume);
    } else {
        const std::string extension = fs::path(path).extension().string();
        if (extension != ".tif" && extension != ".tiff" && extension != ".TIF" && extension != ".TIFF")
            throw UserError(path + ": --stack reads a folder of slices or a multi-page TIFF (.tif, .tiff)");
        if (!fs::exists(path, error)) throw UserError(path + ": no such file");
        readTiffPages(path, volume);
    }
    if (volume.size[2] < 2)
        throw UserError(path + ": has " + std::to_string(volume.size[2]) + " slice" + (volume.size[2] == 1 ? "" : "s") +
                        "; a volume needs at least 2");
    if (std::string problem = volumeSizeProblem(volume.size); !problem.empty()) throw UserError(path + ": " + problem);
    volume.index_to_world.m = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
    return volume;
}

}  // namespace ddt
