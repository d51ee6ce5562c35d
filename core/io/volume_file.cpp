#include "volume_file.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>
#include <type_traits>

#include "output_file.h"
#include "volume_formats.h"

namespace ddt {

namespace fs = std::filesystem;

namespace {

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

// "" when `path` is a file the readers may open, else the reason (as image_reader.cpp words it).
std::string inputFileProblem(const std::string& path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) return "no such file";
    if (fs::is_directory(status)) return "is a folder, not a volume file";
    // Devices and pipes can feed a reader forever (/dev/zero) or block it.
    if (!fs::is_regular_file(status)) return "not a regular file";
    if (::access(path.c_str(), R_OK) != 0) return std::string("cannot open (") + std::strerror(errno) + ")";
    if (fs::file_size(path, ec) == 0 && !ec) return "empty file (0 bytes)";
    return "";
}

// The affine must place every voxel: finite, and no axis of zero length (the optimizer
// measures in the physical frame, core/volume/volume.h).
std::string affineProblem(const Affine& affine) {
    for (const auto& row : affine.m)
        for (double value : row)
            if (!std::isfinite(value)) return "the index-to-world transform has a value that is not finite";
    const std::array<double, 3> spacing = spacingOf(affine);
    for (int a = 0; a < 3; ++a)
        if (!(spacing[a] > 0)) return "axis " + std::to_string(a) + " has zero length in the index-to-world transform";
    // Coplanar axes: the volume of a voxel, relative to the product of its sides, is about 0.
    const auto& m = affine.m;
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (std::fabs(det) <= 1e-9 * spacing[0] * spacing[1] * spacing[2])
        return "the index-to-world transform is singular (its axes are coplanar)";
    return "";
}

// Calls f(T{}) with the C++ type of `type`.
template <class F>
decltype(auto) withSampleType(VoxelType type, F&& f) {
    switch (type) {
        case VoxelType::u8: return f(uint8_t{});
        case VoxelType::i8: return f(int8_t{});
        case VoxelType::u16: return f(uint16_t{});
        case VoxelType::i16: return f(int16_t{});
        case VoxelType::f32: return f(float{});
        case VoxelType::f64: break;
    }
    return f(double{});
}

std::string voxelName(size_t index, const std::array<uint32_t, 3>& size) {
    const size_t x = index % size[0], y = index / size[0] % size[1], z = index / (size_t(size[0]) * size[1]);
    return "(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + ")";
}

}  // namespace

std::optional<VolumeFormat> volumeFormatOf(const std::string& path) {
    const std::string name = lowercase(fs::path(path).filename().string());
    auto endsWith = [&](const char* suffix) { return name.size() > std::strlen(suffix) && name.ends_with(suffix); };
    if (endsWith(".nrrd") || endsWith(".nhdr")) return VolumeFormat::Nrrd;
    if (endsWith(".nii") || endsWith(".nii.gz")) return VolumeFormat::Nifti;
    return std::nullopt;
}

std::string volumeExtensionNames() { return ".nrrd, .nhdr, .nii or .nii.gz"; }

std::string withoutVolumeExtension(const std::string& path) {
    const std::optional<VolumeFormat> format = volumeFormatOf(path);
    if (!format) return path;
    const bool gzipped = lowercase(path).ends_with(".gz");
    return path.substr(0, path.size() - (gzipped ? 7 : *format == VolumeFormat::Nrrd ? 5 : 4));
}

const char* voxelTypeName(VoxelType type) {
    switch (type) {
        case VoxelType::u8: return "uint8";
        case VoxelType::i8: return "int8";
        case VoxelType::u16: return "uint16";
        case VoxelType::i16: return "int16";
        case VoxelType::f32: return "float32";
        case VoxelType::f64: break;
    }
    return "float64";
}

Volume readVolume(const std::string& path) {
    if (std::string problem = inputFileProblem(path); !problem.empty()) throw UserError(path + ": " + problem);
    const std::optional<VolumeFormat> format = volumeFormatOf(path);
    if (!format) throw UserError(path + ": not a volume file (the extension must be " + volumeExtensionNames() + ")");
    Volume volume = *format == VolumeFormat::Nrrd ? readNrrd(path) : readNifti(path);
    if (std::string problem = affineProblem(volume.index_to_world); !problem.empty()) throw UserError(path + ": " + problem);
    return volume;
}

