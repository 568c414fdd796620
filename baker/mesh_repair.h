// Topology repairs behind --repair. They only remove faces, flip faces and give a
// vertex extra copies (one per fan); they never move or weld vertices.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh.h"

namespace vorogeo {

// Runs, in order: drop degenerate faces, drop duplicate faces, orient faces
// consistently per component, cut non-manifold edges and split non-manifold vertices
// into one copy per fan. Appends one notice per repair that changed something.
// `sourceFace` (face -> face number in the input file) is kept aligned when non-empty.
// Requires in-range indices. Afterwards checkMesh() finds nothing but unreferenced vertices.
void repairMesh(Mesh& mesh, std::vector<uint32_t>& sourceFace, std::vector<std::string>& notices);

}  // namespace vorogeo
