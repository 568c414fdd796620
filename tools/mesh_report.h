// Printing mesh statistics for `info` and `demo`: aligned text for people, one JSON
// object for scripts.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "mesh_stats.h"

namespace vorogeo::tools {

void printStatsText(FILE* out, const MeshStats& stats);
// One line, no trailing newline. Keys: see README "vorogeo info".
std::string statsJson(const std::string& file, const MeshStats& stats, double loadSeconds,
                      const std::vector<std::string>& notices);

}  // namespace vorogeo::tools