std::string volumeOutputProblem(const std::string& path, const std::array<uint32_t, 3>& size) {
    if (!volumeFormatOf(path)) return std::string("not a volume file name (the extension must be ") + volumeExtensionNames() + ")";
    if (std::string problem = volumeSizeProblem(size); !problem.empty()) return problem;
    try {
        checkOutputPath(path);
    } catch (const UserError& error) {
        const std::string message = error.what();
        return message.starts_with(path + ": ") ? message.substr(path.size() + 2) : message;
    }
    return "";
}

std::vector<std::string> writeVolume(const std::string& path, const Volume& volume, VoxelType type) {
    const std::optional<VolumeFormat> format = volumeFormatOf(path);
    if (!format) throw UserError(path + ": not a volume file name (the extension must be " + volumeExtensionNames() + ")");
    if (std::string problem = volumeSizeProblem(volume.size); !problem.empty()) throw UserError(path + ": " + problem);
    if (volume.values.size() != volume.voxelCount())
        throw std::invalid_argument("writeVolume: " + std::to_string(volume.values.size()) + " values for " +
                                    std::to_string(volume.voxelCount()) + " voxels");
    refuseInputFile(path, volume);
    std::vector<std::string> notes;
    if (*format == VolumeFormat::Nrrd) writeNrrd(path, volume, type, notes);
    else writeNifti(path, volume, type, notes);
    return notes;
}

void refuseInputFile(const std::string& output, const Volume& volume) {
    if (!volume.metadata) return;
    std::error_code ec;
    for (const std::string& input : volume.metadata->files)
        if (fs::equivalent(output, input, ec)) throw UserError(output + ": is the input file; refusing to overwrite it");
}

// ---- Samples.

size_t sampleSize(VoxelType type) {
    return withSampleType(type, [](auto sample) { return sizeof(sample); });
}

std::vector<float> physicalValues(const std::string& name, const void* data, VoxelType type,
                                  const std::array<uint32_t, 3>& size, double slope, double inter) {
    const size_t count = size_t(size[0]) * size[1] * size[2];
    std::vector<float> values(count);
    const bool scaled = slope != 0;
    withSampleType(type, [&](auto sample) {
        using T = decltype(sample);
        const T* raw = static_cast<const T*>(data);
        for (size_t i = 0; i < count; ++i) values[i] = scaled ? float(double(raw[i]) * slope + inter) : float(raw[i]);
    });
    // One pass for the rare failure, after the fast conversion.
    const auto bad = std::find_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); });
    if (bad != values.end()) {
        const size_t index = size_t(bad - values.begin());
        double raw = 0;
        withSampleType(type, [&](auto sample) { raw = double(static_cast<const decltype(sample)*>(data)[index]); });
        const std::string what = std::isnan(raw) ? "NaN" : std::isinf(raw) ? "infinite" : "beyond float's range once scaled";
        throw UserError(name + ": voxel " + voxelName(index, size) + " is " + what +
                        "; ddtup refuses samples that are not finite (interpolation would spread them)");
    }
    return values;
}

StoredSamples storedSamples(const std::vector<float>& values, VoxelType type, double slope, double inter) {
    StoredSamples stored;
    stored.bytes.resize(values.size() * sampleSize(type));
    withSampleType(type, [&](auto sample) {
        using T = decltype(sample);
        T* out = reinterpret_cast<T*>(stored.bytes.data());
        const bool scaled = slope != 0;
        if constexpr (std::is_floating_point_v<T>) {
            for (size_t i = 0; i < values.size(); ++i)
                out[i] = scaled ? T((double(values[i]) - inter) / slope) : T(values[i]);
        } else {
            constexpr double lo = std::numeric_limits<T>::min(), hi = std::numeric_limits<T>::max();
            uint64_t clamped = 0;
            for (size_t i = 0; i < values.size(); ++i) {
                double raw = std::nearbyint(scaled ? (double(values[i]) - inter) / slope : double(values[i]));
                if (std::isnan(raw)) raw = 0;  // values are never NaN (physicalValues); stay defined anyway
                if (raw < lo || raw > hi) {
                    ++clamped;
                    raw = raw < lo ? lo : hi;
                }
                out[i] = T(raw);
            }
            stored.clamped = clamped;
        }
    });
    return stored;
}

