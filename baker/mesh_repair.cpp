#include "mesh_repair.h"

#include <algorithm>

#include "mesh_check.h"

namespace vorogeo {
namespace {

std::string plural(uint64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

uint64_t removeFaces(Mesh& mesh, const std::vector<uint8_t>& remove, std::vector<uint32_t>& sourceFace) {
    uint32_t out = 0;
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        if (remove[f]) continue;
        mesh.faces[out] = mesh.faces[f];
        if (!sourceFace.empty()) sourceFace[out] = sourceFace[f];
        ++out;
    }
    const uint64_t removed = mesh.faceCount() - out;
    mesh.faces.resize(out);
    if (!sourceFace.empty()) sourceFace.resize(out);
    return removed;
}

// Flips faces so that the two faces of every two-face edge traverse it in opposite
// directions. Per component the orientation flipping fewer faces wins. Returns the
// number of flipped faces; `conflicts` counts edges no choice can fix (non-orientable).
uint64_t orientFaces(Mesh& mesh, uint64_t& conflicts) {
    const uint32_t nf = mesh.faceCount();
    const EdgeGroups groups = groupEdges(mesh, std::vector<uint8_t>(nf, 0));
    struct Link {
        uint32_t f, g;
        bool sameDirection;
    };
    std::vector<Link> links;
    std::vector<uint32_t> degree(nf + 1, 0);
    for (uint32_t e = 0; e < groups.count(); ++e) {
        if (groups.start[e + 1] - groups.start[e] != 2) continue;
        const int32_t h0 = groups.halfedges[groups.start[e]], h1 = groups.halfedges[groups.start[e] + 1];
        links.push_back({uint32_t(h0 / 3), uint32_t(h1 / 3), mesh.tail(h0) == mesh.tail(h1)});
        ++degree[h0 / 3];
        ++degree[h1 / 3];
    }
    // Compressed adjacency: neighbours of f are adj[first[f] .. first[f+1]).
    std::vector<uint32_t> first(nf + 1, 0);
    for (uint32_t f = 0; f < nf; ++f) first[f + 1] = first[f] + degree[f];
    std::vector<uint32_t> fill(first.begin(), first.end() - 1), adj(first[nf]);
    for (uint32_t i = 0; i < links.size(); ++i) {
        adj[fill[links[i].f]++] = i;
        adj[fill[links[i].g]++] = i;
    }

    std::vector<int8_t> flip(nf, -1);
    std::vector<uint32_t> component;
    for (uint32_t seed = 0; seed < nf; ++seed) {
        if (flip[seed] >= 0) continue;
        component.assign(1, seed);
        flip[seed] = 0;
        uint32_t flipped = 0;
        for (size_t q = 0; q < component.size(); ++q) {
            const uint32_t f = component[q];
            for (uint32_t k = first[f]; k < first[f + 1]; ++k) {
                const Link& l = links[adj[k]];
                const uint32_t g = l.f == f ? l.g : l.f;
                if (flip[g] >= 0) continue;
                flip[g] = int8_t(flip[f] ^ int8_t(l.sameDirection));
                flipped += uint32_t(flip[g]);
                component.push_back(g);
            }
        }
        if (2 * size_t(flipped) > component.size())
            for (uint32_t f : component) flip[f] ^= 1;
    }
    conflicts = 0;
    for (const Link& l : links) conflicts += (flip[l.f] ^ flip[l.g]) != int8_t(l.sameDirection);
    uint64_t flipped = 0;
    for (uint32_t f = 0; f < nf; ++f)
        if (flip[f]) {
            std::swap(mesh.faces[f][1], mesh.faces[f][2]);
            ++flipped;
        }
    return flipped;
}

struct SplitCounts {
    uint64_t edgesCut = 0, verticesSplit = 0, verticesAdded = 0, facesDetached = 0;
};

// Index in `group` of the half-edge glued to the group's first opposite pair partner, or
// -1: the first pair (in face order) traversing the edge in opposite directions.
std::pair<int, int> gluedPair(const Mesh& mesh, const int32_t* group, uint32_t n) {
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = i + 1; j < n; ++j)
            if (mesh.tail(group[i]) != mesh.tail(group[j])) return {int(i), int(j)};
    return {-1, -1};
}

// Gives every vertex one copy per fan, fans being joined only through "glued" edges:
// edges with one consistently oriented pair of faces (for an edge with more faces, the
// first such pair; the other faces are cut off it).
void splitFans(Mesh& mesh, SplitCounts& counts, bool countEdges) {
    const EdgeGroups groups = groupEdges(mesh, std::vector<uint8_t>(mesh.faceCount(), 0));
    CornerSets fans(mesh.halfedgeCount());
    for (uint32_t e = 0; e < groups.count(); ++e) {
        const uint32_t n = groups.start[e + 1] - groups.start[e];
        if (n < 2) continue;
        const int32_t* group = &groups.halfedges[groups.start[e]];
        const auto [i, j] = gluedPair(mesh, group, n);
        if (countEdges && (n > 2 || i < 0)) ++counts.edgesCut;
        if (i < 0) continue;
        const uint32_t a = mesh.tail(group[i]), b = mesh.head(group[i]);
        fans.unite(cornerAt(mesh, group[i], a), cornerAt(mesh, group[j], a));
        fans.unite(cornerAt(mesh, group[i], b), cornerAt(mesh, group[j], b));
    }
    // Corners are visited in order and a set's root is its lowest corner, so the fan
    // with the lowest corner keeps the original vertex number.
    std::vector<int64_t> fanVertex(mesh.halfedgeCount(), -1);
    std::vector<uint8_t> taken(mesh.vertexCount(), 0), split(mesh.vertexCount(), 0);
    for (uint32_t c = 0; c < mesh.halfedgeCount(); ++c) {
        const uint32_t root = fans.find(c);
        if (fanVertex[root] < 0) {
            const uint32_t v = mesh.tail(int32_t(c));
            if (!taken[v]) {
                taken[v] = 1;
                fanVertex[root] = v;
            } else {
                fanVertex[root] = mesh.vertexCount();
                mesh.positions.push_back(mesh.positions[v]);
                ++counts.verticesAdded;
                counts.verticesSplit += !split[v];
                split[v] = 1;
            }
        }
    }
    for (uint32_t c = 0; c < mesh.halfedgeCount(); ++c) mesh.faces[c / 3][c % 3] = uint32_t(fanVertex[fans.find(c)]);
}

// Last resort for configurations fan splitting cannot untangle (a face cut off an edge
// that still reaches the same vertex copies through other faces): such faces get
// private copies of their three vertices. Returns the number of detached faces.
uint64_t detachFacesOnBadEdges(Mesh& mesh) {
    const EdgeGroups groups = groupEdges(mesh, std::vector<uint8_t>(mesh.faceCount(), 0));
    std::vector<uint8_t> detach(mesh.faceCount(), 0);
    for (uint32_t e = 0; e < groups.count(); ++e) {
        const uint32_t n = groups.start[e + 1] - groups.start[e];
        const int32_t* group = &groups.halfedges[groups.start[e]];
        if (n < 2) continue;
        const auto [i, j] = gluedPair(mesh, group, n);
        if (n == 2 && i >= 0) continue;
        for (uint32_t k = 0; k < n; ++k)
            if (int(k) != i && int(k) != j && (i >= 0 || k > 0)) detach[group[k] / 3] = 1;
    }
    uint64_t count = 0;
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        if (!detach[f]) continue;
        ++count;
        for (uint32_t& v : mesh.faces[f]) {
            mesh.positions.push_back(mesh.positions[v]);
            v = mesh.vertexCount() - 1;
        }
    }
    return count;
}

}  // namespace

