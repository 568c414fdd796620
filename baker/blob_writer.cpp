#include "blob_writer.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <unistd.h>
#include <zstd.h>

#include "bake_limits.h"
#include "distance_coding.h"
#include "mesh_stats.h"
#include "parallel.h"
#include "vorogeo_container.h"
#include "vorogeo_generated.h"
#include "vorogeo_topology_coding.h"

namespace vorogeo {

namespace {

constexpr uint16_t kNoPath = 4095;
constexpr double kLargestQuantum = 4094.0;

// 12-bit quanta packed two per three bytes (see the schema).
struct Packed12 {
    std::vector<uint8_t> bytes;
    size_t count = 0;
    void push(uint16_t q) {
        if (count % 2 == 0) {
            bytes.push_back(uint8_t(q & 0xFF));
            bytes.push_back(uint8_t(q >> 8));
        } else {
            bytes.back() = uint8_t(bytes.back() | ((q & 0x0F) << 4));
            bytes.push_back(uint8_t(q >> 4));
        }
        ++count;
    }
    size_t size() const { return count; }
};

// Appends one patch matrix as 12-bit quanta; returns the scale. `full` stores every
// row completely (first layer: the search reads whole rows, so they must be contiguous);
// otherwise (second layer, most of the blob) the node x node block whole, "no path" on its
// diagonal, so that a search relaxes a node by one contiguous run, then the node x other
// block, then only the strict upper triangle of the other slots (runtime/src/vg_graph.h).
float quantise(const PatchMatrix& m, bool full, Packed12& out, double& maxAbs) {
    double largest = 0;
    for (double d : m.upper)
        if (std::isfinite(d)) largest = std::max(largest, d);
    const float scale = largest > 0 ? float(largest / kLargestQuantum) : 1.0f;
    auto push = [&](double d) {
        if (!std::isfinite(d)) {
            out.push(kNoPath);
            return;
        }
        const double q = std::min(kLargestQuantum, std::round(d / double(scale)));
        out.push(uint16_t(q));
        maxAbs = std::max(maxAbs, std::fabs(q * double(scale) - d));
    };
    if (full) {
        for (uint32_t i = 0; i < m.rows; ++i)
            for (uint32_t j = 0; j < m.rows; ++j) push(m.at(i, j));
    } else {
        for (uint32_t i = 0; i < m.nodeCount; ++i)
            for (uint32_t j = 0; j < m.nodeCount; ++j) push(i == j ? INFINITY : m.at(i, j));
        for (uint32_t i = 0; i < m.nodeCount; ++i)
            for (uint32_t j = m.nodeCount; j < m.rows; ++j) push(m.at(i, j));
        for (uint32_t i = m.nodeCount; i < m.rows; ++i)
            for (uint32_t j = i + 1; j < m.rows; ++j) push(m.upper[upperIndex(m.rows, i, j)]);
    }
    return scale;
}

// Mesh edges between two graph nodes, as sorted neighbour lists per node: the runtime
// unfolds the two endpoint distances across such an edge, so a path may cross a patch
// border between vertices instead of through one.
void nodeEdges(const Mesh& mesh, const std::vector<uint32_t>& nodeOf, size_t nodeCount,
               std::vector<uint32_t>& begin, std::vector<uint32_t>& neighbours) {
    std::vector<std::vector<uint32_t>> lists(nodeCount);
    for (uint32_t h = 0; h < mesh.halfedgeCount(); ++h) {
        const int32_t twin = mesh.twin[h];
        if (twin >= 0 && uint32_t(twin) < h) continue;  // each edge once
        const uint32_t a = nodeOf[mesh.tail(int32_t(h))], b = nodeOf[mesh.head(int32_t(h))];
        if (a == UINT32_MAX || b == UINT32_MAX || a == b) continue;
        lists[a].push_back(b);
        lists[b].push_back(a);
    }
    begin.assign(1, 0);
    neighbours.clear();
    for (auto& l : lists) {
        std::sort(l.begin(), l.end());
        l.erase(std::unique(l.begin(), l.end()), l.end());
        neighbours.insert(neighbours.end(), l.begin(), l.end());
        begin.push_back(uint32_t(neighbours.size()));
    }
}

// The mesh edges between two node slots of second-layer patch m, both ways, grouped by
// their first slot, with vg_patch_edge_length (what a reader of a coded blob computes
// in their place). nodeSlot is all -1 on entry and on return.
void appendPatchEdges(const PatchMatrix& m, const std::vector<uint32_t>& nodeOf,
                      const std::vector<uint32_t>& nodeVertex, const std::vector<uint32_t>& edgeBegin,
                      const std::vector<uint32_t>& edgeNeighbours, const std::vector<float>& positions,
                      std::vector<int32_t>& nodeSlot, std::vector<fb::PatchEdge>& out) {
    for (uint32_t i = 0; i < m.nodeCount; ++i) nodeSlot[m.vertices[i]] = int32_t(i);
    for (uint32_t i = 0; i < m.nodeCount; ++i) {
        const uint32_t v = m.vertices[i], n = nodeOf[v];
        for (uint32_t e = edgeBegin[n]; e < edgeBegin[n + 1]; ++e) {
            const uint32_t w = nodeVertex[edgeNeighbours[e]];
            if (nodeSlot[w] < 0) continue;
            out.emplace_back(uint16_t(i), uint16_t(nodeSlot[w]), vg_patch_edge_length(positions.data(), v, w));
        }
    }
    for (uint32_t i = 0; i < m.nodeCount; ++i) nodeSlot[m.vertices[i]] = -1;
}

}  // namespace

std::vector<uint8_t> buildGraphBuffer(const Mesh& mesh, const Partition& partition,
                                      const std::vector<PatchMatrix>& first, const std::vector<PatchMatrix>& second,
                                      const std::vector<uint8_t>& secondInactive, const BlobParams& params,
                                      const Landmarks& landmarks, double& quantisationMaxAbs,
                                      const HubLabels& hubs) {
    const uint32_t V = mesh.vertexCount();
    quantisationMaxAbs = 0;

    // Nodes: vertices in the node part of a second-layer patch, by increasing vertex id.
    std::vector<uint32_t> nodeOf(V, UINT32_MAX);
    for (const PatchMatrix& m : second)
        for (uint32_t i = 0; i < m.nodeCount; ++i) nodeOf[m.vertices[i]] = 0;
    std::vector<uint32_t> nodeVertex;
    for (uint32_t v = 0; v < V; ++v)
        if (nodeOf[v] == 0) {
            nodeOf[v] = uint32_t(nodeVertex.size());
            nodeVertex.push_back(v);
        }
    const size_t N = nodeVertex.size();
    std::vector<uint32_t> edgeBegin, edgeNeighbours;
    nodeEdges(mesh, nodeOf, N, edgeBegin, edgeNeighbours);
    std::vector<float> positions(size_t(V) * 3);
    for (uint32_t v = 0; v < V; ++v) {
        positions[3 * v] = float(mesh.positions[v].x);
        positions[3 * v + 1] = float(mesh.positions[v].y);
        positions[3 * v + 2] = float(mesh.positions[v].z);
    }
    std::vector<fb::PatchEdge> secondEdges;
    std::vector<int32_t> nodeSlot(V, -1);  // node slots of the patch at hand

    std::vector<uint32_t> vertexPatch(V, UINT32_MAX);
    std::vector<uint16_t> vertexSlot(V, 0);
    std::vector<std::vector<fb::Membership>> secondOf(N), firstOf(N);
    std::vector<uint32_t> slots;
    Packed12 secondDist, firstDist;
    std::vector<fb::PatchRecord> secondRecords, firstRecords;

    for (uint32_t p = 0; p < second.size(); ++p) {
        const PatchMatrix& m = second[p];
        if (m.vertices.size() > 65535)
            throw std::runtime_error("a second-layer patch has " + std::to_string(m.vertices.size()) +
                                     " vertices (at most 65535): raise --n2");
        const uint32_t begin = uint32_t(slots.size());
        const uint64_t matrixBegin = secondDist.size();
        for (uint32_t i = 0; i < m.vertices.size(); ++i) {
            const uint32_t v = m.vertices[i];
            if (vertexPatch[v] == UINT32_MAX) {
                vertexPatch[v] = p;
                vertexSlot[v] = uint16_t(i);
            }
            if (i < m.nodeCount) {
                secondOf[nodeOf[v]].push_back(fb::Membership(p, i));
                slots.push_back(nodeOf[v]);
            } else {
                slots.push_back(v);
            }
        }
        const float scale = quantise(m, false, secondDist, quantisationMaxAbs);
        const uint32_t edgesBegin = uint32_t(secondEdges.size());
        appendPatchEdges(m, nodeOf, nodeVertex, edgeBegin, edgeNeighbours, positions, nodeSlot, secondEdges);
        secondRecords.emplace_back(begin, uint32_t(m.vertices.size()), m.nodeCount, edgesBegin, matrixBegin, scale,
                                   partition.second[p].parent);
    }

    std::vector<uint32_t> component = vertexComponents(mesh);
    for (uint32_t p = 0; p < first.size(); ++p) {
        const PatchMatrix& m = first[p];
        const uint32_t begin = uint32_t(slots.size());
        const uint64_t matrixBegin = firstDist.size();
        for (uint32_t i = 0; i < m.rows; ++i) {
            firstOf[nodeOf[m.vertices[i]]].push_back(fb::Membership(p, i));
            slots.push_back(nodeOf[m.vertices[i]]);
        }
        const float scale = quantise(m, true, firstDist, quantisationMaxAbs);
        const uint32_t comp = component[partition.first[p].seedVertex];
        firstRecords.emplace_back(begin, m.rows, m.rows, 0, matrixBegin, scale, comp);
    }

    auto flatten = [](const std::vector<std::vector<fb::Membership>>& lists, std::vector<uint32_t>& begin,
                      std::vector<fb::Membership>& all) {
        begin.assign(1, 0);
        for (const auto& l : lists) {
            all.insert(all.end(), l.begin(), l.end());
            begin.push_back(uint32_t(all.size()));
        }
    };
    std::vector<uint32_t> secondBegin, firstBegin;
    std::vector<fb::Membership> secondAll, firstAll;
    flatten(secondOf, secondBegin, secondAll);
    flatten(firstOf, firstBegin, firstAll);
    std::vector<uint8_t> flags(N, 0);
    for (size_t n = 0; n < N; ++n) flags[n] = secondInactive[nodeVertex[n]] ? 1 : 0;

    // Triangles and half-edge twins, for surface points and paths.
    const uint32_t F = mesh.faceCount();
    std::vector<uint32_t> faceVertices(size_t(F) * 3), faceTwin(size_t(F) * 3);
    for (uint32_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k) {
            faceVertices[3 * size_t(f) + k] = mesh.faces[f][k];
            const int32_t t = mesh.twin[3 * size_t(f) + k];
            faceTwin[3 * size_t(f) + k] = t < 0 ? UINT32_MAX : uint32_t(t);
        }
    std::vector<uint32_t> vertexHalfedge(V, UINT32_MAX);
    for (uint32_t v = 0; v < V; ++v)
        if (vertexPatch[v] != UINT32_MAX && mesh.vertexOut[v] >= 0) vertexHalfedge[v] = uint32_t(mesh.vertexOut[v]);

    // Exactly what the vectors take (plus headers and padding), before flatbuffers is asked
    // to build something its 32-bit offsets cannot address.
    auto bytesOf = [](const auto& v) { return uint64_t(v.size()) * sizeof(v[0]) + 16; };
    checkFlatbufferSize(bytesOf(positions) + bytesOf(vertexPatch) + bytesOf(vertexSlot) + bytesOf(nodeVertex) +
                            bytesOf(flags) + bytesOf(secondBegin) + bytesOf(secondAll) + bytesOf(firstBegin) +
                            bytesOf(firstAll) + bytesOf(edgeBegin) + bytesOf(edgeNeighbours) +
                            bytesOf(landmarks.vertices) + bytesOf(landmarks.scales) + bytesOf(landmarks.nodeValues) +
                            bytesOf(secondRecords) + bytesOf(firstRecords) + bytesOf(slots) + bytesOf(secondEdges) +
                            bytesOf(secondDist.bytes) + bytesOf(firstDist.bytes) + bytesOf(faceVertices) +
                            bytesOf(faceTwin) + bytesOf(partition.faceSecond) + bytesOf(vertexHalfedge) +
                            bytesOf(hubs.tree) + bytesOf(hubs.firstLeaf) + bytesOf(hubs.nodeHub) +
                            bytesOf(hubs.columnBegin) + bytesOf(hubs.innerBegin) + bytesOf(hubs.innerNode) +
                            bytesOf(hubs.innerMatrixBegin) + bytesOf(hubs.blockBounds) + bytesOf(hubs.landmarks) +
                            bytesOf(hubs.exitPatchBegin) + bytesOf(hubs.exitListBegin) + bytesOf(hubs.exitLists) + 4096,
                        V);
    flatbuffers::FlatBufferBuilder b(size_t(64) << 20);
    auto posV = b.CreateVector(positions);
    auto vpV = b.CreateVector(vertexPatch);
    auto vsV = b.CreateVector(vertexSlot);
    auto fvV = b.CreateVector(faceVertices);
    auto ftV = b.CreateVector(faceTwin);
    auto fpaV = b.CreateVector(partition.faceSecond);
    auto vhV = b.CreateVector(vertexHalfedge);
    auto nvV = b.CreateVector(nodeVertex);
    auto nfV = b.CreateVector(flags);
    auto nsbV = b.CreateVector(secondBegin);
    auto nsV = b.CreateVectorOfStructs(secondAll);
    auto nfbV = b.CreateVector(firstBegin);
    auto nflV = b.CreateVectorOfStructs(firstAll);
    auto nebV = b.CreateVector(edgeBegin);
    auto neV = b.CreateVector(edgeNeighbours);
    auto lvV = b.CreateVector(landmarks.vertices);
    auto lsV = b.CreateVector(landmarks.scales);
    auto lnV = b.CreateVector(landmarks.nodeValues);
    auto spV = b.CreateVectorOfStructs(secondRecords);
    auto fpV = b.CreateVectorOfStructs(firstRecords);
    auto slV = b.CreateVector(slots);
    auto seV = b.CreateVectorOfStructs(secondEdges);
    auto sdV = b.CreateVector(secondDist.bytes);
    auto fdV = b.CreateVector(firstDist.bytes);
    const bool withHubs = !hubs.tree.empty();
    std::vector<fb::HubTreeNode> hubTree;
    for (const HubTreeNode& t : hubs.tree) hubTree.emplace_back(t.parent, t.hubBegin, t.hubCount, t.pathBegin);
    flatbuffers::Offset<flatbuffers::Vector<const fb::HubTreeNode*>> htV;
    flatbuffers::Offset<flatbuffers::Vector<uint32_t>> hlfV, nhV, hibV, hinV, hepV, helV;
    flatbuffers::Offset<flatbuffers::Vector<uint64_t>> hlbV, himV;
    flatbuffers::Offset<flatbuffers::Vector<uint16_t>> hexV, hlmV;
    flatbuffers::Offset<flatbuffers::Vector<float>> hbbV;
    if (withHubs) {
        htV = b.CreateVectorOfStructs(hubTree);
        hlfV = b.CreateVector(hubs.firstLeaf);
        nhV = b.CreateVector(hubs.nodeHub);
        hlbV = b.CreateVector(hubs.columnBegin);
        hibV = b.CreateVector(hubs.innerBegin);
        hinV = b.CreateVector(hubs.innerNode);
        himV = b.CreateVector(hubs.innerMatrixBegin);
        hbbV = b.CreateVector(hubs.blockBounds);
        hlmV = b.CreateVector(hubs.landmarks);
        if (!hubs.exitPatchBegin.empty()) {
            hepV = b.CreateVector(hubs.exitPatchBegin);
            helV = b.CreateVector(hubs.exitListBegin);
            hexV = b.CreateVector(hubs.exitLists);
        }
    }
    fb::GraphBuilder g(b);
    g.add_vertex_count(V);
    g.add_bbox_diagonal(float(params.bboxDiagonal));
    g.add_positions(posV);
    g.add_vertex_patch(vpV);
    g.add_vertex_slot(vsV);
    g.add_face_vertices(fvV);
    g.add_face_twin(ftV);
    g.add_face_patch(fpaV);
    g.add_vertex_halfedge(vhV);
    g.add_node_vertex(nvV);
    g.add_node_flags(nfV);
    g.add_node_second_begin(nsbV);
    g.add_node_second(nsV);
    g.add_node_first_begin(nfbV);
    g.add_node_first(nflV);
    g.add_node_edge_begin(nebV);
    g.add_node_edge(neV);
    g.add_landmark_vertex(lvV);
    g.add_landmark_scale(lsV);
    g.add_node_landmarks(lnV);
    g.add_second_patches(spV);
    g.add_first_patches(fpV);
    g.add_slots(slV);
    g.add_second_edges(seV);
    g.add_second_distances(sdV);
    g.add_first_distances(fdV);
    g.add_seed(params.seed);
    g.add_n1(params.n1);
    g.add_n2(params.n2);
    g.add_delta(float(params.delta));
    g.add_margin_rings(params.marginRings);
    if (withHubs) {
        g.add_hub_tree(htV);
        g.add_hub_first_leaf(hlfV);
        g.add_node_hub(nhV);
        g.add_hub_label_scale(hubs.labelScale);
        g.add_hub_column_begin(hlbV);
        g.add_hub_columns_count(hubs.columns.size());
        g.add_hub_inner_begin(hibV);
        g.add_hub_inner_node(hinV);
        g.add_hub_inner_matrix_begin(himV);
        g.add_hub_inner_count(hubs.inner.size());
        g.add_hub_block_bounds(hbbV);
        g.add_hub_landmarks(hlmV);
        if (!hubs.exitPatchBegin.empty()) {
            g.add_hub_exit_patch_begin(hepV);
            g.add_hub_exit_list_begin(helV);
            g.add_hub_exit_lists(hexV);
        }
    }
    fb::FinishGraphBuffer(b, g.Finish());
    return std::vector<uint8_t>(b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize());
}

Payload withLabelTables(std::vector<uint8_t> flatbuffer, const HubLabels& hubs) {
    Payload p;
    p.flatbufferSize = flatbuffer.size();
    vg_label_tables at;
    if (!vg_label_tables_at(p.flatbufferSize, hubs.columns.size(), hubs.inner.size(), &at))
        throw std::runtime_error("hub-label tables too large for a blob");
    p.bytes = std::move(flatbuffer);
    if (hubs.tree.empty()) return p;
    // Zeros pad each part to 64 bytes: a label block's 32-byte rows never straddle a
    // cache line (vg_open unpacks the payload 64-byte aligned).
    p.bytes.resize(at.payload_size, 0);
    std::memcpy(p.bytes.data() + at.columns_offset, hubs.columns.data(), 2 * hubs.columns.size());
    std::memcpy(p.bytes.data() + at.inner_offset, hubs.inner.data(), 2 * hubs.inner.size());
    return p;
}

std::vector<uint8_t> sealContainer(const std::vector<uint8_t>& payload, uint32_t flags, int level,
                                   uint64_t flatbufferSize, uint64_t frameBytes) {
    if (flatbufferSize > payload.size()) flatbufferSize = payload.size();
    // What follows the flatbuffer (and its padding to 64 bytes): the tables.
    const uint64_t tableStart = vg_align64(flatbufferSize);
    const uint64_t tableBytes = payload.size() > tableStart ? payload.size() - tableStart : 0;
    std::vector<uint8_t> out(VG_CONTAINER_HEADER_SIZE);
    if (flags & VG_FLAG_ZSTD) {
        // A frame per VG_CONTAINER_FRAME_BYTES of payload, compressed on all threads: the
        // strong levels that coded blobs use take ~20 s on igea's 109 MB in one thread. Each
        // frame depends on its own bytes and the level alone, so the blob is the same for
        // any thread count. Compressed into memory that zstd alone touches: a zeroed vector
        // of the bound would make the whole bound resident (gigabytes for a large labelled mesh).
        if (frameBytes == 0) frameBytes = VG_CONTAINER_FRAME_BYTES;
        const size_t pieces = std::max<size_t>(1, (payload.size() + frameBytes - 1) / frameBytes);
        std::vector<std::unique_ptr<uint8_t[]>> frames(pieces);
        std::vector<size_t> frameSize(pieces, 0);
        parallelFor(pieces, [&](size_t i) {
            const size_t begin = i * frameBytes;
            const size_t size = std::min<size_t>(frameBytes, payload.size() - begin);
            const size_t bound = ZSTD_compressBound(size);
            std::unique_ptr<uint8_t[]> frame(new uint8_t[bound]);
            std::unique_ptr<ZSTD_CCtx, size_t (*)(ZSTD_CCtx*)> context(ZSTD_createCCtx(), ZSTD_freeCCtx);
            if (!context) throw std::runtime_error("zstd compression failed: out of memory");
            ZSTD_CCtx_setParameter(context.get(), ZSTD_c_compressionLevel, level);
            // Coded distances: a 256 KB window keeps zstd's match copies in the cache when
            // vg_open decompresses (igea opens in 83 instead of 98 ms; the blob is 2% larger).
            if (flags & VG_FLAG_CODED_DISTANCES) ZSTD_CCtx_setParameter(context.get(), ZSTD_c_windowLog, 18);
            const size_t n = ZSTD_compress2(context.get(), frame.get(), bound, payload.data() + begin, size);
            if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
            frames[i] = std::move(frame);
            frameSize[i] = n;
        });
        size_t total = 0;
        for (size_t n : frameSize) total += n;
        out.resize(VG_CONTAINER_HEADER_SIZE + total);
        size_t at = VG_CONTAINER_HEADER_SIZE;
        for (size_t i = 0; i < pieces; ++i) {
            std::memcpy(out.data() + at, frames[i].get(), frameSize[i]);
            at += frameSize[i];
            frames[i].reset();
        }
    } else {
        out.resize(VG_CONTAINER_HEADER_SIZE + payload.size());
        if (!payload.empty()) std::memcpy(out.data() + VG_CONTAINER_HEADER_SIZE, payload.data(), payload.size());
    }
    unsigned char* h = out.data();
    std::memcpy(h, VG_CONTAINER_MAGIC, 8);  // includes the terminating zero
    vg_store_le32(h + 8, VG_FORMAT_VERSION);
    vg_store_le32(h + 12, flags);
    vg_store_le64(h + 16, out.size() - VG_CONTAINER_HEADER_SIZE);
    vg_store_le64(h + 24, flatbufferSize);
    vg_store_le64(h + 32, tableBytes);
    vg_store_le64(h + 40, vg_checksum64(h + VG_CONTAINER_HEADER_SIZE, out.size() - VG_CONTAINER_HEADER_SIZE));
    return out;
}

std::vector<uint8_t> packContainer(Payload payload, bool compress, bool compact, int level, bool innerRowsAtOpen) {
    if (innerRowsAtOpen && !(compress && compact))
        throw std::invalid_argument("packContainer: inner rows at open need a compact blob");
    if (!compress) return sealContainer(payload.bytes, 0, level, payload.flatbufferSize);
    if (!compact) return sealContainer(payload.bytes, VG_FLAG_ZSTD, level, payload.flatbufferSize);
    // Coded distances compress 3x (raw quanta hardly compress at all).
    codeDistances(payload.bytes, payload.flatbufferSize, !innerRowsAtOpen);
    return sealContainer(payload.bytes,
                         VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES | (innerRowsAtOpen ? VG_FLAG_INNER_ROWS_AT_OPEN : 0u),
                         level, payload.flatbufferSize);
}

std::vector<uint8_t> packContainer(std::vector<uint8_t> flatbuffer, bool compress, bool compact, int level) {
    Payload p;
    p.flatbufferSize = flatbuffer.size();
    p.bytes = std::move(flatbuffer);
    return packContainer(std::move(p), compress, compact, level);
}

namespace {
std::string temporaryPath(const std::string& path) { return path + ".tmp-" + std::to_string(::getpid()); }
}  // namespace

void checkWritable(const std::string& path) {
    const std::string tmp = temporaryPath(path);
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    std::fclose(f);
    std::remove(tmp.c_str());
}

void writeFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes) {
    const std::string tmp = temporaryPath(path);
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const int writeErrno = errno;
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed) {
        std::remove(tmp.c_str());
        throw std::runtime_error("cannot write " + path + ": " + std::strerror(written ? errno : writeErrno));
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const int e = errno;
        std::remove(tmp.c_str());
        throw std::runtime_error("cannot write " + path + ": " + std::strerror(e));
    }
}

}  // namespace vorogeo
