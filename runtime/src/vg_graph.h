// The opened graph: raw views into the verified flatbuffer, and the few inline helpers
// every query uses (12-bit entry decoding, patch membership of a vertex, components).
// Internal to the runtime.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include "vorogeo.h"

namespace vg {

constexpr uint32_t kNone = 0xFFFFFFFFu;
constexpr uint32_t kNoPathQuantum = 4095;
constexpr uint8_t kNodeMergedAway = 1;  // node_flags bit 0
constexpr uint32_t kMaxLandmarks = 64;
constexpr uint16_t kLandmarkUnreachable = 65535;
constexpr uint32_t kHubBlock = 16;  // hubs per bounded block (vorogeo.fbs hub_block_bounds)

// Mirrors vorogeo.fb.PatchRecord / Membership (little-endian flatbuffer structs; the
// layout is checked against the generated code in vg_open.cpp).
struct Patch {
    uint32_t slotBegin;
    uint32_t slotCount;
    uint32_t nodeCount;
    uint32_t edgeBegin;  // second layer: first of its PatchEdges
    uint64_t matrixBegin;
    float scale;
    uint32_t parent;
};
struct Membership {
    uint32_t patch;
    uint32_t slot;
};
struct HubTreeNode {  // vorogeo.fb.HubTreeNode (bake --hub-labels)
    uint32_t parent, hubBegin, hubCount, pathBegin;
};
// Blocks of kHubBlock hubs that tree node n's hubs fill (the last one padded).
inline uint64_t hubBlocksOf(const HubTreeNode& n) { return (uint64_t(n.hubCount) + kHubBlock - 1) / kHubBlock; }
// End of the hubs of tree node t's subtree, [hubBegin, end) (of T nodes and H hubs): in
// preorder the subtree ends at the first later node whose parent comes before t.
inline uint32_t hubSubtreeEnd(const HubTreeNode* tree, uint32_t T, uint32_t H, uint32_t t) {
    for (uint32_t u = t + 1; u < T; ++u)
        if (tree[u].parent < t) return tree[u].hubBegin;
    return H;
}
struct PatchEdge {  // a mesh edge between two node slots of one second-layer patch
    uint16_t from, to;
    float length;
};

}  // namespace vg

struct vg_graph {
    uint32_t vertexCount, nodeCount, secondCount, firstCount;
    float bboxDiagonal;
    const float* positions;          // 3 per vertex
    const uint32_t* vertexPatch;     // home second-layer patch, kNone when unused
    uint32_t unusedVertexCount;      // vertices with no home patch (used by no face)
    const uint16_t* vertexSlot;
    uint32_t faceCount;
    const uint32_t* faceVertices;    // 3 per face; half-edge h = 3f + k runs faceVertices[h] -> next corner
    const uint32_t* faceTwin;        // 3 per face: opposite half-edge, kNone on a boundary
    const uint32_t* facePatch;       // per face: its second-layer patch
    const uint32_t* vertexHalfedge;  // per vertex: an outgoing half-edge (boundary: one without twin)
    const uint32_t* nodeVertex;
    const uint8_t* nodeFlags;
    const uint32_t* nodeSecondBegin;
    const vg::Membership* nodeSecond;
    const uint32_t* nodeFirstBegin;
    const vg::Membership* nodeFirst;
    const uint32_t* nodeEdgeBegin;   // N + 1 offsets into nodeEdge
    const uint32_t* nodeEdge;        // neighbour nodes joined by a mesh edge
    uint32_t landmarkCount;          // K, at most kMaxLandmarks
    const float* landmarkScale;      // K
    const uint32_t* landmarkVertex;  // K mesh vertices
    const uint16_t* nodeLandmarks;   // N x K, node-major; kLandmarkUnreachable = no path
    const vg::Patch* second;
    const vg::Patch* first;
    const uint32_t* slots;
    const vg::PatchEdge* secondEdges;   // per second-layer patch from its edgeBegin to the next one's
    uint32_t secondEdgeCount;
    const uint8_t* secondDistances;
    const uint8_t* secondDistancesEnd;  // one past its last byte: the row kernels stop before it
    const uint8_t* firstDistances;
    const uint8_t* firstDistancesEnd;   // one past its last byte
    bool avx2;                          // the row kernels may use AVX2 (vg_field_kernels.h)
    bool avx512;                        // ... and lower rows with AVX-512 (only with avx2)
    // Hub labels (bake --hub-labels; vg_hub_labels.cpp); hubTreeCount == 0 when absent.
    uint32_t hubTreeCount, hubCount;
    uint32_t hubMaxPath;                // longest tree path, in hubs
    const vg::HubTreeNode* hubTree;
    const uint32_t* hubFirstLeaf;       // per first-layer patch
    const uint32_t* nodeHub;            // per node: hub number or kNone
    float hubLabelScale;                // distance per step of labels and inner rows
    const uint64_t* hubColumnBegin;     // tree nodes + 1, into hubColumns
    const uint16_t* hubColumns;         // per tree node and block: kHubBlock entries per subtree hub
    const uint32_t* hubInnerBegin;      // first-layer patches + 1, into hubInnerNode
    const uint32_t* hubInnerNode;
    const uint64_t* hubInnerMatrixBegin;  // first-layer patches + 1, into hubInner
    const uint16_t* hubInner;
    const float* hubBlockBounds;        // per block of kHubBlock hubs: sphere, landmark ranges; null: none
    const uint16_t* hubLandmarks;       // per hub its landmark steps in the labels' metric (H x K); null: no landmarks
    // Per second-layer patch, the exits a label query needs in each block of its tree path
    // (vorogeo.fbs hub_exit_*); null: none, every exit is read.
    const uint32_t* hubExitPatchBegin;  // second-layer patches + 1, into hubExitListBegin
    const uint32_t* hubExitListBegin;   // into hubExitLists
    const uint16_t* hubExitLists;

