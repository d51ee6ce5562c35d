// Mesh files (`--mesh`): the optimised mesh as PLY or OBJ, written like images are, through a
// temporary file beside the output that is renamed into place once every byte is on disk.
// core/image/indexed_mesh.h says what the vertices, colours and triangles mean.
#pragma once

#include <optional>
#include <string>

#include "byte_buffer.h"
#include "indexed_mesh.h"

namespace ddt {

enum class MeshFormat {
    Ply,  // binary little-endian: float x y z, colours as the input's type (uchar, ushort or float), int faces
    Obj,  // text: `v x y z r g b` (the widely read vertex-colour extension; alpha is dropped), `f` 1-based
    Svg,  // one path per triangle, a linear gradient where the colour varies (core/io/svg_format.cpp)
};

// The format a path's extension (or a bare name: "ply", ".obj") names, any case; nullopt if none.
std::optional<MeshFormat> meshFormatOf(const std::string& path_or_name);
// The formats' names for messages: "ply, obj or svg".
const char* meshFormatNames();

// The most triangles an SVG file holds. librsvg refuses documents of more than 1 000 000
// elements or 500 000 references by url() (its src/limits.rs: a defence against malicious
// files), and a triangle with a gradient takes four elements (path, gradient, two stops) and
// one reference. Larger meshes are for PLY and OBJ (or simplification).
constexpr uint64_t kMaxSvgTriangles = 200000;
// "" if a mesh of `faces` triangles can be written as `format`, else the reason.
std::string checkMeshSize(MeshFormat format, uint64_t faces);

// The file in `format`, with `comment` (one line) in its header.
void writeMesh(MeshFormat format, const IndexedMesh& mesh, const std::string& comment, const ByteSink& sink);

// Writes `mesh` to `path` in the format its extension names. Throws UserError("PATH: reason")
// for an unknown extension, an unwritable folder or a failed write (a full disk); the file is
// then left as it was.
void writeMeshFile(const std::string& path, const IndexedMesh& mesh, const std::string& comment);

}  // namespace ddt
