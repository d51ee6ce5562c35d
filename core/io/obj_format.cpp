#include "mesh_formats.h"

namespace ddt {

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

}  // namespace ddt
