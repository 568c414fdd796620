#include "patch_topology.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace vorogeo {
namespace {

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

bool isBorderHalfedge(const Mesh& mesh, const std::vector<uint32_t>& faceRegion, int32_t h) {
    const int32_t t = mesh.twin[h];
    return t < 0 || faceRegion[t / 3] != faceRegion[h / 3];
}

// The border half-edge that follows border half-edge h on its region's boundary loop:
// turn around head(h) through the region's faces until the region is left.
int32_t nextBorderHalfedge(const Mesh& mesh, const std::vector<uint32_t>& faceRegion, int32_t h) {
    int32_t g = Mesh::next(h);
    while (!isBorderHalfedge(mesh, faceRegion, g)) g = Mesh::next(mesh.twin[g]);
    return g;
}

}  // namespace

std::vector<RegionTopology> regionTopology(const Mesh& mesh, const std::vector<uint32_t>& faceRegion,
                                           uint32_t regionCount) {
    if (mesh.twin.size() != mesh.halfedgeCount() || faceRegion.size() != mesh.faceCount())
        throw std::invalid_argument("regionTopology: mesh connectivity or face labels missing");
    std::vector<RegionTopology> out(regionCount);
    const uint32_t nf = mesh.faceCount(), nh = mesh.halfedgeCount();

    std::vector<uint32_t> parent(nf);
    std::iota(parent.begin(), parent.end(), 0u);
    for (uint32_t f = 0; f < nf; ++f) {
        const uint32_t r = faceRegion[f];
        if (r == kNoRegion) continue;
        ++out[r].faces;
        for (int k = 0; k < 3; ++k) {
            const int32_t h = int32_t(3 * f + k), t = mesh.twin[h];
            if (t < 0 || faceRegion[t / 3] != r) {
                ++out[r].edges;
            } else if (h < t) {
                ++out[r].edges;
                const uint32_t a = findRoot(parent, f), b = findRoot(parent, uint32_t(t / 3));
                if (a != b) parent[std::max(a, b)] = std::min(a, b);
            }
        }
    }
    for (uint32_t f = 0; f < nf; ++f)
        if (faceRegion[f] != kNoRegion && findRoot(parent, f) == f) ++out[faceRegion[f]].components;

    std::vector<uint8_t> seen(nh, 0);
    for (uint32_t h = 0; h < nh; ++h) {
        const uint32_t r = faceRegion[h / 3];
        if (r == kNoRegion || seen[h] || !isBorderHalfedge(mesh, faceRegion, int32_t(h))) continue;
        ++out[r].boundaryLoops;
        for (int32_t g = int32_t(h); !seen[g]; g = nextBorderHalfedge(mesh, faceRegion, g)) seen[g] = 1;
    }

    // Around each vertex, the faces in rotation order; a region's fans are its maximal runs.
    std::vector<uint32_t> seq;
    std::vector<std::pair<uint32_t, uint32_t>> runs;  // (region, number of runs)
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        const int32_t h0 = mesh.vertexOut[v];
        if (h0 < 0) continue;
        seq.clear();
        int32_t h = h0;
        do {
            seq.push_back(faceRegion[h / 3]);
            h = mesh.nextAroundVertex(h);
        } while (h >= 0 && h != h0);
        const bool cyclic = h == h0;
        runs.clear();
        const size_t n = seq.size();
        for (size_t i = 0; i < n; ++i) {
            const uint32_t r = seq[i];
            if (r == kNoRegion) continue;
            const bool start = i > 0 ? seq[i - 1] != r : (!cyclic || seq[n - 1] != r);
            auto it = std::find_if(runs.begin(), runs.end(), [&](const auto& p) { return p.first == r; });
            if (it == runs.end()) {
                runs.push_back({r, 0});
                it = runs.end() - 1;
            }
            if (start) ++it->second;
        }
        for (const auto& [r, count] : runs) {
            ++out[r].vertices;
            if (count >= 2) {  // (0 runs: the region surrounds v completely, one fan)
                if (out[r].pinchedVertices++ == 0) out[r].firstPinchedVertex = v;
            }
        }
    }
    return out;
}

std::vector<std::vector<uint32_t>> regionBoundaryLoops(const Mesh& mesh, const std::vector<uint32_t>& faceRegion,
                                                       uint32_t region) {
    std::vector<std::vector<uint32_t>> loops;
    std::vector<uint8_t> seen(mesh.halfedgeCount(), 0);
    for (uint32_t h = 0; h < mesh.halfedgeCount(); ++h) {
        if (faceRegion[h / 3] != region || seen[h] || !isBorderHalfedge(mesh, faceRegion, int32_t(h))) continue;
        loops.emplace_back();
        for (int32_t g = int32_t(h); !seen[g]; g = nextBorderHalfedge(mesh, faceRegion, g)) {
            seen[g] = 1;
            loops.back().push_back(mesh.tail(g));
        }
    }
    return loops;
}

std::vector<std::vector<uint32_t>> cutIntoDisks(const Mesh& mesh, const std::vector<uint32_t>& faces) {
    std::vector<uint32_t> sorted = faces;
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    std::vector<uint8_t> inSet(mesh.faceCount(), 0);
    for (uint32_t f : sorted) inSet.at(f) = 1;
    std::vector<int32_t> pieceOf(mesh.faceCount(), -1);
    std::vector<int32_t> vertexPiece(mesh.vertexCount(), -1);  // last piece that used the vertex
    std::vector<std::vector<uint32_t>> pieces;
    std::vector<uint32_t> queue;
    for (uint32_t start : sorted) {
        if (pieceOf[start] >= 0) continue;
        const int32_t p = int32_t(pieces.size());
        pieces.emplace_back();
        queue.clear();
        auto add = [&](uint32_t f) {
            pieceOf[f] = p;
            pieces.back().push_back(f);
            for (int k = 0; k < 3; ++k) {
                vertexPiece[mesh.faces[f][k]] = p;
                const int32_t t = mesh.twin[3 * f + k];
                if (t >= 0 && inSet[t / 3] && pieceOf[t / 3] < 0) queue.push_back(uint32_t(t / 3));
            }
        };
        add(start);
        for (size_t q = 0; q < queue.size(); ++q) {
            const uint32_t f = queue[q];
            if (pieceOf[f] >= 0) continue;
            int shared = 0, sharedK = 0;
            for (int k = 0; k < 3; ++k) {
                const int32_t t = mesh.twin[3 * f + k];
                if (t >= 0 && pieceOf[t / 3] == p) ++shared, sharedK = k;
            }
            // One shared edge: the third vertex must be new (else an annulus or a pinch).
            // Two: the face closes the fan at their common vertex, still a disk.
            // Three: it would close a sphere.
            if ((shared == 1 && vertexPiece[mesh.faces[f][(sharedK + 2) % 3]] != p) || shared == 2) add(f);
        }
        std::sort(pieces.back().begin(), pieces.back().end());
    }
    return pieces;
}

}  // namespace vorogeo
