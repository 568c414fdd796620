// Splitting the polygons of a mesh file into triangles.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"

namespace vorogeo {

// Appends n-2 triangles covering polygon `poly` (n >= 3 vertex indices, all valid), each
// with the polygon's orientation. Ear clipping in the polygon's best-fit plane, so that
// non-convex polygons are cut inside; when no ear exists (self-intersecting or degenerate
// polygon, or more than 2000 vertices) the rest becomes a fan. Returns false when that
// fallback was used.
bool triangulatePolygon(const std::vector<Vec3>& positions, const uint32_t* poly, uint32_t n, std::vector<Tri>& out);

}  // namespace vorogeo