    // Set by vg_open_file only: what vg_close_file releases.
    vg_allocator fileAllocator;
    void* fileMemory;
    void* fileMapping;
    size_t fileMappingSize;
};

namespace vg {

// Entry k of a packed 12-bit array, in quanta. It starts at bit 12k, so the 16 bits from
// byte 12k / 8 hold it shifted by 0 or 4 (branch-free: column walks meet both parities
// in no predictable order).
inline uint32_t quantum(const uint8_t* packed, uint64_t k) {
    const uint8_t* p = packed + ((3 * k) >> 1);
    const uint32_t word = uint32_t(p[0]) | (uint32_t(p[1]) << 8);
    return (word >> ((uint32_t(k) & 1u) << 2)) & 0xFFFu;
}

// Second-layer patch matrix (format 4), with n nodes among S slots and I = S - n others:
// the node x node block whole (n x n, row a "no path" at a: a search relaxes a node by one
// contiguous run, and a patch's node rows lie together), then the node x other block
// (n x I, row a: node a to every other slot, what the one-to-all fill reads), then the
// upper triangle of the other slots.
inline uint64_t nodeRowStart(const Patch& p, uint32_t a) { return p.matrixBegin + uint64_t(a) * p.nodeCount; }
inline uint64_t interiorRowStart(const Patch& p, uint32_t a) {
    return p.matrixBegin + uint64_t(p.nodeCount) * p.nodeCount + uint64_t(a) * (p.slotCount - p.nodeCount);
}

// Entries of a second-layer matrix with S slots of which n are nodes.
inline uint64_t secondMatrixEntries(uint64_t S, uint64_t n) { return n * S + (S - n) * (S - n - (S > n ? 1 : 0)) / 2; }

// Packed index of the entry for slots i != j.
inline uint64_t entryIndex(const Patch& p, uint32_t i, uint32_t j) {
    const uint32_t n = p.nodeCount;
    if (i < n) return j < n ? nodeRowStart(p, i) + j : interiorRowStart(p, i) + (j - n);
    if (j < n) return interiorRowStart(p, j) + (i - n);
    uint64_t a = i - n, b = j - n;  // two others: the triangle's row min, column max
    if (a > b) {
        const uint64_t t = a;
        a = b;
        b = t;
    }
    const uint64_t interior = p.slotCount - n;
    return p.matrixBegin + uint64_t(n) * p.slotCount + a * (2 * interior - a - 1) / 2 + (b - a - 1);
}

// Distance between slots i and j of a second-layer patch (0 on the diagonal, +inf for
// "no path").
inline float entry(const Patch& p, const uint8_t* packed, uint32_t i, uint32_t j) {
    if (i == j) return 0.0f;
    const uint32_t q = quantum(packed, entryIndex(p, i, j));
    return q == kNoPathQuantum ? __builtin_inff() : float(q) * p.scale;
}

// The edges of second-layer patch i: [begin, end) in secondEdges.
inline uint32_t patchEdgesEnd(const vg_graph& g, uint32_t i) {
    return i + 1 < g.secondCount ? g.second[i + 1].edgeBegin : g.secondEdgeCount;
}

inline bool nodeActive(const vg_graph& g, uint32_t node) { return (g.nodeFlags[node] & kNodeMergedAway) == 0; }

// The most slots of a first-layer patch, and the most nodes of a second-layer patch (what
// per-patch scratch is sized by).
inline uint64_t largestFirstPatch(const vg_graph& g) {
    uint64_t most = 0;
    for (uint32_t i = 0; i < g.firstCount; ++i) most = g.first[i].slotCount > most ? g.first[i].slotCount : most;
    return most;
}
inline uint64_t largestSecondPatchNodes(const vg_graph& g) {
    uint64_t most = 0;
    for (uint32_t i = 0; i < g.secondCount; ++i) most = g.second[i].nodeCount > most ? g.second[i].nodeCount : most;
    return most;
}

// Position of x among the `count` increasing ids at `ids` (bisection), kNone when absent.
inline uint32_t sortedIndex(const uint32_t* ids, uint32_t count, uint32_t x) {
    uint32_t lo = 0, hi = count;
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (ids[mid] < x) lo = mid + 1;
        else hi = mid;
    }
    return lo < count && ids[lo] == x ? lo : kNone;
}

