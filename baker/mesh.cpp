#include "mesh.h"

#include <algorithm>
#include <utility>

namespace vorogeo {

std::vector<HalfedgeKey> halfedgesByEdge(const Mesh& mesh) {
    const uint32_t nh = mesh.halfedgeCount();
    std::vector<HalfedgeKey> keys(nh);
    for (uint32_t h = 0; h < nh; ++h) {
        uint64_t a = mesh.tail(int32_t(h)), b = mesh.head(int32_t(h));
        keys[h] = {(std::min(a, b) << 32) | std::max(a, b), int32_t(h)};
    }
    std::sort(keys.begin(), keys.end(), [](const HalfedgeKey& x, const HalfedgeKey& y) {
        return x.edge != y.edge ? x.edge < y.edge : x.h < y.h;
    });
    return keys;
}

ConnectivityReport buildConnectivity(Mesh& mesh) {
    ConnectivityReport report;
    const uint32_t nv = mesh.vertexCount();
    const uint32_t nh = mesh.halfedgeCount();

    const std::vector<HalfedgeKey> keys = halfedgesByEdge(mesh);  // twins become neighbours

    std::vector<int32_t> twin(nh, -1);
    auto noteBadVertex = [&](uint32_t v) {
        if (report.firstBadVertex < 0 || int64_t(v) < report.firstBadVertex) report.firstBadVertex = v;
    };
    for (uint32_t i = 0; i < nh;) {
        uint32_t j = i;
        while (j < nh && keys[j].edge == keys[i].edge) ++j;
        const uint32_t n = j - i;
        if (n == 2) {
            int32_t h0 = keys[i].h, h1 = keys[i + 1].h;
            if (mesh.tail(h0) == mesh.tail(h1)) {  // same direction: orientation flip or duplicate
                ++report.nonManifoldEdges;
                noteBadVertex(std::min(mesh.tail(h0), mesh.head(h0)));
            } else {
                twin[h0] = h1;
                twin[h1] = h0;
            }
        } else if (n > 2) {
            ++report.nonManifoldEdges;
            noteBadVertex(uint32_t(keys[i].edge >> 32));
        }
        i = j;
    }
    if (report.nonManifoldEdges) {
        report.ok = false;
        return report;
    }

    // Every vertex must see exactly one fan of faces.
    std::vector<int32_t> out(nv, -1);
    std::vector<uint32_t> valence(nv, 0);
    for (uint32_t h = 0; h < nh; ++h) {
        uint32_t v = mesh.tail(int32_t(h));
        ++valence[v];
        // Prefer the boundary half-edge so rotation from it covers the whole fan.
        if (out[v] < 0 || (twin[h] < 0 && twin[out[v]] >= 0)) out[v] = int32_t(h);
    }
    mesh.twin = std::move(twin);
    std::vector<uint8_t> boundary(nv, 0);
    for (uint32_t v = 0; v < nv; ++v) {
        if (out[v] < 0) continue;
        boundary[v] = mesh.twin[out[v]] < 0;
        uint32_t seen = 0;
        int32_t h = out[v];
        do {
            ++seen;
            h = mesh.nextAroundVertex(h);
        } while (h >= 0 && h != out[v] && seen <= valence[v]);
        if (seen != valence[v]) {
            ++report.nonManifoldVertices;
            noteBadVertex(v);
        }
    }
    if (report.nonManifoldVertices) {
        mesh.twin.clear();
        report.ok = false;
        return report;
    }
    mesh.vertexOut = std::move(out);
    mesh.boundaryVertex = std::move(boundary);
    return report;
}

double cornerAngle(const Mesh& mesh, uint32_t f, int k) {
    const Vec3& p = mesh.positions[mesh.faces[f][k]];
    Vec3 a = mesh.positions[mesh.faces[f][(k + 1) % 3]] - p;
    Vec3 b = mesh.positions[mesh.faces[f][(k + 2) % 3]] - p;
    // atan2 stays accurate for needle triangles where acos of a dot product does not.
    return std::atan2(length(cross(a, b)), dot(a, b));
}

std::vector<double> vertexAngleSums(const Mesh& mesh) {
    std::vector<double> sums(mesh.vertexCount(), 0.0);
    for (uint32_t f = 0; f < mesh.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) sums[mesh.faces[f][k]] += cornerAngle(mesh, f, k);
    return sums;
}

}  // namespace vorogeo
