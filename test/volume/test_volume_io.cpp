// Volume files (core/io/volume_file.h, volume_slices.h): NRRD and NIfTI round trips of every
// sample type, NIfTI scaling, geometry kept through resampling and format conversion, bad
// inputs refused with one line naming the file, and the middle-slice previews.
// Inputs are written here by hand (NRRD headers as text, NIfTI-1 headers at the standard's
// byte offsets), and outputs are checked in their bytes where the numbers matter, so that
// the reader under test is not the only judge of the writer.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "temp_folder.h"
#include "user_error.h"
#include "volume.h"
#include "volume_file.h"
#include "volume_slices.h"

using ddt::Affine;
using ddt::VoxelType;
using ddt::Volume;

namespace {

using Bytes = std::vector<unsigned char>;

// ---- Files by hand.

void writeFile(const std::string& path, const std::string& text, const Bytes& data = {}) {
    std::ofstream file(path, std::ios::binary);
    file.write(text.data(), std::streamsize(text.size()));
    file.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size()));
    REQUIRE(file.good());
}

Bytes readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(file), {});
}

std::string readText(const std::string& path) {
    const Bytes bytes = readFile(path);
    return std::string(bytes.begin(), bytes.end());
}

// The whole content of a gzip file, through zlib.
Bytes gunzip(const std::string& path) {
    gzFile file = gzopen(path.c_str(), "rb");
    REQUIRE(file != nullptr);
    Bytes bytes;
    unsigned char buffer[4096];
    int n;
    while ((n = gzread(file, buffer, sizeof buffer)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
    gzclose(file);
    return bytes;
}

void gzipFile(const std::string& path, const Bytes& bytes) {
    gzFile file = gzopen(path.c_str(), "wb");
    REQUIRE(file != nullptr);
    REQUIRE(gzwrite(file, bytes.data(), unsigned(bytes.size())) == int(bytes.size()));
    gzclose(file);
}

// Values in the machine's byte order, little-endian on every machine ddtup builds for.
template <class T>
void put(Bytes& bytes, size_t offset, T value) {
    if (bytes.size() < offset + sizeof value) bytes.resize(offset + sizeof value);
    std::memcpy(&bytes[offset], &value, sizeof value);
}
template <class T>
T get(const Bytes& bytes, size_t offset) {
    T value{};
    REQUIRE(bytes.size() >= offset + sizeof value);
    std::memcpy(&value, &bytes[offset], sizeof value);
    return value;
}
template <class T>
Bytes bytesOf(const std::vector<T>& values) {
    Bytes bytes(values.size() * sizeof(T));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

// NIfTI-1 header fields: byte offsets from the standard (nifti1.h).
constexpr size_t kDim = 40, kIntentCode = 68, kDatatype = 70, kBitpix = 72, kPixdim = 76, kVoxOffset = 108,
                 kSclSlope = 112, kSclInter = 116, kXyztUnits = 123, kDescrip = 148, kQformCode = 252,
                 kSformCode = 254, kQuaternB = 256, kQoffsetX = 268, kSrowX = 280, kMagic = 344;
constexpr int16_t kUint8 = 2, kInt16 = 4, kInt32 = 8, kFloat32 = 16, kFloat64 = 64, kRgb24 = 128, kInt8 = 256,
                  kUint16 = 512;

// A single-file NIfTI-1 header with unit pixdims and no transform (codes 0), then the
// 4-byte extension flag: 352 bytes, the samples follow.
Bytes niftiHeader(std::vector<int16_t> dims, int16_t datatype, int16_t bitpix) {
    Bytes h(352, 0);
    put<int32_t>(h, 0, 348);
    put<int16_t>(h, kDim, int16_t(dims.size()));
    for (size_t d = 0; d < dims.size(); ++d) put<int16_t>(h, kDim + 2 * (d + 1), dims[d]);
    for (size_t d = dims.size() + 1; d < 8; ++d) put<int16_t>(h, kDim + 2 * d, 1);
    put<int16_t>(h, kDatatype, datatype);
    put<int16_t>(h, kBitpix, bitpix);
    for (int d = 0; d < 8; ++d) put<float>(h, kPixdim + 4 * d, 1.0f);
    put<float>(h, kVoxOffset, 352.0f);
    std::memcpy(&h[kMagic], "n+1", 4);
    return h;
}

// The header niftiHeader() makes, in big-endian byte order: every field it sets reversed.
void makeBigEndian(Bytes& h) {
    auto reverse = [&](size_t offset, size_t size) { std::reverse(h.begin() + long(offset), h.begin() + long(offset + size)); };
    reverse(0, 4);
    for (int d = 0; d < 8; ++d) reverse(kDim + 2 * d, 2);
    reverse(kDatatype, 2);
    reverse(kBitpix, 2);
    for (int d = 0; d < 8; ++d) reverse(kPixdim + 4 * d, 4);
    reverse(kVoxOffset, 4);
}

void setSform(Bytes& h, int16_t code, const double rows[3][4]) {
    put<int16_t>(h, kSformCode, code);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) put<float>(h, kSrowX + 16 * r + 4 * c, float(rows[r][c]));
}

// The sform rows a NIfTI-1 file holds.
Affine sformOf(const Bytes& h) {
    Affine a;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) a.m[r][c] = get<float>(h, kSrowX + 16 * r + 4 * c);
    return a;
}

// ---- Volumes in memory.

Volume makeVolume(std::array<uint32_t, 3> size, VoxelType type, std::vector<float> values, const Affine& affine) {
    Volume v;
    v.size = size;
    v.type = type;
    v.values = std::move(values);
    v.index_to_world = affine;
    return v;
}

Affine affineOf(const double rows[3][4]) {
    Affine a;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) a.m[r][c] = rows[r][c];
    return a;
}

