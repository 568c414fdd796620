// Loading a mesh, and a blob baked from it, for a subcommand: prints the loader's notices
// and a one-line error.
#pragma once

#include <string>

#include "mesh.h"
#include "runtime_graph.h"

namespace vorogeo::tools {

// False after printing "vorogeo CMD: FILE: problem" to stderr.
bool loadMeshForCommand(const char* command, const std::string& path, bool repair, Mesh& mesh);

// Opens the blob at `path` and checks it was baked from `mesh`: the same vertex count, and
// with `sameFaces` the same face count too (commands that take surface points). False after
// printing "vorogeo CMD: problem" to stderr.
bool loadBlobForMesh(const char* command, const std::string& path, const Mesh& mesh, bool sameFaces,
                     RuntimeGraph& graph);

}  // namespace vorogeo::tools
