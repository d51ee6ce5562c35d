#include "mesh_file.h"

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "checked_file.h"
#include "mesh_formats.h"
#include "output_file.h"

namespace ddt {

std::optional<MeshFormat> meshFormatOf(const std::string& path_or_name) {
    std::string extension = std::filesystem::path(path_or_name).extension().string();
    if (extension.empty())  // a bare name, with or without its dot (".obj" is all stem to std::filesystem)
        extension = path_or_name.starts_with('.') ? path_or_name : "." + path_or_name;
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (extension == ".ply") return MeshFormat::Ply;
    if (extension == ".obj") return MeshFormat::Obj;
    if (extension == ".svg") return MeshFormat::Svg;
    return std::nullopt;
}

const char* meshFormatNames() { return "ply, obj or svg"; }

std::string checkMeshSize(MeshFormat format, uint64_t faces) {
    if (format != MeshFormat::Svg || faces <= kMaxSvgTriangles) return "";
    return "the mesh has " + std::to_string(faces) + " triangles, and SVG export takes at most " +
           std::to_string(kMaxSvgTriangles) + " (librsvg refuses larger documents); write PLY or OBJ";
}

void writeMesh(MeshFormat format, const IndexedMesh& mesh, const std::string& comment, const ByteSink& sink) {
    ByteBuffer out(sink);
    if (format == MeshFormat::Ply) writePly(mesh, comment, out);
    else if (format == MeshFormat::Obj) writeObj(mesh, comment, out);
    else writeSvg(mesh, comment, out);
    out.flush();
}

void writeMeshFile(const std::string& path, const IndexedMesh& mesh, const std::string& comment) {
    const std::optional<MeshFormat> format = meshFormatOf(path);
    if (!format) throw UserError(path + ": unknown mesh format (the extension must name " + meshFormatNames() + ")");
    if (std::string problem = checkMeshSize(*format, mesh.faceCount()); !problem.empty()) throw UserError(path + ": " + problem);
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