// Spacing (0.5, 0.5, 2.5) at (10, 20, 30).
constexpr double kKnownRows[3][4] = {{0.5, 0, 0, 10}, {0, 0.5, 0, 20}, {0, 0, 2.5, 30}};
// Rotated by 30° about z: columns (0.5 cos 30°, 0.5 sin 30°, 0), (−0.25, 0.5 cos 30°, 0).
const double kCos30 = std::sqrt(3.0) / 2;
const double kObliqueRows[3][4] = {{0.5 * kCos30, -0.25, 0, -7}, {0.25, 0.5 * kCos30, 0, 3}, {0, 0, 2.5, 11}};

void requireAffine(const Affine& got, const double expected[3][4], double margin) {
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            INFO("row " << r << " column " << c << ": " << got.m[r][c] << " vs " << expected[r][c]);
            REQUIRE(got.m[r][c] == Approx(expected[r][c]).margin(margin));
        }
}

// 24 values a type holds exactly, with both ends of its range.
std::vector<float> levels(VoxelType type) {
    std::vector<float> v(24);
    for (int k = 0; k < 24; ++k) {
        switch (type) {
            case VoxelType::u8: v[k] = float(k * 11); break;
            case VoxelType::i8: v[k] = float(-128 + k * 11); break;
            case VoxelType::u16: v[k] = float(k * 2849); break;
            case VoxelType::i16: v[k] = float(-32768 + k * 2849); break;
            default: v[k] = float(k - 12) * 0.37f; break;
        }
    }
    const float top = type == VoxelType::u8 ? 255 : type == VoxelType::i8 ? 127 : type == VoxelType::u16 ? 65535
                    : type == VoxelType::i16 ? 32767 : 3e38f;
    v[5] = top;
    if (type == VoxelType::f32 || type == VoxelType::f64) v[6] = 1e-30f, v[7] = -3e38f;
    return v;
}

// The message of the UserError `f` throws; fails the test if it throws none.
template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const ddt::UserError& error) {
        return error.what();
    }
    FAIL("no UserError");
    return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Everything written to stderr (file descriptor 2) while it lives.
class CapturedStderr {
public:
    CapturedStderr() : path_(std::filesystem::temp_directory_path() / ("ddtup-stderr-" + std::to_string(::getpid()))) {
        std::fflush(stderr);
        saved_ = ::dup(2);
        const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        ::dup2(fd, 2);
        ::close(fd);
    }
    ~CapturedStderr() { restore(); std::filesystem::remove(path_); }
    std::string text() {
        restore();
        return readText(path_.string());
    }

private:
    void restore() {
        if (saved_ < 0) return;
        std::fflush(stderr);
        ::dup2(saved_, 2);
        ::close(saved_);
        saved_ = -1;
    }
    std::filesystem::path path_;
    int saved_ = -1;
};

// A little-endian short NRRD header with the given extra lines, sizes 4 3 2.
std::string nrrdHeader(const std::string& type, const std::string& extra, const std::string& sizes = "4 3 2",
                       const std::string& dimension = "3") {
    return "NRRD0004\ntype: " + type + "\ndimension: " + dimension + "\nsizes: " + sizes +
           "\nendian: little\nencoding: raw\n" + extra + "\n";
}

}  // namespace

TEST_CASE("volume io: isVolumePath knows the four extensions in any case", "[volume-io]") {
    CHECK(ddt::isVolumePath("a/b.nrrd"));
    CHECK(ddt::isVolumePath("B.NHDR"));
    CHECK(ddt::isVolumePath("head.nii"));
    CHECK(ddt::isVolumePath("head.Nii.Gz"));
    CHECK_FALSE(ddt::isVolumePath("head.gz"));
    CHECK_FALSE(ddt::isVolumePath("head.png"));
    CHECK_FALSE(ddt::isVolumePath(".nii"));
    CHECK(ddt::volumeFormatOf("x.nii.gz") == ddt::VolumeFormat::Nifti);
    CHECK(ddt::volumeFormatOf("x.nhdr") == ddt::VolumeFormat::Nrrd);
}

TEST_CASE("volume io: every sample type round-trips through NRRD and NIfTI exactly", "[volume-io]") {
    TempFolder folder;
    const VoxelType types[] = {VoxelType::u8, VoxelType::i8, VoxelType::u16, VoxelType::i16, VoxelType::f32, VoxelType::f64};
    const int16_t nifti_codes[] = {kUint8, kInt8, kUint16, kInt16, kFloat32, kFloat64};
    const char* nrrd_names[] = {"unsigned char", "signed char", "unsigned short", "short", "float", "double"};
    for (int t = 0; t < 6; ++t) {
        const Volume volume = makeVolume({4, 3, 2}, types[t], levels(types[t]), affineOf(kKnownRows));
        for (const std::string extension : {".nrrd", ".nhdr", ".nii", ".nii.gz"}) {
            const std::string path = folder / (std::string("v") + std::to_string(t) + extension);
            INFO(path);
            REQUIRE(ddt::writeVolume(path, volume, types[t]).empty());
            const Volume back = ddt::readVolume(path);
            CHECK(back.size == volume.size);
            CHECK(back.type == types[t]);
            REQUIRE(back.values.size() == 24);
            for (size_t i = 0; i < 24; ++i) {
                INFO("voxel " << i);
                CHECK(back.values[i] == volume.values[i]);
            }
            requireAffine(back.index_to_world, kKnownRows, 1e-6);
            REQUIRE(back.metadata);
            if (extension == ".nii") CHECK(get<int16_t>(readFile(path), kDatatype) == nifti_codes[t]);
            if (extension == ".nrrd") CHECK(contains(readText(path), std::string("type: ") + nrrd_names[t] + "\n"));
        }
    }
}

