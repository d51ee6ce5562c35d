// Mesh files (`--mesh`): the optimised mesh as PLY or OBJ, written like images are, through a
// temporary file beside the output that is renamed into place once every byte is on disk.
// core/indexed_mesh.h says what the vertices, colours and triangles mean.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "indexed_mesh.h"

namespace ddt {

enum class MeshFormat {
    Ply,  // binary little-endian: float x y z, colours as the input's type (uchar, ushort or float), int faces
    Obj,  // text: `v x y z r g b` (the widely read vertex-colour extension; alpha is dropped), `f` 1-based
};

// The format a path's extension (or a bare name: "ply", ".obj") names, any case; nullopt if none.
std::optional<MeshFormat> meshFormatOf(const std::string& path_or_name);
// The formats' names for messages: "ply or obj".
const char* meshFormatNames();

// Where the file's bytes go, in pieces of any size.
using ByteSink = std::function<void(const char* data, size_t size)>;
// The file in `format`, with `comment` (one line) in its header.
void writeMesh(MeshFormat format, const IndexedMesh& mesh, const std::string& comment, const ByteSink& sink);

// Writes `mesh` to `path` in the format its extension names. Throws UserError("PATH: reason")
// for an unknown extension, an unwritable folder or a failed write (a full disk); the file is
// then left as it was.
void writeMeshFile(const std::string& path, const IndexedMesh& mesh, const std::string& comment);

}  // namespace ddt
