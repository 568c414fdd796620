// The baker's compact triangle mesh: flat position and triangle arrays plus the
// half-edge connectivity that geodesic code walks in its hot loops.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace vorogeo {

struct Vec3 {
    double x = 0, y = 0, z = 0;
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline double distance(Vec3 a, Vec3 b) { return length(a - b); }

using Tri = std::array<uint32_t, 3>;

// Half-edge h = 3*f + k runs from faces[f][k] to faces[f][(k+1)%3]; its twin is the
// half-edge of the neighbouring face along the same edge, or -1 on a boundary.
// Connectivity is valid only for an oriented 2-manifold (with boundary), which is
// what validation guarantees before anything calls buildConnectivity().
struct Mesh {
    std::vector<Vec3> positions;
    std::vector<Tri> faces;

    // Filled by buildConnectivity().
    std::vector<int32_t> twin;        // 3F entries
    std::vector<int32_t> vertexOut;   // V entries: an outgoing half-edge, -1 if isolated;
                                      // for a boundary vertex the one with no twin, so that
                                      // rotating with nextAroundVertex() visits every face.
    std::vector<uint8_t> boundaryVertex;  // V entries: 1 if on a boundary loop

    uint32_t vertexCount() const { return static_cast<uint32_t>(positions.size()); }
    uint32_t faceCount() const { return static_cast<uint32_t>(faces.size()); }
    uint32_t halfedgeCount() const { return 3u * faceCount(); }

    static int32_t faceOf(int32_t h) { return h / 3; }
    static int32_t next(int32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
    static int32_t prev(int32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }
    uint32_t tail(int32_t h) const { return faces[h / 3][h % 3]; }
    uint32_t head(int32_t h) const { return faces[h / 3][(h % 3 + 1) % 3]; }
    // The vertex of h's face that is not on h.
    uint32_t apex(int32_t h) const { return faces[h / 3][(h % 3 + 2) % 3]; }
    double edgeLength(int32_t h) const { return distance(positions[tail(h)], positions[head(h)]); }

    // Next outgoing half-edge of tail(h), turning through the face before h; -1 at a boundary.
    int32_t nextAroundVertex(int32_t h) const { return twin[prev(h)]; }
};

// A half-edge with the key of its undirected edge (lower vertex id in the high 32 bits).
struct HalfedgeKey {
    uint64_t edge;
    int32_t h;
};
// All half-edges sorted by undirected edge, then by id: the half-edges of one edge are
// adjacent. Needs only the face list.
std::vector<HalfedgeKey> halfedgesByEdge(const Mesh& mesh);

// Result of buildConnectivity: ok, or the first problem found.
struct ConnectivityReport {
    bool ok = true;
    uint64_t nonManifoldEdges = 0;      // edges used by more than two faces, or twice in one direction
    uint64_t nonManifoldVertices = 0;   // vertices whose faces form more than one fan
    int64_t firstBadVertex = -1;
};

// Builds twin, vertexOut and boundaryVertex. On a non-manifold input it reports the
// counts and leaves the connectivity arrays empty.
ConnectivityReport buildConnectivity(Mesh& mesh);

// Interior angle of face f at its corner k.
double cornerAngle(const Mesh& mesh, uint32_t f, int k);

// Sum of the face angles around every vertex (2*pi on a flat interior vertex).
std::vector<double> vertexAngleSums(const Mesh& mesh);

}  // namespace vorogeo