TEST_CASE("volume io: NIfTI scl_slope and scl_inter give physical values and are kept for integers", "[volume-io]") {
    TempFolder folder;
    // Raw int16 samples k − 2 (−2 … 21), slope 0.5, intercept −10: physical 0.5 (k − 2) − 10.
    std::vector<int16_t> raw(24);
    for (int k = 0; k < 24; ++k) raw[k] = int16_t(k - 2);
    Bytes header = niftiHeader({4, 3, 2}, kInt16, 16);
    put<float>(header, kSclSlope, 0.5f);
    put<float>(header, kSclInter, -10.0f);
    const std::string scaled = folder / "scaled.nii";
    writeFile(scaled, std::string(header.begin(), header.end()), bytesOf(raw));

    const Volume volume = ddt::readVolume(scaled);
    CHECK(volume.type == VoxelType::i16);
    for (int k = 0; k < 24; ++k) CHECK(volume.values[k] == 0.5f * float(k - 2) - 10.0f);

    SECTION("slope 0 means no scaling") {
        put<float>(header, kSclSlope, 0.0f);
        const std::string plain = folder / "plain.nii";
        writeFile(plain, std::string(header.begin(), header.end()), bytesOf(raw));
        const Volume unscaled = ddt::readVolume(plain);
        for (int k = 0; k < 24; ++k) CHECK(unscaled.values[k] == float(k - 2));
    }
    SECTION("an int16 output keeps the slope and intercept and stores the raw samples") {
        const std::string out = folder / "out.nii";
        ddt::writeVolume(out, volume, VoxelType::i16);
        const Bytes bytes = readFile(out);
        CHECK(get<float>(bytes, kSclSlope) == 0.5f);
        CHECK(get<float>(bytes, kSclInter) == -10.0f);
        const size_t offset = size_t(get<float>(bytes, kVoxOffset));
        for (int k = 0; k < 24; ++k) CHECK(get<int16_t>(bytes, offset + 2 * k) == k - 2);
        const Volume back = ddt::readVolume(out);
        CHECK(back.values == volume.values);
    }
    SECTION("a float output stores the physical values unscaled") {
        const std::string out = folder / "out.nii";
        ddt::writeVolume(out, volume, VoxelType::f32);
        const Bytes bytes = readFile(out);
        CHECK(get<float>(bytes, kSclSlope) == 1.0f);
        CHECK(get<float>(bytes, kSclInter) == 0.0f);
        const size_t offset = size_t(get<float>(bytes, kVoxOffset));
        for (int k = 0; k < 24; ++k) CHECK(get<float>(bytes, offset + 4 * k) == 0.5f * float(k - 2) - 10.0f);
    }
}

TEST_CASE("volume io: integer outputs are rounded to the nearest and clamped, with a note", "[volume-io]") {
    TempFolder folder;
    std::vector<float> values(24, 7.0f);
    values[0] = -3.0f;   // clamped to 0
    values[1] = 0.4f;    // 0
    values[2] = 0.6f;    // 1
    values[3] = 254.4f;  // 254
    values[4] = 300.0f;  // clamped to 255
    const Volume volume = makeVolume({4, 3, 2}, VoxelType::f32, values, affineOf(kKnownRows));
    const std::string out = folder / "rounded.nii";
    const std::vector<std::string> notes = ddt::writeVolume(out, volume, VoxelType::u8);
    REQUIRE(notes.size() == 1);
    CHECK(notes[0] == out + ": 2 samples were clamped to the uint8 range");
    const Bytes bytes = readFile(out);
    const uint8_t expected[6] = {0, 0, 1, 254, 255, 7};
    for (int k = 0; k < 6; ++k) CHECK(int(bytes[352 + k]) == int(expected[k]));
}

