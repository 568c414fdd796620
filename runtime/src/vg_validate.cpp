// The blob is untrusted input: after the flatbuffers verifier has checked that every
// vector lies inside the buffer, this checks what the queries assume, so that no query
// can read out of bounds whatever the bytes: every index in range, every count
// consistent, every back reference (vertex -> slot -> vertex, node -> membership -> node)
// pointing home, positions and scales finite. One pass over each array.
#include "vg_validate.h"
#include "vorogeo_container.h"
#include "vorogeo_distance_coding.h"

#include "vorogeo_coded_sequences.h"
#include "vorogeo_topology_coding.h"

#include "vorogeo_generated.h"

namespace vg {
namespace {

static_assert(sizeof(Patch) == sizeof(vorogeo::fb::PatchRecord), "PatchRecord layout");
static_assert(alignof(Patch) == alignof(vorogeo::fb::PatchRecord), "PatchRecord alignment");
static_assert(sizeof(Membership) == sizeof(vorogeo::fb::Membership), "Membership layout");
static_assert(sizeof(PatchEdge) == sizeof(vorogeo::fb::PatchEdge), "PatchEdge layout");
static_assert(sizeof(HubTreeNode) == sizeof(vorogeo::fb::HubTreeNode), "HubTreeNode layout");
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the runtime reads flatbuffer vectors in place and needs a little-endian target"
#endif

template <class T>
const T* raw(const flatbuffers::Vector<T>* v) {
    return v ? v->data() : nullptr;
}
template <class S, class T>
const S* rawStructs(const flatbuffers::Vector<const T*>* v) {
    return v ? reinterpret_cast<const S*>(v->data()) : nullptr;
}
template <class V>
uint64_t count(const V* v) {
    return v ? v->size() : 0;
}

bool finite(float x) { return x == x && x - x == 0.0f; }

// The verifier checks that vectors lie inside the buffer, not that their elements are
// aligned for their type (a crafted buffer can put 8-byte structs at 4-byte offsets).
template <class T>
bool aligned(const T* p) {
    return (reinterpret_cast<uintptr_t>(p) & (alignof(T) - 1)) == 0;
}


// Second layer: node rows over all slots, then the interior triangle (vg_graph.h). First
// layer (`nodesOnly`): whole node x node matrices (a lone first-layer patch has no nodes).
bool patchesValid(const Patch* patches, uint64_t patchCount, uint64_t slotCount, uint64_t entryCapacity,
                  uint64_t parentLimit, bool nodesOnly) {
    for (uint64_t i = 0; i < patchCount; ++i) {
        const Patch& p = patches[i];
        if (uint64_t(p.slotBegin) + p.slotCount > slotCount) return false;
        if ((p.slotCount == 0 && !nodesOnly) || p.nodeCount > p.slotCount || p.slotCount > 65536u) return false;
        if (nodesOnly && p.nodeCount != p.slotCount) return false;
        const uint64_t n = p.slotCount, entries = nodesOnly ? n * n : secondMatrixEntries(n, p.nodeCount);
        if (p.matrixBegin > entryCapacity || entries > entryCapacity - p.matrixBegin) return false;
        if (!finite(p.scale) || p.scale < 0.0f) return false;
        if (parentLimit != 0 && p.parent >= parentLimit) return false;
    }
    return true;
}

bool slotsValid(const Patch* patches, uint64_t patchCount, const uint32_t* slots, uint64_t nodes,
                uint64_t vertices) {
    for (uint64_t i = 0; i < patchCount; ++i) {
        const Patch& p = patches[i];
        for (uint32_t s = 0; s < p.slotCount; ++s) {
            const uint32_t id = slots[p.slotBegin + s];
            if (s < p.nodeCount ? id >= nodes : id >= vertices) return false;
        }
    }
    return true;
}

bool membershipsValid(const uint32_t* begin, const Membership* list, uint64_t listSize, uint64_t nodes,
                      const Patch* patches, uint64_t patchCount, const uint32_t* slots) {
    if (begin[0] != 0 || begin[nodes] != listSize) return false;
    for (uint64_t n = 0; n < nodes; ++n) {
        // Each offset within the list, not only the last one: a list is read before the
        // next offsets are checked.
        if (begin[n] > begin[n + 1] || begin[n + 1] > listSize) return false;
        for (uint32_t m = begin[n]; m < begin[n + 1]; ++m) {
            if (list[m].patch >= patchCount) return false;
            const Patch& p = patches[list[m].patch];
            if (list[m].slot >= p.nodeCount || slots[p.slotBegin + list[m].slot] != n) return false;
        }
    }
    return true;
}

// Faces: used corners held by the face's patch, twins that pair up along the same edge
// in opposite directions, and each used vertex's half-edge starting at it. Needs the
// vertex, node and patch checks above.
bool facesValid(const vg_graph& g) {
    const uint64_t H = 3 * uint64_t(g.faceCount);
    for (uint64_t h = 0; h < H; ++h) {
        const uint32_t v = g.faceVertices[h];
        if (v >= g.vertexCount || g.vertexPatch[v] == kNone) return false;
    }
    for (uint64_t f = 0; f < g.faceCount; ++f) {
        const uint32_t patch = g.facePatch[f];
        if (patch >= g.secondCount) return false;
        for (uint32_t k = 0; k < 3; ++k)
            if (slotIn(g, g.faceVertices[3 * f + k], patch) == kNone) return false;
    }
    // Face by face, so that h's next half-edge needs no division (this loop is a third of
    // a large blob's validation).
    for (uint64_t f = 0; f < g.faceCount; ++f) {
        const uint32_t* corner = g.faceVertices + 3 * f;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint64_t h = 3 * f + k;
            const uint32_t t = g.faceTwin[h];
            if (t == kNone) continue;
            if (t >= H || t == h || g.faceTwin[t] != h) return false;
            const uint32_t tailH = corner[k], headH = corner[k == 2 ? 0 : k + 1];
            if (g.faceVertices[t] != headH || g.faceVertices[nextHalfedge(t)] != tailH) return false;
        }
    }
    for (uint64_t v = 0; v < g.vertexCount; ++v) {
        const uint32_t h = g.vertexHalfedge[v];
        if (g.vertexPatch[v] == kNone) {
            if (h != kNone) return false;
            continue;
        }
        if (h >= H || g.faceVertices[h] != v) return false;
    }
    return true;
}

// Hub labels (optional, all or none): a tree in preorder whose hub ranges tile [0, H) and
// whose path positions add up; per tree node a column matrix exactly as large as its blocks
// and its subtree's hubs say; inner rows whose nodes are increasing node ids and whose
// matrices are as large as their patches say. The query reads within these bounds whatever
// the numbers are.
// Exit lists (optional beside the labels, all three or none): per second-layer patch one
// list per block of its first-layer patch's tree path, each an increasing run of indices
// below the number of that patch's slots that are hubs. (The query also skips an entry
// whose hub lies outside the block's rows, so no list can make it read past a matrix.)
bool exitListsValid(const vorogeo::fb::Graph* g, vg_graph& out) {
    const bool any = g->hub_exit_patch_begin() || g->hub_exit_list_begin() || g->hub_exit_lists();
    if (!any) return true;
    if (!g->hub_exit_patch_begin() || !g->hub_exit_list_begin() || !g->hub_exit_lists()) return false;
    const uint32_t* patchBegin = raw(g->hub_exit_patch_begin());
    const uint32_t* listBegin = raw(g->hub_exit_list_begin());
    const uint16_t* lists = raw(g->hub_exit_lists());
    if (!aligned(patchBegin) || !aligned(listBegin) || !aligned(lists)) return false;
    const uint64_t S2 = out.secondCount;
    if (count(g->hub_exit_patch_begin()) != S2 + 1 || patchBegin[0] != 0) return false;
    for (uint64_t q = 0; q < S2; ++q) {
        const uint32_t p = out.second[q].parent;
        if (p >= out.firstCount) return false;
        uint64_t pathBlocks = 0;  // the blocks of p's tree path (a valid tree: the walk ends)
        for (uint32_t t = out.hubFirstLeaf[p]; t != kNone; t = out.hubTree[t].parent)
            pathBlocks += hubBlocksOf(out.hubTree[t]);
        if (patchBegin[q + 1] < patchBegin[q] || patchBegin[q + 1] - patchBegin[q] != pathBlocks) return false;
    }
    const uint64_t lists64 = count(g->hub_exit_lists());
    if (count(g->hub_exit_list_begin()) != uint64_t(patchBegin[S2]) + 1 || listBegin[0] != 0 ||
        listBegin[patchBegin[S2]] != lists64)
        return false;
    for (uint64_t q = 0; q < S2; ++q) {
        const Patch& first = out.first[out.second[q].parent];
        uint32_t exits = 0;
        for (uint32_t k = 0; k < first.slotCount; ++k) exits += out.nodeHub[out.slots[first.slotBegin + k]] != kNone;
        for (uint32_t i = patchBegin[q]; i < patchBegin[q + 1]; ++i) {
            if (listBegin[i] > listBegin[i + 1] || listBegin[i + 1] > lists64) return false;
            for (uint32_t e = listBegin[i]; e < listBegin[i + 1]; ++e)
                if (lists[e] >= exits || (e > listBegin[i] && lists[e] <= lists[e - 1])) return false;
        }
    }
    out.hubExitPatchBegin = patchBegin;
    out.hubExitListBegin = listBegin;
    out.hubExitLists = lists;
    return true;
}

// A coded blob's distance, topology, sequence and position arrays and patch edge lengths
// are decoded where they lie: the index sequences first (the structure then verified
// again), the rest after every other array is checked. The flatbuffers verifier lets two
// vectors share bytes, so a crafted blob could make decoding rewrite indices that were
// already found in range: each decoded array must share no byte with any array the
// runtime reads. Everything a query reads is listed here.
bool decodedArraysApart(const vorogeo::fb::Graph* g) {
    struct Range {
        const uint8_t* begin;
        const uint8_t* end;
    };
    constexpr uint32_t kCapacity = 40;
    Range all[kCapacity];
    uint32_t n = 0;
    bool full = false;  // more arrays listed than room: refuse (every coded blob, so a test sees it)
    auto addBytes = [&](const void* data, uint64_t bytes) {
        if (n == kCapacity) {
            full = true;
            return;
        }
        const uint8_t* b = static_cast<const uint8_t*>(data);
        all[n++] = Range{b, b + bytes};
    };
    auto add = [&](const auto* v) {
        if (v != nullptr && v->size() != 0) addBytes(v->Data(), uint64_t(v->size()) * sizeof(*v->data()));
    };
    // The decoded ones first.
    add(g->positions());
    add(g->second_distances());
    add(g->first_distances());
    add(g->face_vertices());
    add(g->face_twin());
    add(g->vertex_halfedge());
    add(g->second_edges());  // its lengths
    vorogeo::forEachCodedSequence(g, [&](const uint32_t* data, uint64_t size) { addBytes(data, size * sizeof(uint32_t)); });
    const uint32_t decoded = n;
    add(g->vertex_patch());
    add(g->vertex_slot());
    add(g->face_patch());
    add(g->node_flags());
    add(g->node_second());
    add(g->node_first());
    add(g->landmark_vertex());
    add(g->landmark_scale());
    add(g->node_landmarks());
    add(g->second_patches());
    add(g->first_patches());
    add(g->hub_tree());
    add(g->hub_first_leaf());
    add(g->node_hub());
    add(g->hub_column_begin());
    add(g->hub_inner_begin());
    add(g->hub_inner_node());
    add(g->hub_inner_matrix_begin());
    add(g->hub_block_bounds());
    add(g->hub_landmarks());
    add(g->hub_exit_patch_begin());
    add(g->hub_exit_lists());
    if (full) return false;
    for (uint32_t i = 0; i < decoded; ++i)
        for (uint32_t j = 0; j < n; ++j)
            if (j != i && all[i].begin < all[j].end && all[j].begin < all[i].end) return false;
    return true;
}

bool hubsValid(const vorogeo::fb::Graph* g, uint64_t flatbufferSize, const Tables& tables, vg_graph& out) {
    out.hubTreeCount = 0;
    out.hubCount = 0;
    out.hubMaxPath = 0;
    out.hubBlockBounds = nullptr;
    out.hubLandmarks = nullptr;
    out.hubExitPatchBegin = nullptr;
    out.hubExitListBegin = nullptr;
    out.hubExitLists = nullptr;
    const uint64_t T = count(g->hub_tree());
    const uint64_t columnCount = g->hub_columns_count(), innerCount = g->hub_inner_count();
    const bool any = T != 0 || g->hub_first_leaf() || g->node_hub() || g->hub_column_begin() || columnCount != 0 ||
                     g->hub_inner_begin() || g->hub_inner_node() || g->hub_inner_matrix_begin() || innerCount != 0 ||
                     g->hub_block_bounds() || g->hub_landmarks() || tables.size != 0;
    if (!any) return true;
    // The tables after the flatbuffer: exactly the bytes their counts take.
    vg_label_tables at;
    if (!vg_label_tables_at(flatbufferSize, columnCount, innerCount, &at) || at.table_bytes != tables.size ||
        tables.bytes == nullptr)
        return false;
    const uint16_t* columns = reinterpret_cast<const uint16_t*>(tables.bytes);
    const uint16_t* inner = reinterpret_cast<const uint16_t*>(tables.bytes + (at.inner_offset - at.columns_offset));
    const uint64_t N = out.nodeCount, S1 = out.firstCount;
    if (T == 0 || T >= kNone || count(g->hub_column_begin()) != T + 1 || count(g->hub_first_leaf()) != S1 ||
        count(g->node_hub()) != N || count(g->hub_inner_begin()) != S1 + 1 ||
        count(g->hub_inner_matrix_begin()) != S1 + 1)
        return false;
    const float labelScale = g->hub_label_scale();
    if (!finite(labelScale) || labelScale < 0.0f) return false;
    const HubTreeNode* tree = rawStructs<HubTreeNode>(g->hub_tree());
    const uint64_t* columnBegin = raw(g->hub_column_begin());
    const uint64_t* matrixBegin = raw(g->hub_inner_matrix_begin());
    if (!aligned(tree) || !aligned(columnBegin) || !aligned(matrixBegin) || !aligned(columns) || !aligned(inner) ||
        !aligned(raw(g->node_hub())) || !aligned(raw(g->hub_first_leaf())) ||
        !aligned(raw(g->hub_inner_begin())) || !aligned(raw(g->hub_inner_node())))
        return false;
    uint64_t nextHub = 0, maxPath = 0, blocks = 0;
    for (uint64_t t = 0; t < T; ++t) {
        const HubTreeNode& n = tree[t];
        blocks += hubBlocksOf(n);
        if (t == 0 ? n.parent != kNone : n.parent >= t) return false;
        if (t > 0) {  // preorder: the parent is the previous node or one of its ancestors
            uint32_t a = uint32_t(t - 1);
            while (a != kNone && a != n.parent) a = tree[a].parent;
            if (a == kNone) return false;
        }
        const uint64_t parentEnd = t == 0 ? 0 : uint64_t(tree[n.parent].pathBegin) + tree[n.parent].hubCount;
        if (n.pathBegin != parentEnd || n.hubBegin != nextHub) return false;
        nextHub += n.hubCount;
        const uint64_t path = uint64_t(n.pathBegin) + n.hubCount;
        if (nextHub >= kNone || path > 65536u) return false;
        if (path > maxPath) maxPath = path;
    }
    const uint64_t H = nextHub;
    if (columnBegin[0] != 0 || columnBegin[T] != columnCount) return false;
    for (uint32_t t = 0; t < T; ++t) {  // each block: one row of kHubBlock entries per subtree hub
        const uint64_t rows = uint64_t(hubSubtreeEnd(tree, uint32_t(T), uint32_t(H), t)) - tree[t].hubBegin;
        const uint64_t entries = hubBlocksOf(tree[t]) * kHubBlock * rows;
        if (columnBegin[t] > columnBegin[t + 1] || columnBegin[t + 1] - columnBegin[t] != entries) return false;
    }
    const uint32_t* leaf = raw(g->hub_first_leaf());
    for (uint64_t p = 0; p < S1; ++p)
        if (leaf[p] >= T || out.first[p].slotCount > 65536u) return false;
    const uint32_t* nodeHub = raw(g->node_hub());
    for (uint64_t n = 0; n < N; ++n)
        if (nodeHub[n] != kNone && nodeHub[n] >= H) return false;
    const uint32_t* innerBegin = raw(g->hub_inner_begin());
    const uint32_t* innerNode = raw(g->hub_inner_node());
    if (innerBegin[0] != 0 || innerBegin[S1] != count(g->hub_inner_node()) || matrixBegin[0] != 0 ||
        matrixBegin[S1] != innerCount)
        return false;
    for (uint64_t p = 0; p < S1; ++p) {
        if (innerBegin[p] > innerBegin[p + 1] || innerBegin[p + 1] > count(g->hub_inner_node())) return false;
        for (uint32_t i = innerBegin[p]; i < innerBegin[p + 1]; ++i)
            if (innerNode[i] >= N || (i > innerBegin[p] && innerNode[i] <= innerNode[i - 1])) return false;
        const uint64_t entries = uint64_t(innerBegin[p + 1] - innerBegin[p]) * out.first[p].slotCount;
        if (matrixBegin[p] > matrixBegin[p + 1] || matrixBegin[p + 1] - matrixBegin[p] != entries) return false;
    }
    out.hubTreeCount = uint32_t(T);
    out.hubCount = uint32_t(H);
    out.hubMaxPath = uint32_t(maxPath);
    out.hubTree = tree;
    out.hubFirstLeaf = leaf;
    out.nodeHub = nodeHub;
    out.hubLabelScale = labelScale;
    out.hubColumnBegin = columnBegin;
    out.hubColumns = columns;
    out.hubInnerBegin = innerBegin;
    out.hubInnerNode = innerNode;
    out.hubInnerMatrixBegin = matrixBegin;
    out.hubInner = inner;
    // Block bounds (optional beside the labels): finite spheres, landmark ranges lo <= hi.
    if (g->hub_block_bounds()) {
        const float* bounds = raw(g->hub_block_bounds());
        const uint64_t stride = 4 + 2 * uint64_t(out.landmarkCount);
        if (count(g->hub_block_bounds()) != stride * blocks || !aligned(bounds)) return false;
        for (uint64_t b = 0; b < blocks; ++b) {
            const float* r = bounds + b * stride;
            if (!finite(r[0]) || !finite(r[1]) || !finite(r[2]) || !finite(r[3]) || r[3] < 0.0f) return false;
            for (uint64_t k = 0; k < out.landmarkCount; ++k)
                if (!(r[4 + 2 * k] <= r[5 + 2 * k])) return false;  // also NaN
        }
        out.hubBlockBounds = bounds;
    }
    // The hubs' landmark distances: every hub's, whenever there are landmarks (any values).
    const uint64_t landmarkEntries = uint64_t(out.hubCount) * out.landmarkCount;
    if (count(g->hub_landmarks()) != landmarkEntries) return false;
    if (landmarkEntries != 0) {
        if (!aligned(raw(g->hub_landmarks()))) return false;
        out.hubLandmarks = raw(g->hub_landmarks());
    }
    return exitListsValid(g, out);
}

}  // namespace

