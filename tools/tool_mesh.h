// Loading a mesh for a subcommand: prints the loader's notices and its one-line error.
#pragma once

#include <string>

#include "mesh.h"

namespace vorogeo::tools {

// False after printing "vorogeo CMD: FILE: problem" to stderr.
bool loadMeshForCommand(const char* command, const std::string& path, bool repair, Mesh& mesh);

}  // namespace vorogeo::tools