// The node id of a vertex, or kNone when it is interior to its patch (or unused).
inline uint32_t vertexNode(const vg_graph& g, uint32_t v) {
    const uint32_t patch = g.vertexPatch[v];
    if (patch == kNone) return kNone;
    const Patch& p = g.second[patch];
    const uint32_t slot = g.vertexSlot[v];
    return slot < p.nodeCount ? g.slots[p.slotBegin + slot] : kNone;
}

// Slot of vertex v in second-layer patch `patch`, or kNone when the patch does not hold v.
inline uint32_t slotIn(const vg_graph& g, uint32_t v, uint32_t patch) {
    if (g.vertexPatch[v] == patch) return g.vertexSlot[v];
    const uint32_t node = vertexNode(g, v);
    if (node == kNone) return kNone;
    for (uint32_t m = g.nodeSecondBegin[node]; m < g.nodeSecondBegin[node + 1]; ++m)
        if (g.nodeSecond[m].patch == patch) return g.nodeSecond[m].slot;
    return kNone;
}

// Half-edge helpers: h = 3f + k.
inline uint32_t nextHalfedge(uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
inline uint32_t prevHalfedge(uint32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }
inline uint32_t tailOf(const vg_graph& g, uint32_t h) { return g.faceVertices[h]; }
inline uint32_t headOf(const vg_graph& g, uint32_t h) { return g.faceVertices[nextHalfedge(h)]; }

// The connected component of a used vertex (the parent of its first-layer patch).
inline uint32_t vertexComponent(const vg_graph& g, uint32_t v) {
    return g.first[g.second[g.vertexPatch[v]].parent].parent;
}

// Calls f(patch, slot) for every second-layer patch holding vertex v (used vertices only):
// all memberships of a node, the home patch of any other vertex.
template <class F>
inline void forEachPatchOf(const vg_graph& g, uint32_t v, F&& f) {
    const uint32_t node = vertexNode(g, v);
    if (node == kNone) {
        f(g.vertexPatch[v], uint32_t(g.vertexSlot[v]));
        return;
    }
    for (uint32_t m = g.nodeSecondBegin[node]; m < g.nodeSecondBegin[node + 1]; ++m)
        f(g.nodeSecond[m].patch, g.nodeSecond[m].slot);
}

// Unfolding a border edge (u, w) of length l into the plane, u at (0, 0) and w at (l, 0):
// a point at distances a from u and b from w sits at (x, -y) below the line (source
// side) or (x, y) above it (target side). The straight segment between a source point
// and a target point is how far s is from t across the edge: a geodesic that crosses a
// patch border between two vertices is this short, where a path through a border vertex
// is longer (by up to a few percent for pairs a few edges apart).
struct UnfoldedPoint {
    float x, y;
};

// False when the distances do not form a proper triangle with the edge (also for NaN, +inf).
inline bool unfoldPoint(float a, float b, float l, UnfoldedPoint& p) {
    if (!(l > 0.0f)) return false;
    p.x = (a * a - b * b + l * l) * (0.5f / l);
    const float y2 = a * a - p.x * p.x;
    if (!(y2 > 0.0f)) return false;
    p.y = __builtin_sqrtf(y2);
    return true;
}

// Unfolding assumes locally flat distance fields; where they are not, it could undercut
// the true distance. It is trusted to shorten a path through a border node by at most
// this factor (the searches prune with the same margin, which keeps bounded queries equal
// to unbounded ones).
constexpr float kUnfoldSlack = 1.15f;

// The segment from source point s to target point t across the edge, kept within
// kUnfoldSlack of the better node path (a + c through u, b + e through w); +inf when the
// segment misses the edge's interior.
inline float crossingLength(UnfoldedPoint s, UnfoldedPoint t, float l, float viaU, float viaW) {
    const float x = s.x + (t.x - s.x) * (s.y / (s.y + t.y));  // where the segment meets the edge line
    if (!(x > 0.0f && x < l)) return __builtin_inff();
    const float dx = t.x - s.x, dy = t.y + s.y;
    const float d = __builtin_sqrtf(dx * dx + dy * dy);
    const float viaNode = (viaU < viaW ? viaU : viaW) / kUnfoldSlack;
    return d < viaNode ? viaNode : d;
}

// The crossing of edge (u, w) from distances a = d(s,u), b = d(s,w), c = d(t,u), e = d(t,w).
inline float crossing(float a, float b, float c, float e, float l) {
    UnfoldedPoint s, t;
    if (!unfoldPoint(a, b, l, s) || !unfoldPoint(c, e, l, t)) return __builtin_inff();
    return crossingLength(s, t, l, a + c, b + e);
}

inline float euclidean(const vg_graph& g, uint32_t a, uint32_t b) {
    const float* pa = g.positions + 3 * uint64_t(a);
    const float* pb = g.positions + 3 * uint64_t(b);
    const float dx = pa[0] - pb[0], dy = pa[1] - pb[1], dz = pa[2] - pb[2];
    return __builtin_sqrtf(dx * dx + dy * dy + dz * dz);
}

}  // namespace vg
