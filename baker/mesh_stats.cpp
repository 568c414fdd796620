#include "mesh_stats.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace vorogeo {
namespace {

void requireConnectivity(const Mesh& mesh) {
    if (mesh.twin.size() != mesh.halfedgeCount() || mesh.vertexOut.size() != mesh.vertexCount())
        throw std::invalid_argument("mesh statistics need a prepared mesh (call prepareMesh or loadMesh first)");
}

}  // namespace

std::vector<uint32_t> vertexComponents(const Mesh& mesh, std::vector<uint32_t>* faceComponent) {
    requireConnectivity(mesh);
    std::vector<uint32_t> faceComp(mesh.faceCount(), kNoComponent);
    std::vector<uint32_t> queue;
    uint32_t next = 0;
    for (uint32_t seed = 0; seed < mesh.faceCount(); ++seed) {
        if (faceComp[seed] != kNoComponent) continue;
        faceComp[seed] = next;
        queue.assign(1, seed);
        for (size_t q = 0; q < queue.size(); ++q)
            for (int k = 0; k < 3; ++k) {
                const int32_t t = mesh.twin[3 * queue[q] + k];
                if (t >= 0 && faceComp[t / 3] == kNoComponent) {
                    faceComp[t / 3] = next;
                    queue.push_back(uint32_t(t / 3));
                }
            }
        ++next;
    }
    std::vector<uint32_t> vertexComp(mesh.vertexCount(), kNoComponent);
    for (uint32_t f = 0; f < mesh.faceCount(); ++f)
        for (uint32_t v : mesh.faces[f]) vertexComp[v] = faceComp[f];
    if (faceComponent) *faceComponent = std::move(faceComp);
    return vertexComp;
}

BoundaryLoops boundaryLoops(const Mesh& mesh) {
    requireConnectivity(mesh);
    BoundaryLoops out;
    out.vertexLoop.assign(mesh.vertexCount(), -1);
    std::vector<uint8_t> seen(mesh.halfedgeCount(), 0);
    for (uint32_t start = 0; start < mesh.halfedgeCount(); ++start) {
        if (mesh.twin[start] >= 0 || seen[start]) continue;
        const int32_t loop = int32_t(out.loops.size());
        out.loops.emplace_back();
        // A manifold boundary vertex has exactly one outgoing boundary half-edge, and
        // buildConnectivity stores it as vertexOut: that is the loop's next step.
        for (int32_t h = int32_t(start); !seen[h]; h = mesh.vertexOut[mesh.head(h)]) {
            seen[h] = 1;
            out.loops.back().push_back(h);
            out.vertexLoop[mesh.tail(h)] = loop;
        }
    }
    return out;
}

std::vector<uint8_t> holeAdjacentVertices(const Mesh& mesh) {
    const BoundaryLoops loops = boundaryLoops(mesh);
    std::vector<uint8_t> mark(mesh.vertexCount(), 0);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) mark[v] = loops.vertexLoop[v] >= 0;
    return mark;
}

MeshStats computeStats(const Mesh& mesh) {
    requireConnectivity(mesh);
    MeshStats s;
    s.vertices = mesh.vertexCount();
    s.faces = mesh.faceCount();

    std::vector<uint32_t> faceComp;
    const std::vector<uint32_t> vertexComp = vertexComponents(mesh, &faceComp);
    const BoundaryLoops loops = boundaryLoops(mesh);
    uint32_t componentCount = 0;
    for (uint32_t c : faceComp) componentCount = std::max(componentCount, c + 1);
    s.components = componentCount;
    s.componentList.resize(componentCount);
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) ++s.componentList[faceComp[f]].faces;
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        if (vertexComp[v] == kNoComponent) ++s.isolatedVertices;
        else ++s.componentList[vertexComp[v]].vertices;
    }
    for (const auto& loop : loops.loops) ++s.componentList[faceComp[loop.front() / 3]].boundaryLoops;
    s.boundaryLoops = loops.loops.size();

    // Every undirected edge once: boundary half-edges, and the lower of each twin pair.
    double sum = 0;
    s.edgeLenMin = std::numeric_limits<double>::infinity();
    for (uint32_t h = 0; h < mesh.halfedgeCount(); ++h) {
        const int32_t t = mesh.twin[h];
        if (t >= 0 && t < int32_t(h)) continue;
        s.boundaryEdges += t < 0;
        ++s.componentList[faceComp[h / 3]].edges;
        const double l = mesh.edgeLength(int32_t(h));
        sum += l;
        s.edgeLenMin = std::min(s.edgeLenMin, l);
        s.edgeLenMax = std::max(s.edgeLenMax, l);
        ++s.edges;
    }
    s.edgeLenMean = s.edges ? sum / double(s.edges) : 0;
    if (!s.edges) s.edgeLenMin = 0;

    for (ComponentStats& c : s.componentList) {
        c.euler = int64_t(c.vertices) - int64_t(c.edges) + int64_t(c.faces);
        c.genus = (2 - c.euler - int64_t(c.boundaryLoops)) / 2;
        s.euler += c.euler;
        s.genus += c.genus;
    }

    if (mesh.vertexCount()) {
        s.bboxMin = s.bboxMax = mesh.positions[0];
        for (const Vec3& p : mesh.positions) {
            s.bboxMin = {std::min(s.bboxMin.x, p.x), std::min(s.bboxMin.y, p.y), std::min(s.bboxMin.z, p.z)};
            s.bboxMax = {std::max(s.bboxMax.x, p.x), std::max(s.bboxMax.y, p.y), std::max(s.bboxMax.z, p.z)};
        }
        s.bboxDiag = distance(s.bboxMin, s.bboxMax);
    }

    for (const Tri& t : mesh.faces)
        s.area += 0.5 * length(cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]));

    // A flat interior vertex sums to 2*pi up to rounding; only clearly larger sums count
    // as saddles (the geodesic-relevant kind of vertex: shortest paths can pass through them).
    const std::vector<double> angles = vertexAngleSums(mesh);
    const double twoPi = 2 * M_PI, tolerance = 1e-9;
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        if (vertexComp[v] == kNoComponent || mesh.boundaryVertex[v]) continue;
        ++s.interiorVertices;
        const bool saddle = angles[v] > twoPi + tolerance;
        s.saddleVertices += saddle;
        s.nearFlatSaddleVertices += saddle && angles[v] < twoPi * (1 + kNearFlatSaddleExcess);
    }
    const double interior = double(s.interiorVertices);
    s.saddleRatio = s.interiorVertices ? double(s.saddleVertices) / interior : 0;
    s.nearFlatSaddleRatio = s.interiorVertices ? double(s.nearFlatSaddleVertices) / interior : 0;
    return s;
}

}  // namespace vorogeo