TEST_CASE("volume io: the geometry of a resampled 4×3×2 volume reaches the NRRD and NIfTI headers", "[volume-io]") {
    TempFolder folder;
    // 4×3×2, spacing (0.5, 0.5, 2.5) at (10, 20, 30), resampled to 8×6×5: spacing
    // (0.25, 0.25, 1) and origin (9.875, 19.875, 29.25) (test_volume_geometry.cpp works it out).
    const std::string input = folder / "in.nrrd";
    writeFile(input, nrrdHeader("short", "space: right-anterior-superior\nspace directions: (0.5,0,0) (0,0.5,0) (0,0,2.5)\n"
                                         "space origin: (10,20,30)\n"),
              Bytes(48, 0));
    const Volume in = ddt::readVolume(input);
    requireAffine(in.index_to_world, kKnownRows, 0);

    Volume out = in;
    out.size = {8, 6, 5};
    out.values.assign(out.voxelCount(), 1.0f);
    out.index_to_world = ddt::resampledAffine(in.index_to_world, in.size, out.size);

    const std::string nrrd = folder / "out.nrrd";
    ddt::writeVolume(nrrd, out, VoxelType::i16);
    const std::string text = readText(nrrd);
    INFO(text.substr(0, text.find("\n\n")));
    CHECK(contains(text, "sizes: 8 6 5\n"));
    CHECK(contains(text, "space: right-anterior-superior\n"));
    CHECK(contains(text, "space directions: (0.25,0,0) (0,0.25,0) (0,0,1)\n"));
    CHECK(contains(text, "space origin: (9.875,19.875,29.25)\n"));

    const std::string nifti = folder / "out.nii";
    ddt::writeVolume(nifti, out, VoxelType::i16);
    const Bytes h = readFile(nifti);
    CHECK(get<int16_t>(h, kDim + 2) == 8);
    CHECK(get<int16_t>(h, kDim + 6) == 5);
    CHECK(get<int16_t>(h, kSformCode) == 1);
    CHECK(get<int16_t>(h, kQformCode) == 1);
    const double expected[3][4] = {{0.25, 0, 0, 9.875}, {0, 0.25, 0, 19.875}, {0, 0, 1, 29.25}};
    requireAffine(sformOf(h), expected, 0);
    // The qform: no rotation (quaternion 0), the same offset, pixdims the spacings.
    for (int i = 0; i < 3; ++i) CHECK(get<float>(h, kQuaternB + 4 * i) == 0.0f);
    CHECK(get<float>(h, kQoffsetX) == 9.875f);
    CHECK(get<float>(h, kQoffsetX + 4) == 19.875f);
    CHECK(get<float>(h, kQoffsetX + 8) == 29.25f);
    CHECK(get<float>(h, kPixdim + 4) == 0.25f);
    CHECK(get<float>(h, kPixdim + 12) == 1.0f);
}

TEST_CASE("volume io: an oblique affine is carried through NRRD and NIfTI", "[volume-io]") {
    TempFolder folder;
    const Volume volume = makeVolume({4, 3, 2}, VoxelType::f32, levels(VoxelType::f32), affineOf(kObliqueRows));
    for (const std::string extension : {".nrrd", ".nii", ".nii.gz", ".nhdr"}) {
        const std::string path = folder / ("oblique" + extension);
        INFO(path);
        ddt::writeVolume(path, volume, VoxelType::f32);
        // NIfTI-1 holds the sform in float: 1e-6 of these numbers.
        requireAffine(ddt::readVolume(path).index_to_world, kObliqueRows, extension == ".nrrd" || extension == ".nhdr" ? 1e-12 : 1e-5);
    }
    // And from the bytes: the sform's first column is (0.5 cos 30°, 0.25, 0).
    const Bytes h = readFile(folder / "oblique.nii");
    CHECK(get<float>(h, kSrowX) == Approx(0.4330127));
    CHECK(get<float>(h, kSrowX + 16) == Approx(0.25));
}

TEST_CASE("volume io: a NIfTI's qform and sform are both moved by the resampling", "[volume-io]") {
    TempFolder folder;
    // qform (code 1): no rotation, pixdims 2, offset (−5, −5, −5). sform (code 2), a different
    // transform: columns (0, 2, 0), (−2, 0, 0), (0, 0, 2) at (100, 50, 10).
    Bytes h = niftiHeader({4, 3, 2}, kUint8, 8);
    put<int16_t>(h, kQformCode, 1);
    for (int d = 1; d <= 3; ++d) put<float>(h, kPixdim + 4 * d, 2.0f);
    for (int i = 0; i < 3; ++i) put<float>(h, kQoffsetX + 4 * i, -5.0f);
    const double sform[3][4] = {{0, -2, 0, 100}, {2, 0, 0, 50}, {0, 0, 2, 10}};
    setSform(h, 2, sform);
    put<char>(h, kXyztUnits, 2 | 8);  // mm, seconds
    std::memcpy(&h[kDescrip], "two transforms", 15);
    const std::string input = folder / "two.nii";
    writeFile(input, std::string(h.begin(), h.end()), Bytes(24, 3));

    const Volume in = ddt::readVolume(input);
    requireAffine(in.index_to_world, sform, 0);  // the sform wins

    // Doubled along each axis, 8×6×4: every column halves, and the origin moves by
    // A · (−0.25, −0.25, −0.25) (half a new voxel minus half an old one, in index units):
    //   sform: (100, 50, 10) − 0.25 · ((0, 2, 0) + (−2, 0, 0) + (0, 0, 2)) = (100.5, 49.5, 9.5)
    //   qform: (−5, −5, −5) − 0.25 · (2, 2, 2) = (−5.5, −5.5, −5.5), pixdims 1.
    Volume out = in;
    out.size = {8, 6, 4};
    out.values.assign(out.voxelCount(), 3.0f);
    out.index_to_world = ddt::resampledAffine(in.index_to_world, in.size, out.size);
    const std::string path = folder / "two-out.nii";
    ddt::writeVolume(path, out, VoxelType::u8);

    const Bytes o = readFile(path);
    CHECK(get<int16_t>(o, kSformCode) == 2);
    CHECK(get<int16_t>(o, kQformCode) == 1);
    const double expected_sform[3][4] = {{0, -1, 0, 100.5}, {1, 0, 0, 49.5}, {0, 0, 1, 9.5}};
    requireAffine(sformOf(o), expected_sform, 1e-6);
    for (int i = 0; i < 3; ++i) {
        CHECK(get<float>(o, kQuaternB + 4 * i) == Approx(0.0).margin(1e-7));
        CHECK(get<float>(o, kQoffsetX + 4 * i) == Approx(-5.5).margin(1e-6));
        CHECK(get<float>(o, kPixdim + 4 * (i + 1)) == Approx(1.0).margin(1e-6));
    }
    CHECK(get<char>(o, kXyztUnits) == (2 | 8));
    CHECK(std::string(reinterpret_cast<const char*>(&o[kDescrip])) == "two transforms");
}

