#include <algorithm>
#include <cmath>

#include "mesh_formats.h"

namespace ddt {

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

}  // namespace ddt
