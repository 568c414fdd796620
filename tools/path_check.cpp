#include "path_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vorogeo::tools {

namespace {

constexpr double kZeroWeight = 1e-6;

Vec3 toVec(const float* p) { return Vec3{p[0], p[1], p[2]}; }

}  // namespace

PathChecker::PathChecker(const Mesh& mesh) : mesh_(mesh), vertexFaces_(mesh.vertexCount()) {
    Vec3 lo = mesh.positions.empty() ? Vec3{0, 0, 0} : mesh.positions[0], hi = lo;
    for (const Vec3& p : mesh.positions) {
        lo = Vec3{std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = Vec3{std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    tolerance_ = 1e-5 * std::max(distance(lo, hi), 1e-30);
    for (uint32_t f = 0; f < mesh.faceCount(); ++f)
        for (uint32_t v : mesh.faces[f]) vertexFaces_[v].push_back(f);
}

std::vector<uint32_t> PathChecker::facesOf(const vg_point& p) const {
    int nonzero = 0, zero = -1, one = -1;
    for (int k = 0; k < 3; ++k) {
        if (std::fabs(p.bary[k]) > kZeroWeight) ++nonzero;
        else zero = k;
        if (std::fabs(p.bary[k] - 1.0f) <= kZeroWeight) one = k;
    }
    const Tri& t = mesh_.faces[p.face];
    if (one >= 0) return vertexFaces_[t[one]];
    std::vector<uint32_t> faces{p.face};
    if (nonzero == 2) {
        const int32_t across = mesh_.twin[3 * p.face + (zero + 1) % 3];  // the edge opposite corner `zero`
        if (across >= 0) faces.push_back(uint32_t(across / 3));
    }
    return faces;
}

PathCheck PathChecker::check(const std::vector<vg_path_point>& path) const {
    PathCheck r;
    char text[256];
    auto fail = [&](const char* what, size_t i) {
        if (!r.ok) return;
        r.ok = false;
        std::snprintf(text, sizeof text, "point %zu of %zu: %s", i, path.size(), what);
        r.problem = text;
    };
    r.length = polylineLength(path);
    for (size_t i = 0; i < path.size(); ++i) {
        const vg_point& p = path[i].point;
        if (p.face >= mesh_.faceCount()) {
            fail("face out of range", i);
            break;
        }
        double sum = 0;
        Vec3 at{0, 0, 0};
        for (int k = 0; k < 3; ++k) {
            if (!(p.bary[k] >= -kZeroWeight)) fail("negative or NaN weight", i);
            sum += p.bary[k];
            at = at + mesh_.positions[mesh_.faces[p.face][k]] * double(p.bary[k]);
        }
        if (!(std::fabs(sum - 1) <= 1e-5)) fail("weights do not sum to 1", i);
        if (!(distance(at, toVec(path[i].position)) <= tolerance_)) fail("position is not where face and weights say", i);
        if (i == 0) continue;
        const std::vector<uint32_t> a = facesOf(path[i - 1].point), b = facesOf(p);
        bool shared = false;
        for (uint32_t f : a) shared = shared || std::find(b.begin(), b.end(), f) != b.end();
        if (!shared) fail("shares no face with the point before it", i);
    }
    return r;
}

double polylineLength(const std::vector<vg_path_point>& path) {
    double length = 0;
    for (size_t i = 1; i < path.size(); ++i) length += distance(toVec(path[i - 1].position), toVec(path[i].position));
    return length;
}

}  // namespace vorogeo::tools
