#include "tool_mesh.h"

#include <cstdio>

#include "mesh_io.h"

namespace vorogeo::tools {

bool loadMeshForCommand(const char* command, const std::string& path, bool repair, Mesh& mesh) {
    LoadOptions options;
    options.repair = repair;
    const LoadReport report = loadMesh(path, options, mesh);
    for (const std::string& n : report.notices) std::fprintf(stderr, "vorogeo %s: note: %s\n", command, n.c_str());
    if (!report.ok) {
        std::fprintf(stderr, "vorogeo %s: %s\n", command, report.error.c_str());
        return false;
    }
    return true;
}

bool loadBlobForMesh(const char* command, const std::string& path, const Mesh& mesh, bool sameFaces,
                     RuntimeGraph& graph) {
    std::string error;
    if (!graph.load(path, error)) {
        std::fprintf(stderr, "vorogeo %s: %s\n", command, error.c_str());
        return false;
    }
    if (sameFaces && (graph.vertexCount() != mesh.vertexCount() || vg_face_count(graph.graph()) != mesh.faceCount())) {
        std::fprintf(stderr, "vorogeo %s: the blob has %u vertices and %u faces but the mesh has %u and %u: "
                     "not baked from this mesh\n", command, graph.vertexCount(), vg_face_count(graph.graph()),
                     mesh.vertexCount(), mesh.faceCount());
        return false;
    }
    if (graph.vertexCount() != mesh.vertexCount()) {
        std::fprintf(stderr, "vorogeo %s: the blob has %u vertices but the mesh has %u: not baked from this mesh\n",
                     command, graph.vertexCount(), mesh.vertexCount());
        return false;
    }
    return true;
}

}  // namespace vorogeo::tools
