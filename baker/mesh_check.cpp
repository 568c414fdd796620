#include "mesh_check.h"

#include <algorithm>
#include <array>

namespace vorogeo {

std::vector<uint8_t> degenerateFaces(const Mesh& mesh) {
    std::vector<uint8_t> bad(mesh.faceCount(), 0);
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        const Tri& t = mesh.faces[f];
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
            bad[f] = 1;
            continue;
        }
        // Exactly zero only: with float32 input the products are exact in double, so this
        // flags truly collinear corners and nothing that is merely thin.
        const Vec3 n = cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]);
        bad[f] = n.x == 0 && n.y == 0 && n.z == 0;
    }
    return bad;
}

std::vector<uint8_t> duplicateFaces(const Mesh& mesh, const std::vector<uint8_t>& ignore) {
    std::vector<std::array<uint32_t, 4>> keys;  // sorted vertex triple, then face index
    keys.reserve(mesh.faceCount());
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        if (ignore[f]) continue;
        Tri t = mesh.faces[f];
        std::sort(t.begin(), t.end());
        keys.push_back({t[0], t[1], t[2], f});
    }
    std::sort(keys.begin(), keys.end());
    std::vector<uint8_t> dup(mesh.faceCount(), 0);
    for (size_t i = 1; i < keys.size(); ++i)
        if (keys[i][0] == keys[i - 1][0] && keys[i][1] == keys[i - 1][1] && keys[i][2] == keys[i - 1][2])
            dup[keys[i][3]] = 1;  // the lowest-numbered copy stays unflagged
    return dup;
}

EdgeGroups groupEdges(const Mesh& mesh, const std::vector<uint8_t>& ignore) {
    std::vector<std::pair<uint64_t, int32_t>> keys;
    keys.reserve(mesh.halfedgeCount());
    for (uint32_t h = 0; h < mesh.halfedgeCount(); ++h) {
        if (ignore[h / 3]) continue;
        const uint64_t a = mesh.tail(int32_t(h)), b = mesh.head(int32_t(h));
        keys.emplace_back((std::min(a, b) << 32) | std::max(a, b), int32_t(h));
    }
    std::sort(keys.begin(), keys.end());
    EdgeGroups g;
    g.halfedges.reserve(keys.size());
    g.start.reserve(keys.size() / 2 + 2);
    for (size_t i = 0; i < keys.size(); ++i) {
        if (i == 0 || keys[i].first != keys[i - 1].first) g.start.push_back(uint32_t(i));
        g.halfedges.push_back(keys[i].second);
    }
    g.start.push_back(uint32_t(keys.size()));
    return g;
}

MeshDefects checkMesh(const Mesh& mesh) {
    MeshDefects d;
    const uint32_t nv = mesh.vertexCount(), nf = mesh.faceCount();

    for (uint32_t f = 0; f < nf; ++f)
        for (uint32_t v : mesh.faces[f])
            if (v >= nv) {
                if (!d.outOfRangeFaces++) {
                    d.firstOutOfRangeFace = f;
                    d.badIndex = v;
                }
                break;
            }
    for (uint32_t v = 0; v < nv; ++v) {
        const Vec3& p = mesh.positions[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            if (!d.nonFiniteVertices++) d.firstNonFiniteVertex = v;
    }
    if (d.outOfRangeFaces) return d;

    std::vector<uint8_t> used(nv, 0);
    for (const Tri& t : mesh.faces)
        for (uint32_t v : t) used[v] = 1;
    d.unreferencedVertices = uint64_t(std::count(used.begin(), used.end(), 0));

    std::vector<uint8_t> ignore = degenerateFaces(mesh);
    for (uint32_t f = 0; f < nf; ++f)
        if (ignore[f] && !d.degenerateFaces++) d.firstDegenerateFace = f;
    const std::vector<uint8_t> dup = duplicateFaces(mesh, ignore);
    for (uint32_t f = 0; f < nf; ++f)
        if (dup[f]) {
            if (!d.duplicateFaces++) d.firstDuplicateFace = f;
            ignore[f] = 1;
        }

    // Groups come sorted by (lower vertex, upper vertex), so the first group found
    // with a defect is the lowest-numbered edge.
    const EdgeGroups groups = groupEdges(mesh, ignore);
    CornerSets fans(mesh.halfedgeCount());
    for (uint32_t g = 0; g < groups.count(); ++g) {
        const uint32_t b = groups.start[g], n = groups.start[g + 1] - b;
        const int32_t h0 = groups.halfedges[b];
        const uint32_t lo = std::min(mesh.tail(h0), mesh.head(h0)), hi = std::max(mesh.tail(h0), mesh.head(h0));
        if (n == 2 && mesh.tail(h0) == mesh.tail(groups.halfedges[b + 1])) {
            if (!d.misorientedEdges++) d.firstMisorientedEdge[0] = lo, d.firstMisorientedEdge[1] = hi;
        } else if (n > 2) {
            if (!d.nonManifoldEdges++) d.firstNonManifoldEdge[0] = lo, d.firstNonManifoldEdge[1] = hi;
        }
        // Faces sharing an edge belong to the same fan at both of its ends.
        for (uint32_t i = 1; i < n; ++i) {
            const int32_t h = groups.halfedges[b + i];
            fans.unite(cornerAt(mesh, h0, lo), cornerAt(mesh, h, lo));
            fans.unite(cornerAt(mesh, h0, hi), cornerAt(mesh, h, hi));
        }
    }
    // Each fan has exactly one root corner; a vertex with two roots is non-manifold.
    std::vector<uint32_t> fanCount(nv, 0);
    for (uint32_t c = 0; c < mesh.halfedgeCount(); ++c)
        if (!ignore[c / 3] && fans.find(c) == c) ++fanCount[mesh.tail(int32_t(c))];
    for (uint32_t v = 0; v < nv; ++v)
        if (fanCount[v] > 1 && !d.nonManifoldVertices++) d.firstNonManifoldVertex = v;
    return d;
}

}  // namespace vorogeo
