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

}  // namespace vorogeo::tools