void repairMesh(Mesh& mesh, std::vector<uint32_t>& sourceFace, std::vector<std::string>& notices) {
    if (uint64_t n = removeFaces(mesh, degenerateFaces(mesh), sourceFace))
        notices.push_back("repair: dropped " + plural(n, "degenerate face", "degenerate faces") +
                          " (zero area or repeated vertex)");
    if (uint64_t n = removeFaces(mesh, duplicateFaces(mesh, std::vector<uint8_t>(mesh.faceCount(), 0)), sourceFace))
        notices.push_back("repair: dropped " + plural(n, "duplicate face", "duplicate faces"));

    uint64_t conflicts = 0;
    if (uint64_t n = orientFaces(mesh, conflicts))
        notices.push_back("repair: flipped " + plural(n, "face", "faces") + " to orient every component consistently");
    if (conflicts)
        notices.push_back("repair: " + plural(conflicts, "edge", "edges") +
                          " cannot be oriented consistently (non-orientable surface) and will be cut");

    SplitCounts counts;
    splitFans(mesh, counts, true);
    for (int round = 0; round < 4 && !checkMesh(mesh).clean(); ++round) {
        counts.facesDetached += detachFacesOnBadEdges(mesh);
        splitFans(mesh, counts, false);
    }
    if (counts.edgesCut)
        notices.push_back("repair: cut " + plural(counts.edgesCut, "non-manifold edge", "non-manifold edges") +
                          " (faces beyond one consistently oriented pair no longer share it)");
    if (counts.verticesSplit)
        notices.push_back("repair: split " + plural(counts.verticesSplit, "non-manifold vertex", "non-manifold vertices") +
                          " into one copy per fan of faces (added " +
                          plural(counts.verticesAdded, "vertex", "vertices") + ")");
    if (counts.facesDetached)
        notices.push_back("repair: detached " + plural(counts.facesDetached, "face", "faces") +
                          " that could not share their edges manifoldly (each got its own 3 vertices)");
}

}  // namespace vorogeo