TEST_CASE("volume io: NRRD in LPS to NIfTI and back keeps every voxel's place", "[volume-io]") {
    TempFolder folder;
    // LPS: +x left, +y posterior. In RAS (NIfTI's frame) x and y change sign: the rows
    // (−0.5·…) below, worked out by hand from the NRRD's directions and origin.
    const std::string input = folder / "lps.nrrd";
    writeFile(input,
              nrrdHeader("unsigned char", "space: left-posterior-superior\nspace directions: (0.5,0,0) (0,0.5,0) (0,0,2.5)\n"
                                          "space origin: (10,20,30)\nspace units: \"mm\" \"mm\" \"mm\"\n"),
              Bytes(24, 9));
    const Volume lps = ddt::readVolume(input);
    requireAffine(lps.index_to_world, kKnownRows, 0);  // its own frame, as read

    const std::string nifti = folder / "ras.nii";
    ddt::writeVolume(nifti, lps, VoxelType::u8);
    const Bytes h = readFile(nifti);
    const double ras[3][4] = {{-0.5, 0, 0, -10}, {0, -0.5, 0, -20}, {0, 0, 2.5, 30}};
    requireAffine(sformOf(h), ras, 0);
    CHECK(get<int16_t>(h, kSformCode) == 1);
    CHECK(get<int16_t>(h, kQformCode) == 1);
    CHECK((get<char>(h, kXyztUnits) & 7) == 2);  // mm

    const Volume from_nifti = ddt::readVolume(nifti);
    requireAffine(from_nifti.index_to_world, ras, 1e-6);
    const std::string back = folder / "back.nrrd";
    ddt::writeVolume(back, from_nifti, VoxelType::u8);
    const std::string text = readText(back);
    CHECK(contains(text, "space: right-anterior-superior\n"));
    CHECK(contains(text, "space directions: (-0.5,0,0) (0,-0.5,0) (0,0,2.5)\n"));
    CHECK(contains(text, "space origin: (-10,-20,30)\n"));
    CHECK(ddt::readVolume(back).values == lps.values);
}

TEST_CASE("volume io: a sheared NRRD becomes a NIfTI with an sform and no qform", "[volume-io]") {
    TempFolder folder;
    // The y axis leans towards x: a qform (rotation and scaling only) cannot hold it.
    const std::string input = folder / "sheared.nrrd";
    writeFile(input, nrrdHeader("unsigned char", "space: right-anterior-superior\nspace directions: (1,0,0) (0.5,1,0) (0,0,2)\n"
                                                 "space origin: (0,0,0)\n"),
              Bytes(24, 1));
    const std::string out = folder / "sheared.nii";
    ddt::writeVolume(out, ddt::readVolume(input), VoxelType::u8);
    const Bytes h = readFile(out);
    CHECK(get<int16_t>(h, kSformCode) == 1);
    CHECK(get<int16_t>(h, kQformCode) == 0);
    const double rows[3][4] = {{1, 0.5, 0, 0}, {0, 1, 0, 0}, {0, 0, 2, 0}};
    requireAffine(sformOf(h), rows, 0);

    // Coplanar axes place no volume at all: refused.
    const std::string flat = folder / "coplanar.nrrd";
    writeFile(flat, nrrdHeader("unsigned char", "space: right-anterior-superior\nspace directions: (1,0,0) (0,1,0) (1,1,0)\n"),
              Bytes(24, 1));
    CHECK(contains(errorOf([&] { ddt::readVolume(flat); }), flat + ": the index-to-world transform is singular"));
}

TEST_CASE("volume io: a big-endian NIfTI is read in its byte order", "[volume-io]") {
    TempFolder folder;
    Bytes h = niftiHeader({4, 3, 2}, kInt16, 16);
    makeBigEndian(h);
    Bytes data;
    for (int k = 0; k < 24; ++k) {
        const uint16_t value = uint16_t(int16_t(300 * k - 3000));
        data.push_back(uint8_t(value >> 8));
        data.push_back(uint8_t(value & 0xff));
    }
    const std::string path = folder / "big.nii";
    writeFile(path, std::string(h.begin(), h.end()), data);
    const Volume volume = ddt::readVolume(path);
    CHECK(volume.size == std::array<uint32_t, 3>{4, 3, 2});
    for (int k = 0; k < 24; ++k) CHECK(volume.values[k] == float(300 * k - 3000));
}

TEST_CASE("volume io: sides above 32767 are written as NIfTI-2, which reads back", "[volume-io]") {
    TempFolder folder;
    std::vector<float> values(32768 * 2 * 2);
    for (size_t i = 0; i < values.size(); ++i) values[i] = float(i % 251);
    const Volume volume = makeVolume({32768, 2, 2}, VoxelType::u8, values, affineOf(kKnownRows));
    const std::string path = folder / "wide.nii";
    ddt::writeVolume(path, volume, VoxelType::u8);
    const Bytes bytes = readFile(path);
    CHECK(get<int32_t>(bytes, 0) == 540);  // NIfTI-2's sizeof_hdr
    CHECK(std::memcmp(&bytes[4], "n+2", 4) == 0);
    const Volume back = ddt::readVolume(path);
    CHECK(back.size == volume.size);
    CHECK(back.values == values);
    requireAffine(back.index_to_world, kKnownRows, 0);
    REQUIRE(back.metadata->nifti);
    CHECK(back.metadata->nifti->version == 2);
}

