// Checks of a vg_path polyline against the mesh, shared by `vorogeo path` and the tests:
// its length, that every point is where its face and weights say, and that consecutive
// points lie on one common face (so each segment runs on the surface).
#pragma once

#include <string>
#include <vector>

#include "mesh.h"
#include "vorogeo.h"

namespace vorogeo::tools {

struct PathCheck {
    double length = 0;
    bool ok = true;
    std::string problem;  // the first problem found
};

class PathChecker {
public:
    explicit PathChecker(const Mesh& mesh);
    PathCheck check(const std::vector<vg_path_point>& path) const;

private:
    const Mesh& mesh_;
    double tolerance_;                              // position tolerance, from the bounding box
    std::vector<std::vector<uint32_t>> vertexFaces_;
    // Faces a point lies on: its face, the face across its edge, or all faces around its vertex.
    std::vector<uint32_t> facesOf(const vg_point& p) const;
};

// Length of a polyline.
double polylineLength(const std::vector<vg_path_point>& path);

}  // namespace vorogeo::tools
