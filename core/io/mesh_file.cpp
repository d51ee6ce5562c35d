#include "mesh_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "checked_file.h"
#include "output_file.h"

namespace ddt {

namespace {

// Collects a file's bytes and hands them to the sink in pieces of about a megabyte.
class ByteBuffer {
public:
    explicit ByteBuffer(const ByteSink& sink) : sink_(sink) { bytes_.reserve(kPiece + 256); }
    ~ByteBuffer() = default;

    void text(const std::string& s) { append(s.data(), s.size()); }
    template <typename T>
    void binary(T value) {  // little-endian, as x86 and ARM store it
        append(reinterpret_cast<const char*>(&value), sizeof(value));
    }
    template <typename T>
    void number(T value) {  // the shortest text that reads back as the same value
        char digits[32];
        const auto [end, error] = std::to_chars(digits, digits + sizeof(digits), value);
        append(digits, size_t(end - digits));
    }
    void flush() {
        if (!bytes_.empty()) sink_(bytes_.data(), bytes_.size());
        bytes_.clear();
    }

private:
    static constexpr size_t kPiece = size_t(1) << 20;
    void append(const char* data, size_t size) {
        bytes_.append(data, size);
        if (bytes_.size() >= kPiece) flush();
    }

    const ByteSink& sink_;
    std::string bytes_;
};

// The colour channels a file stores per vertex: red, green, blue (grey repeated) and alpha
// where the image has it; `channel[k]` is the mesh's channel for stored channel k.
struct StoredColour {
    uint32_t count = 0;
    uint32_t channel[4] = {};
};
StoredColour storedColourOf(uint32_t channels) {
    if (channels == 1) return {3, {0, 0, 0}};
    if (channels == 2) return {4, {0, 0, 0, 1}};
    if (channels == 3) return {3, {0, 1, 2}};
    return {4, {0, 1, 2, 3}};
}

void writePly(const IndexedMesh& mesh, const std::string& comment, ByteBuffer& out) {
    const StoredColour stored = storedColourOf(mesh.channels);
    const char* type = mesh.colour_type == SampleType::UInt8    ? "uchar"
                       : mesh.colour_type == SampleType::UInt16 ? "ushort"
                                                                : "float";
    out.text("ply\nformat binary_little_endian 1.0\ncomment " + comment + "\nelement vertex " +
             std::to_string(mesh.vertexCount()) + "\nproperty float x\nproperty float y\nproperty float z\n");
    const char* names[4] = {"red", "green", "blue", "alpha"};
    for (uint32_t k = 0; k < stored.count; ++k) out.text(std::string("property ") + type + " " + names[k] + "\n");
    out.text("element face " + std::to_string(mesh.faceCount()) + "\nproperty list uchar int vertex_indices\nend_header\n");
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        for (uint32_t k = 0; k < 3; ++k) out.binary(float(mesh.positions[3 * size_t(v) + k]));
        const float* colour = &mesh.colours[size_t(v) * mesh.channels];
        for (uint32_t k = 0; k < stored.count; ++k) {
            const float value = colour[stored.channel[k]];
            // Integer types round to the nearest level, as the image writers do.
            if (mesh.colour_type == SampleType::UInt8) out.binary(uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)));
            else if (mesh.colour_type == SampleType::UInt16)
                out.binary(uint16_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 65535.0f)));
            else out.binary(value);
        }
    }
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        out.binary(uint8_t(3));
        for (uint32_t k = 0; k < 3; ++k) out.binary(int32_t(mesh.faces[3 * size_t(f) + k]));
    }
}

void writeObj(const IndexedMesh& mesh, const std::string& comment, ByteBuffer& out) {
    const StoredColour stored = storedColourOf(mesh.channels);
    out.text("# " + comment + "\n");
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        out.text("v");
        for (uint32_t k = 0; k < 3; ++k) {
            out.text(" ");
            out.number(mesh.positions[3 * size_t(v) + k]);
        }
        const float* colour = &mesh.colours[size_t(v) * mesh.channels];
        for (uint32_t k = 0; k < 3; ++k) {  // alpha has no place in `v`
            out.text(" ");
            out.number(colour[stored.channel[k]]);
        }
        out.text("\n");
    }
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        out.text("f");
        for (uint32_t k = 0; k < 3; ++k) {
            out.text(" ");
            out.number(mesh.faces[3 * size_t(f) + k] + 1);
        }
        out.text("\n");
    }
}

}  // namespace

std::optional<MeshFormat> meshFormatOf(const std::string& path_or_name) {
    std::string extension = std::filesystem::path(path_or_name).extension().string();
    if (extension.empty())  // a bare name, with or without its dot (".obj" is all stem to std::filesystem)
        extension = path_or_name.starts_with('.') ? path_or_name : "." + path_or_name;
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (extension == ".ply") return MeshFormat::Ply;
    if (extension == ".obj") return MeshFormat::Obj;
    return std::nullopt;
}

const char* meshFormatNames() { return "ply or obj"; }

void writeMesh(MeshFormat format, const IndexedMesh& mesh, const std::string& comment, const ByteSink& sink) {
    ByteBuffer out(sink);
    if (format == MeshFormat::Ply) writePly(mesh, comment, out);
    else writeObj(mesh, comment, out);
    out.flush();
}

void writeMeshFile(const std::string& path, const IndexedMesh& mesh, const std::string& comment) {
    const std::optional<MeshFormat> format = meshFormatOf(path);
    if (!format) throw UserError(path + ": unknown mesh format (the extension must name " + meshFormatNames() + ")");
    checkOutputPath(path);
    const std::unique_ptr<TempFile> temp = createTempFile(path);
    CheckedFile file(temp->path());
    writeMesh(*format, mesh, comment, [&](const char* data, size_t size) {
        if (!file.failure()) file.write(data, size);
    });
    file.close();
    if (file.failure()) throw UserError(path + ": " + std::strerror(file.failure()));
    moveIntoPlace(*temp, path, path);
}

}  // namespace ddt
