// Loop subdivision (OpenMesh's uniform Loop subdivider): every round splits each triangle
// into four and smooths the vertices, so a mesh grows 4x per round. Used to make large
// test meshes from the shared ones (igea x4, x16) for the scaling measurements.
#pragma once

#include <string>

#include "mesh.h"

namespace vorogeo {

// Subdivides a validated mesh (connectivity built) `rounds` times into `out` (connectivity
// built too). Vertex i of `in` is vertex i of `out` (moved by the smoothing, except
// isolated vertices, which keep their place); new vertices follow. False with a message
// when OpenMesh refuses a face or the result would pass the 32-bit vertex or half-edge limits.
bool loopSubdivide(const Mesh& in, unsigned rounds, Mesh& out, std::string& error);

}  // namespace vorogeo
