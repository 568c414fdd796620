// A mesh with one colour per vertex as binary PLY, for viewing a field in MeshLab or
// Blender.
#pragma once

#include <string>
#include <vector>

#include "image.h"
#include "mesh.h"

namespace vorogeo::tools {

// Writes atomically (temporary file, then rename); throws std::runtime_error naming the
// problem. `colours` has one entry per vertex.
void writeColouredPly(const Mesh& mesh, const std::vector<Rgb>& colours, const std::string& path);

}  // namespace vorogeo::tools