TEST_CASE("volume io: an NRRD with spacings only, or without any, gets a diagonal affine at 0", "[volume-io]") {
    TempFolder folder;
    const std::string spaced = folder / "spaced.nrrd";
    writeFile(spaced, nrrdHeader("unsigned char", "spacings: 0.5 0.75 3\n"), Bytes(24, 1));
    const double spacing_rows[3][4] = {{0.5, 0, 0, 0}, {0, 0.75, 0, 0}, {0, 0, 3, 0}};
    requireAffine(ddt::readVolume(spaced).index_to_world, spacing_rows, 0);
    const std::string bare = folder / "bare.nrrd";
    writeFile(bare, nrrdHeader("unsigned char", ""), Bytes(24, 1));
    const double unit_rows[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    requireAffine(ddt::readVolume(bare).index_to_world, unit_rows, 0);
    // Written back, still spacings only: there is no world frame to claim.
    const std::string out = folder / "out.nrrd";
    ddt::writeVolume(out, ddt::readVolume(spaced), VoxelType::u8);
    const std::string text = readText(out);
    CHECK(contains(text, "spacings: 0.5 0.75 3\n"));
    CHECK_FALSE(contains(text, "space:"));
}

TEST_CASE("volume io: NRRD metadata is kept from input to output", "[volume-io]") {
    TempFolder folder;
    const std::string input = folder / "meta.nrrd";
    writeFile(input,
              nrrdHeader("short",
                         "content: head CT\nspace: left-posterior-superior\nspace directions: (0.5,0,0) (0,0.5,0) (0,0,2.5)\n"
                         "kinds: domain domain domain\ncenters: cell cell cell\nlabels: \"x\" \"y\" \"z\"\n"
                         "space units: \"mm\" \"mm\" \"mm\"\nspace origin: (1,2,3)\nsample units: HU\n"
                         "# a comment\nmodality:=CT\n"),
              Bytes(48, 0));
    const std::string out = folder / "meta-out.nrrd";
    const std::vector<std::string> notes = ddt::writeVolume(out, ddt::readVolume(input), VoxelType::i16);
    const std::string text = readText(out);
    INFO(text.substr(0, text.find("\n\n")));
    // Teem's canonical spelling: "centerings".
    for (const char* line : {"content: head CT\n", "space: left-posterior-superior\n", "kinds: domain domain domain\n",
                             "centerings: cell cell cell\n", "labels: \"x\" \"y\" \"z\"\n", "space units: \"mm\" \"mm\" \"mm\"\n",
                             "space origin: (1,2,3)\n", "# a comment\n", "modality:=CT\n"})
        CHECK(contains(text, line));
    // The sample units are the one field teem 1.12 cannot write safely: left out, with a note.
    CHECK_FALSE(contains(text, "sample units"));
    REQUIRE(notes.size() == 1);
    CHECK(notes[0] == out + ": the sample units (HU) are left out: teem 1.12 cannot write them safely");
}

TEST_CASE("volume io: detached NRRD headers (.nhdr) are read, big-endian too, and written", "[volume-io]") {
    TempFolder folder;
    // Big-endian uint16 samples 256·k + 1 in a data file beside the header.
    Bytes data;
    for (int k = 0; k < 24; ++k) data.push_back(uint8_t(k)), data.push_back(1);
    writeFile(folder / "samples.raw", "", data);
    writeFile(folder / "head.nhdr", "NRRD0004\ntype: unsigned short\ndimension: 3\nsizes: 4 3 2\nendian: big\n"
                                    "encoding: raw\nspacings: 1 1 1\ndata file: samples.raw\n");
    const Volume volume = ddt::readVolume(folder / "head.nhdr");
    for (int k = 0; k < 24; ++k) CHECK(volume.values[k] == float(256 * k + 1));
    REQUIRE(volume.metadata);
    CHECK(volume.metadata->files.size() == 2);

    // Written: out.nhdr names out.raw beside it.
    ddt::writeVolume(folder / "out.nhdr", volume, VoxelType::u16);
    // Older NRRD versions mark a header-relative data file with "./".
    const std::string header = readText(folder / "out.nhdr");
    CHECK((contains(header, "data file: out.raw\n") || contains(header, "data file: ./out.raw\n")));
    CHECK(readFile(folder / "out.raw").size() == 48);
    CHECK(ddt::readVolume(folder / "out.nhdr").values == volume.values);
    // The data file the input names is an input file too: never replaced.
    const std::string message = errorOf([&] { ddt::writeVolume(folder / "samples.nhdr", volume, VoxelType::u16); });
    CHECK(contains(message, "samples.raw: is the input file"));
    CHECK(readFile(folder / "samples.raw") == data);
}

TEST_CASE("volume io: .nii.gz is read and written through gzip", "[volume-io]") {
    TempFolder folder;
    std::vector<uint8_t> raw(24);
    for (int k = 0; k < 24; ++k) raw[k] = uint8_t(10 * k);
    const Bytes header = niftiHeader({4, 3, 2}, kUint8, 8);
    Bytes file = header;
    file.insert(file.end(), raw.begin(), raw.end());
    gzipFile(folder / "in.nii.gz", file);
    const Volume volume = ddt::readVolume(folder / "in.nii.gz");
    for (int k = 0; k < 24; ++k) CHECK(volume.values[k] == float(10 * k));

    ddt::writeVolume(folder / "out.nii.gz", volume, VoxelType::u8);
    const Bytes written = readFile(folder / "out.nii.gz");
    REQUIRE(written.size() > 2);
    CHECK((written[0] == 0x1f && written[1] == 0x8b));  // the gzip signature
    const Bytes inflated = gunzip(folder / "out.nii.gz");
    REQUIRE(inflated.size() == 352 + 24);
    CHECK(get<int32_t>(inflated, 0) == 348);
    for (int k = 0; k < 24; ++k) CHECK(int(inflated[352 + k]) == 10 * k);

    // A compressed input makes a compressed NRRD.
    ddt::writeVolume(folder / "out.nrrd", volume, VoxelType::u8);
    CHECK(contains(readText(folder / "out.nrrd"), "encoding: gzip\n"));
    CHECK(ddt::readVolume(folder / "out.nrrd").values == volume.values);
}

TEST_CASE("volume io: NaN and infinite samples are refused with the voxel named", "[volume-io]") {
    TempFolder folder;
    std::vector<float> values(24, 1.0f);
    values[1] = std::numeric_limits<float>::quiet_NaN();  // voxel (1, 0, 0)
    const std::string nrrd = folder / "nan.nrrd";
    writeFile(nrrd, nrrdHeader("float", ""), bytesOf(values));
    std::string message = errorOf([&] { ddt::readVolume(nrrd); });
    CHECK(contains(message, nrrd + ": voxel (1, 0, 0) is NaN"));

    values[1] = 1.0f;
    values[4 * 3 + 5] = -std::numeric_limits<float>::infinity();  // voxel (1, 1, 1)
    const Bytes header = niftiHeader({4, 3, 2}, kFloat32, 32);
    const std::string nifti = folder / "inf.nii";
    writeFile(nifti, std::string(header.begin(), header.end()), bytesOf(values));
    message = errorOf([&] { ddt::readVolume(nifti); });
    CHECK(contains(message, nifti + ": voxel (1, 1, 1) is infinite"));
}

TEST_CASE("volume io: bad inputs get one line naming the file and the reason, and stderr stays clean", "[volume-io]") {
    TempFolder folder;
    struct Case {
        std::string name, header;
        Bytes data;
        std::string reason;
    };
    auto nifti = [](std::vector<int16_t> dims, int16_t type, int16_t bits) {
        const Bytes h = niftiHeader(std::move(dims), type, bits);
        return std::string(h.begin(), h.end());
    };
    const std::vector<Case> cases = {
        {"short.nrrd", nrrdHeader("short", ""), Bytes(10, 0), "truncated"},
        {"long.nrrd", nrrdHeader("short", ""), Bytes(96, 0), "does not match"},
        {"short.nii", nifti({4, 3, 2}, kInt16, 16), Bytes(30, 0), "truncated"},
        {"long.nii", nifti({4, 3, 2}, kInt16, 16), Bytes(60, 0), "does not match"},
        {"series.nii", nifti({4, 3, 2, 5}, kUint8, 8), Bytes(120, 0), "4-D series of 5 volumes"},
        {"vector.nii", nifti({4, 3, 2, 1, 3}, kFloat32, 32), Bytes(288, 0), "3 values per voxel"},
        {"rgb.nii", nifti({4, 3, 2}, kRgb24, 24), Bytes(72, 0), "multi-component"},
        {"int32.nii", nifti({4, 3, 2}, kInt32, 32), Bytes(96, 0), "sample type INT32 is not supported"},
        {"flat.nii", nifti({4, 3}, kUint8, 8), Bytes(12, 0), "not a volume"},
        {"plane.nii", nifti({4, 3, 1}, kUint8, 8), Bytes(12, 0), "not a volume"},
        {"vector.nrrd", nrrdHeader("float", "kinds: vector domain domain domain\n", "3 4 3 2", "4"), Bytes(288, 0),
         "multi-component"},
        {"rgb.nrrd", nrrdHeader("unsigned char", "kinds: RGB-color domain domain\n", "3 4 3", "3"), Bytes(36, 0),
         "multi-component"},
        {"flat.nrrd", nrrdHeader("unsigned char", "", "4 3", "2"), Bytes(12, 0), "not a volume"},
        {"int.nrrd", nrrdHeader("int", ""), Bytes(96, 0), "sample type int is not supported"},
        {"wide.nrrd", nrrdHeader("unsigned char", "", "70000 2 2"), {}, "above 65536"},
        {"huge.nrrd", nrrdHeader("unsigned char", "", "2048 2048 1024"), {}, "2^31"},
        {"garbage.nrrd", "this is not a header\n", {}, "not a readable NRRD file"},
        {"garbage.nii", std::string(400, 'x'), {}, "not a readable NIfTI"},
        {"tiny.nii", "abc", {}, "truncated"},
        {"lost.nhdr", "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 3 2\nendian: little\nencoding: raw\ndata file: missing.raw\n", {},
         "not a readable NRRD"},
        {"empty.nrrd", "", {}, "empty file"},
    };
    for (const Case& c : cases) {
        const std::string path = folder / c.name;
        writeFile(path, c.header, c.data);
        CapturedStderr captured;
        const std::string message = errorOf([&] { ddt::readVolume(path); });
        INFO(message);
        CHECK(message.starts_with(path + ": "));
        CHECK(contains(message, c.reason));
        CHECK(message.find('\n') == std::string::npos);
        CHECK(captured.text().empty());
    }
    CHECK(contains(errorOf([&] { ddt::readVolume(folder / "absent.nii"); }), "absent.nii: no such file"));
    CHECK(contains(errorOf([&] { ddt::readVolume(folder.path().string()); }), "is a folder"));
    writeFile(folder / "volume.png", "x");
    CHECK(contains(errorOf([&] { ddt::readVolume(folder / "volume.png"); }), "not a volume file"));
}

TEST_CASE("volume io: a failed write leaves nothing, and the input is never overwritten", "[volume-io]") {
    TempFolder folder;
    // Values that gzip cannot squeeze below the 1000 bytes the disk takes.
    std::vector<float> values(24000);
    for (size_t i = 0; i < values.size(); ++i) values[i] = float((i * 2654435761u) % 100003) * 0.731f;
    const Volume volume = makeVolume({40, 30, 20}, VoxelType::f32, values, affineOf(kKnownRows));
    for (const std::string name : {"full.nrrd", "full.nii", "full.nii.gz"}) {
        ::setenv("DDTUP_TEST_WRITE_LIMIT", "1000", 1);  // a disk that fills after 1000 bytes
        const std::string message = errorOf([&] { ddt::writeVolume(folder / name, volume, VoxelType::f32); });
        ::unsetenv("DDTUP_TEST_WRITE_LIMIT");
        CHECK(message == folder / name + ": No space left on device");
        CHECK(folder.names().empty());
    }

    const std::string input = folder / "in.nii";
    ddt::writeVolume(input, volume, VoxelType::f32);
    const Bytes before = readFile(input);
    const Volume read = ddt::readVolume(input);
    CHECK(contains(errorOf([&] { ddt::writeVolume(input, read, VoxelType::u8); }), "is the input file"));
    CHECK(readFile(input) == before);
    CHECK(folder.names() == std::set<std::string>{"in.nii"});
}

TEST_CASE("volume io: volumeOutputProblem says what is wrong before any work", "[volume-io]") {
    TempFolder folder;
    CHECK(ddt::volumeOutputProblem(folder / "ok.nii", {4, 3, 2}).empty());
    CHECK(contains(ddt::volumeOutputProblem(folder / "out.png", {4, 3, 2}), "not a volume file name"));
    CHECK(contains(ddt::volumeOutputProblem(folder / "out.nrrd", {4, 3, 1}), "not a volume"));
    CHECK(contains(ddt::volumeOutputProblem(folder / "missing/out.nrrd", {4, 3, 2}), "does not exist"));
}

TEST_CASE("volume io: the middle slices are windowed to the data range, one pixel per voxel", "[volume-io]") {
    TempFolder folder;
    // 3 × 4 × 5 voxels of value x + 10 y + 100 z − 1000: min −1000, max −568 (range 432).
    // The middle voxel is (1, 2, 2). A value v becomes round(255 (v + 1000) / 432).
    std::vector<float> values(60);
    for (uint32_t z = 0; z < 5; ++z)
        for (uint32_t y = 0; y < 4; ++y)
            for (uint32_t x = 0; x < 3; ++x) values[x + 3 * (y + 4 * z)] = float(x + 10 * y + 100 * z) - 1000.0f;
    const Volume volume = makeVolume({3, 4, 5}, VoxelType::i16, values, affineOf(kKnownRows));
    const std::vector<std::string> paths = ddt::writeMiddleSlices(volume, folder.path().string(), "ct");
    REQUIRE(paths.size() == 3);
    CHECK(paths[0] == folder / "ct-axial.png");

    auto pixels = [](const std::string& path, int width, int height) {
        auto input = OIIO::ImageInput::open(path);
        REQUIRE(input);
        CHECK(input->spec().width == width);
        CHECK(input->spec().height == height);
        CHECK(input->spec().nchannels == 1);
        CHECK(input->spec().format == OIIO::TypeDesc::UINT8);
        std::vector<uint8_t> p(size_t(width) * height);
        REQUIRE(input->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, p.data()));
        return p;
    };
    // Axial, z = 2: pixel (column x, row y) holds x + 10 y + 200.
    const std::vector<uint8_t> axial = pixels(folder / "ct-axial.png", 3, 4);
    CHECK(int(axial[0]) == 118);           // v + 1000 = 200: 255 · 200 / 432 = 118.06
    CHECK(int(axial[3 * 3 + 2]) == 137);   // (2, 3): 232 → 136.94
    // Coronal, y = 2: column x, row r at z = 4 − r: the top row is z = 4.
    const std::vector<uint8_t> coronal = pixels(folder / "ct-coronal.png", 3, 5);
    CHECK(int(coronal[0]) == 248);         // (0, 2, 4): 420 → 247.92
    CHECK(int(coronal[4 * 3 + 1]) == 12);  // (1, 2, 0): 21 → 12.40
    // Sagittal, x = 1: column y, row r at z = 4 − r.
    const std::vector<uint8_t> sagittal = pixels(folder / "ct-sagittal.png", 4, 5);
    CHECK(int(sagittal[3]) == 254);        // (1, 3, 4): 431 → 254.41
    CHECK(int(sagittal[4 * 4 + 0]) == 1);  // (1, 0, 0): 1 → 0.59

    // A constant volume: every pixel 0.
    const Volume flat = makeVolume({3, 4, 5}, VoxelType::u8, std::vector<float>(60, 7.0f), affineOf(kKnownRows));
    ddt::writeMiddleSlices(flat, folder.path().string(), "flat");
    for (uint8_t p : pixels(folder / "flat-sagittal.png", 4, 5)) CHECK(int(p) == 0);
}
