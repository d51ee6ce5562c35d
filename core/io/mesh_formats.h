// The mesh file formats (core/io/mesh_file.h), one writer each, and what they share.
#pragma once

#include <cstdint>
#include <string>

#include "byte_buffer.h"
#include "indexed_mesh.h"

namespace ddt {

// The colour channels a file stores per vertex: red, green, blue (grey repeated) and alpha
// where the image has it; `channel[k]` is the mesh's channel for stored channel k.
struct StoredColour {
    uint32_t count = 0;
    uint32_t channel[4] = {};
};
inline StoredColour storedColourOf(uint32_t channels) {
    if (channels == 1) return {3, {0, 0, 0}};
    if (channels == 2) return {4, {0, 0, 0, 1}};
    if (channels == 3) return {3, {0, 1, 2}};
    return {4, {0, 1, 2, 3}};
}

// Each writes the whole file, with `comment` (one line) in its header.
void writePly(const IndexedMesh& mesh, const std::string& comment, ByteBuffer& out);
void writeObj(const IndexedMesh& mesh, const std::string& comment, ByteBuffer& out);
void writeSvg(const IndexedMesh& mesh, const std::string& comment, ByteBuffer& out);

}  // namespace ddt