vg_status verifyAndBind(const unsigned char* flatbuffer, size_t size, const Tables& tables, vg_graph& graph,
                        bool codedTopology) {
    flatbuffers::Verifier verifier(flatbuffer, size);
    if (!vorogeo::fb::VerifyGraphBuffer(verifier)) return VG_ERR_CORRUPT_STRUCTURE;
    const vorogeo::fb::Graph* g = vorogeo::fb::GetGraph(flatbuffer);
    if (codedTopology) {
        if (!decodedArraysApart(g)) return VG_ERR_CORRUPT_STRUCTURE;
        // Any bytes decode to some indices, which are checked below as in an uncoded blob.
        vorogeo::forEachCodedSequence(g, [](const uint32_t* data, uint64_t size) {
            vg_code_sequence(const_cast<uint32_t*>(data), size, 1);
        });
        // The arrays are apart from each other, but a crafted blob can lay a coded sequence
        // over the flatbuffer's own structure (a table's offsets, a vtable, a vector's
        // length), which decoding then rewrites: the structure is verified again as it is
        // now, and the arrays found apart again, before anything is read through it.
        flatbuffers::Verifier again(flatbuffer, size);
        if (!vorogeo::fb::VerifyGraphBuffer(again) || !decodedArraysApart(g)) return VG_ERR_CORRUPT_STRUCTURE;
    }

    const uint64_t V = g->vertex_count();
    const uint64_t N = count(g->node_vertex());
    const uint64_t S2 = count(g->second_patches()), S1 = count(g->first_patches());
    const uint64_t slotCount = count(g->slots());
    if (V == 0 || V >= kNone || N >= kNone || S2 >= kNone || S1 >= kNone || S1 == 0 || S2 == 0)
        return VG_ERR_CORRUPT_CONTENT;
    if (count(g->positions()) != 3 * V || count(g->vertex_patch()) != V || count(g->vertex_slot()) != V ||
        count(g->node_flags()) != N || count(g->node_second_begin()) != N + 1 ||
        count(g->node_first_begin()) != N + 1 || count(g->node_edge_begin()) != N + 1)
        return VG_ERR_CORRUPT_CONTENT;
    if (!finite(g->bbox_diagonal()) || g->bbox_diagonal() < 0.0f) return VG_ERR_CORRUPT_CONTENT;

    vg_graph out;
    out.vertexCount = uint32_t(V);
    out.nodeCount = uint32_t(N);
    out.secondCount = uint32_t(S2);
    out.firstCount = uint32_t(S1);
    out.bboxDiagonal = g->bbox_diagonal();
    out.positions = raw(g->positions());
    out.vertexPatch = raw(g->vertex_patch());
    out.vertexSlot = raw(g->vertex_slot());
    const uint64_t F = count(g->face_patch());
    if (F >= kNone / 3 || count(g->face_vertices()) != 3 * F || count(g->face_twin()) != 3 * F ||
        count(g->vertex_halfedge()) != V)
        return VG_ERR_CORRUPT_CONTENT;
    out.faceCount = uint32_t(F);
    out.faceVertices = raw(g->face_vertices());
    out.faceTwin = raw(g->face_twin());
    out.facePatch = raw(g->face_patch());
    out.vertexHalfedge = raw(g->vertex_halfedge());
    out.nodeVertex = raw(g->node_vertex());
    out.nodeFlags = raw(g->node_flags());
    out.nodeSecondBegin = raw(g->node_second_begin());
    out.nodeSecond = rawStructs<Membership>(g->node_second());
    out.nodeFirstBegin = raw(g->node_first_begin());
    out.nodeFirst = rawStructs<Membership>(g->node_first());
    out.nodeEdgeBegin = raw(g->node_edge_begin());
    out.nodeEdge = raw(g->node_edge());
    const uint64_t K = count(g->landmark_vertex());
    if (K > kMaxLandmarks || count(g->landmark_scale()) != K || count(g->node_landmarks()) != N * K)
        return VG_ERR_CORRUPT_CONTENT;
    out.landmarkCount = uint32_t(K);
    out.landmarkScale = raw(g->landmark_scale());
    out.landmarkVertex = raw(g->landmark_vertex());
    out.nodeLandmarks = raw(g->node_landmarks());
    out.second = rawStructs<Patch>(g->second_patches());
    out.first = rawStructs<Patch>(g->first_patches());
    out.slots = raw(g->slots());
    out.secondEdges = rawStructs<PatchEdge>(g->second_edges());
    if (count(g->second_edges()) >= kNone) return VG_ERR_CORRUPT_CONTENT;
    out.secondEdgeCount = uint32_t(count(g->second_edges()));
    out.secondDistances = raw(g->second_distances());
    out.secondDistancesEnd = out.secondDistances + count(g->second_distances());
    out.firstDistances = raw(g->first_distances());
    out.firstDistancesEnd = out.firstDistances + count(g->first_distances());

    if (!aligned(out.positions) || !aligned(out.vertexPatch) || !aligned(out.vertexSlot) ||
        !aligned(out.nodeVertex) || !aligned(out.nodeSecondBegin) || !aligned(out.nodeSecond) ||
        !aligned(out.nodeFirstBegin) || !aligned(out.nodeFirst) || !aligned(out.nodeEdgeBegin) ||
        !aligned(out.nodeEdge) || !aligned(out.landmarkScale) || !aligned(out.nodeLandmarks) ||
        !aligned(out.second) || !aligned(out.first) || !aligned(out.slots) || !aligned(out.faceVertices) ||
        !aligned(out.secondEdges) ||
        !aligned(out.faceTwin) || !aligned(out.facePatch) || !aligned(out.vertexHalfedge))
        return VG_ERR_CORRUPT_STRUCTURE;
    for (uint64_t k = 0; k < K; ++k)
        if (!finite(out.landmarkScale[k]) || out.landmarkScale[k] < 0.0f || g->landmark_vertex()->Get(k) >= V)
            return VG_ERR_CORRUPT_CONTENT;
    // Patches of both layers, then their slot lists.
    if (!patchesValid(out.second, S2, slotCount, vg_coding_entries(count(g->second_distances())), S1, false) ||
        !patchesValid(out.first, S1, slotCount, vg_coding_entries(count(g->first_distances())), 0, true) ||
        !slotsValid(out.second, S2, out.slots, N, V) || !slotsValid(out.first, S1, out.slots, N, V))
        return VG_ERR_CORRUPT_CONTENT;

    // Nodes: strictly increasing vertices, memberships that point back.
    for (uint64_t n = 0; n < N; ++n) {
        if (out.nodeVertex[n] >= V || (n > 0 && out.nodeVertex[n] <= out.nodeVertex[n - 1]))
            return VG_ERR_CORRUPT_CONTENT;
    }
    if (!membershipsValid(out.nodeSecondBegin, out.nodeSecond, count(g->node_second()), N, out.second, S2, out.slots) ||
        !membershipsValid(out.nodeFirstBegin, out.nodeFirst, count(g->node_first()), N, out.first, S1, out.slots))
        return VG_ERR_CORRUPT_CONTENT;

    // Patch edges: each patch's range in order, both ends node slots of that patch, in
    // order of their first slot (the fill finds a slot's edges by where they start:
    // vg_workspace's slotFirstEdge), a length that unfolds (finite, not negative); in a
    // coded blob 0, the length being computed below (vorogeo_topology_coding.h).
    for (uint64_t i = 0; i < S1; ++i)
        if (out.first[i].edgeBegin != 0) return VG_ERR_CORRUPT_CONTENT;
    for (uint32_t i = 0; i < S2; ++i) {
        const uint32_t begin = out.second[i].edgeBegin, end = patchEdgesEnd(out, i);
        if (begin > end || end > out.secondEdgeCount) return VG_ERR_CORRUPT_CONTENT;
        for (uint32_t e = begin; e < end; ++e) {
            const PatchEdge& E = out.secondEdges[e];
            if (E.from >= out.second[i].nodeCount || E.to >= out.second[i].nodeCount || E.from == E.to ||
                (e > begin && E.from < out.secondEdges[e - 1].from) ||
                (codedTopology ? E.length != 0.0f : !finite(E.length) || E.length < 0.0f))
                return VG_ERR_CORRUPT_CONTENT;
        }
    }

    // Node edges: offsets in order, neighbours in range.
    if (out.nodeEdgeBegin[0] != 0 || out.nodeEdgeBegin[N] != count(g->node_edge())) return VG_ERR_CORRUPT_CONTENT;
    for (uint64_t n = 0; n < N; ++n) {
        if (out.nodeEdgeBegin[n] > out.nodeEdgeBegin[n + 1] || out.nodeEdgeBegin[n + 1] > count(g->node_edge()))
            return VG_ERR_CORRUPT_CONTENT;
        for (uint32_t e = out.nodeEdgeBegin[n]; e < out.nodeEdgeBegin[n + 1]; ++e)
            if (out.nodeEdge[e] >= N) return VG_ERR_CORRUPT_CONTENT;
    }

    // Vertices: the home slot holds the vertex (as itself, or as its node).
    out.unusedVertexCount = 0;
    for (uint64_t v = 0; v < V; ++v) {
        const uint32_t patch = out.vertexPatch[v];
        if (patch == kNone) {
            ++out.unusedVertexCount;
            continue;
        }
        if (patch >= S2) return VG_ERR_CORRUPT_CONTENT;
        const Patch& p = out.second[patch];
        const uint32_t slot = out.vertexSlot[v];
        if (slot >= p.slotCount) return VG_ERR_CORRUPT_CONTENT;
        const uint32_t id = out.slots[p.slotBegin + slot];
        if (slot < p.nodeCount ? out.nodeVertex[id] != v : id != v) return VG_ERR_CORRUPT_CONTENT;
    }
    // Every slot's vertex is a used vertex (so that its component is defined), an interior
    // slot only in its vertex's home patch and a node's vertex never in an interior slot:
    // one-to-all writes each interior vertex once, from its home patch, without comparing.
    for (uint64_t i = 0; i < S2; ++i) {
        const Patch& p = out.second[i];
        for (uint32_t s = p.nodeCount; s < p.slotCount; ++s) {
            const uint32_t v = out.slots[p.slotBegin + s];
            if (out.vertexPatch[v] != i || out.vertexSlot[v] != s) return VG_ERR_CORRUPT_CONTENT;
        }
    }
    for (uint64_t n = 0; n < N; ++n) {
        const uint32_t v = out.nodeVertex[n];
        if (out.vertexPatch[v] == kNone || out.vertexSlot[v] >= out.second[out.vertexPatch[v]].nodeCount)
            return VG_ERR_CORRUPT_CONTENT;
    }

    if (!hubsValid(g, size, tables, out)) return VG_ERR_CORRUPT_CONTENT;

    // Last, the arrays a coded blob decodes where they lie. Nothing is read through the
    // flatbuffer's structure from here on: a decoded array may lie over it (the arrays are
    // apart from each other, not from the tables' offsets or the vectors' lengths), so
    // decoding may rewrite it.
    if (codedTopology) vg_code_positions(const_cast<float*>(out.positions), 3 * V, 1);
    for (uint64_t i = 0; i < 3 * V; ++i)
        if (!finite(out.positions[i])) return VG_ERR_CORRUPT_CONTENT;
    if (codedTopology) {
        vg_code_topology(const_cast<uint32_t*>(out.faceVertices), const_cast<uint32_t*>(out.faceTwin),
                         3 * uint64_t(out.faceCount), const_cast<uint32_t*>(out.vertexHalfedge), V, 1);
        // The ends are node slots (checked above) of nodes whose vertices are in range, at
        // finite positions: the lengths are finite and not negative.
        PatchEdge* edges = const_cast<PatchEdge*>(out.secondEdges);
        for (uint32_t i = 0; i < S2; ++i) {
            const Patch& p = out.second[i];
            const uint32_t* slots = out.slots + p.slotBegin;
            for (uint32_t e = p.edgeBegin, end = patchEdgesEnd(out, i); e < end; ++e)
                edges[e].length = vg_patch_edge_length(out.positions, out.nodeVertex[slots[edges[e].from]],
                                                       out.nodeVertex[slots[edges[e].to]]);
        }
    }
    if (!facesValid(out)) return VG_ERR_CORRUPT_CONTENT;

    graph = out;
    return VG_OK;
}

}  // namespace vg
