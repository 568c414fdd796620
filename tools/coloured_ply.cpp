#include "coloured_ply.h"

#include <cstring>
#include <stdexcept>

#include "blob_writer.h"

namespace vorogeo::tools {

namespace {

template <class T>
void append(std::vector<uint8_t>& out, T value) {
    uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));  // PLY binary_little_endian; x86 and ARM hosts are little-endian
    out.insert(out.end(), bytes, bytes + sizeof(T));
}

}  // namespace

void writeColouredPly(const Mesh& mesh, const std::vector<Rgb>& colours, const std::string& path) {
    if (colours.size() != mesh.vertexCount()) throw std::runtime_error("one colour per vertex expected");
    const std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by vorogeo\nelement vertex " +
                               std::to_string(mesh.vertexCount()) +
                               "\nproperty float x\nproperty float y\nproperty float z\n"
                               "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face " +
                               std::to_string(mesh.faceCount()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    std::vector<uint8_t> out(header.begin(), header.end());
    out.reserve(out.size() + size_t(mesh.vertexCount()) * 15 + size_t(mesh.faceCount()) * 13);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        append(out, float(mesh.positions[v].x));
        append(out, float(mesh.positions[v].y));
        append(out, float(mesh.positions[v].z));
        append(out, colours[v].r);
        append(out, colours[v].g);
        append(out, colours[v].b);
    }
    for (const Tri& t : mesh.faces) {
        append(out, uint8_t(3));
        for (uint32_t v : t) append(out, int32_t(v));
    }
    writeFileAtomically(path, out);
}

}  // namespace vorogeo::tools