void noteClamped(const std::string& path, const StoredSamples& samples, VoxelType type, std::vector<std::string>& notes) {
    if (samples.clamped == 0) return;
    notes.push_back(path + ": " + std::to_string(samples.clamped) + (samples.clamped == 1 ? " sample was" : " samples were") +
                    " clamped to the " + voxelTypeName(type) + " range");
}

// ---- Geometry.

Affine convertFrame(const Affine& affine, WorldFrame from, WorldFrame to) {
    if (from == to || from == WorldFrame::Other || to == WorldFrame::Other) return affine;
    // Which of x and y point the other way than in RAS.
    auto flips = [](WorldFrame frame) { return std::array<bool, 2>{frame != WorldFrame::Ras, frame == WorldFrame::Lps}; };
    const std::array<bool, 2> a = flips(from), b = flips(to);
    Affine result = affine;
    for (int r = 0; r < 2; ++r)
        if (a[r] != b[r])
            for (double& value : result.m[r]) value = -value + 0.0;  // + 0: no −0 for 0 (NRRD would print "-0")
    return result;
}

Affine followIndexMap(const Affine& other, const Affine& input, const Affine& output) {
    // M = input⁻¹ · output, in 4 × 4 homogeneous form: L⁻¹ L_out and L⁻¹ (t_out − t_in).
    const auto& m = input.m;
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!std::isfinite(det) || det == 0) return other;
    double inverse[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            // Cofactor of (c, r) over det: the adjugate's transpose.
            const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            inverse[r][c] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
        }
    double map[3][4];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            double sum = 0;
            for (int k = 0; k < 3; ++k) sum += inverse[r][k] * (output.m[k][c] - (c == 3 ? m[k][3] : 0.0));
            map[r][c] = sum;
        }
    Affine result;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            double sum = c == 3 ? other.m[r][3] : 0.0;
            for (int k = 0; k < 3; ++k) sum += other.m[r][k] * map[k][c];
            result.m[r][c] = sum;
        }
    return result;
}

bool hasOrthogonalAxes(const Affine& affine) {
    const std::array<double, 3> length = spacingOf(affine);
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b) {
            double dot = 0;
            for (int r = 0; r < 3; ++r) dot += affine.m[r][a] * affine.m[r][b];
            if (std::fabs(dot) > 1e-6 * length[a] * length[b]) return false;
        }
    return true;
}

// ---- Output.

namespace {

// The stdio stream's writes, into the CheckedFile (glibc's fopencookie: 0 means failure).
ssize_t writeToCheckedFile(void* cookie, const char* data, size_t size) {
    CheckedFile* file = static_cast<CheckedFile*>(cookie);
    return file->failure() ? 0 : ssize_t(file->write(data, size));
}

}  // namespace

VolumeOutputFile::VolumeOutputFile(const std::string& path) : path_(path) {
    checkOutputPath(path);
    temp_ = createTempFile(path);
    try {
        file_ = std::make_unique<CheckedFile>(temp_->path());
    } catch (const std::system_error& error) {
        throw UserError(path + ": cannot write (" + std::strerror(error.code().value()) + ")");
    }
    cookie_io_functions_t functions{};
    functions.write = writeToCheckedFile;
    stream_ = ::fopencookie(file_.get(), "w", functions);
    if (!stream_) throw UserError(path + ": cannot write (" + std::strerror(errno) + ")");
    // Teem and zlib write in pieces of a few KiB: fewer, larger writes.
    std::setvbuf(stream_, nullptr, _IOFBF, size_t(1) << 20);
}

VolumeOutputFile::~VolumeOutputFile() {
    if (stream_) std::fclose(stream_);
}

void VolumeOutputFile::commit() {
    const bool flushed = std::fflush(stream_) == 0;
    std::fclose(stream_);
    stream_ = nullptr;
    file_->close();
    if (file_->failure()) throw UserError(path_ + ": " + std::strerror(file_->failure()));
    if (!flushed) throw UserError(path_ + ": cannot write (" + std::strerror(errno) + ")");
    moveIntoPlace(*temp_, path_, path_);
}

UserError VolumeOutputFile::failure(const std::string& what) {
    if (stream_) std::fflush(stream_);
    if (file_->failure()) return UserError(path_ + ": " + std::strerror(file_->failure()));
    return UserError(path_ + ": cannot write (" + what + ")");
}

}  // namespace ddt
