#include "blob_reader.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include <zstd.h>

#include "runtime_graph.h"
#include "vorogeo_coded_sequences.h"
#include "vorogeo_container.h"
#include "vorogeo_distance_coding.h"
#include "vorogeo_label_coding.h"
#include "vorogeo_topology_coding.h"

namespace vorogeo::tools {

namespace {

// Where a coded blob is decoded. Every decoded array lies apart from every other (the
// runtime's validation, which the blob has passed, checks that), but one may lie over the
// flatbuffer's own structure (offsets, vtables, lengths), which decoding it would rewrite:
// so the structure is read from `plain`, an untouched copy, and the decoded values are
// written to and read from `out` at the same offsets. Nothing is then read through a
// structure that decoding changed.
struct Decoding {
    const fb::Graph* g;  // in plain
    const uint8_t* plain;
    uint8_t* out;
    // The place in `out` of what lies at p in `plain`.
    template <class T>
    T* at(const T* p) const {
        return reinterpret_cast<T*>(out + (reinterpret_cast<const uint8_t*>(p) - plain));
    }
};

// Decodes the hub-label tables in place (schema/vorogeo_label_coding.h), when there are
// labels, after checking the table ranges the decoder reads (the first-layer slots and the
// nodes' vertices are checked by decodeLayers before).
bool decodeLabels(const Decoding& d, BlobContents& blob, std::string& error) {
    const fb::Graph* g = d.g;
    const auto* tree = g->hub_tree();
    if (!tree || tree->size() == 0) return true;
    const uint64_t T = tree->size(), S1 = g->first_patches()->size(), nodes = g->node_vertex()->size();
    if (!g->hub_column_begin() || !g->hub_inner_begin() || !g->hub_inner_node() || !g->hub_inner_matrix_begin() ||
        g->hub_column_begin()->size() != T + 1 || g->hub_inner_begin()->size() != S1 + 1 ||
        g->hub_inner_matrix_begin()->size() != S1 + 1) {
        error = "coded hub labels without the tables they are decoded into";
        return false;
    }
    std::vector<int32_t> detours(2 * 65536);
    std::vector<unsigned char> planes(2 * VG_LABEL_CHUNK);

    uint16_t* columns = blob.hubColumns.data();
    const uint64_t columnCount = blob.hubColumns.size();
    for (uint64_t t = 0; t < T; ++t) {
        const uint64_t begin = g->hub_column_begin()->Get(t), end = g->hub_column_begin()->Get(t + 1);
        const uint64_t blocks = (uint64_t(tree->Get(t)->hub_count()) + 15) / 16;
        if (begin > end || end > columnCount || (blocks == 0 ? end != begin : (end - begin) % (16 * blocks) != 0) ||
            (end - begin) / 16 > 0xFFFFFFFFu) {
            error = "a hub tree node's label blocks lie outside hub_columns";
            return false;
        }
    }
    vg_label_planes(reinterpret_cast<unsigned char*>(columns), columnCount, planes.data(), 0);
    for (uint64_t t = 0; t < T; ++t) {
        const uint64_t begin = g->hub_column_begin()->Get(t), end = g->hub_column_begin()->Get(t + 1);
        const uint64_t blocks = (uint64_t(tree->Get(t)->hub_count()) + 15) / 16;
        if (blocks == 0) continue;
        const uint64_t rows = (end - begin) / (16 * blocks);
        for (uint64_t k = 0; k < blocks; ++k)
            vg_code_label_table(columns, columns, begin + k * rows * 16, uint32_t(rows), 16, nullptr, detours.data(), 1);
    }

    uint16_t* inner = blob.hubInner.data();
    const uint64_t innerCount = blob.hubInner.size(), innerNodes = g->hub_inner_node()->size();
    for (uint64_t p = 0; p < S1; ++p) {
        const uint64_t r0 = g->hub_inner_begin()->Get(uint32_t(p)), r1 = g->hub_inner_begin()->Get(uint32_t(p + 1));
        const uint64_t m0 = g->hub_inner_matrix_begin()->Get(uint32_t(p)), m1 = g->hub_inner_matrix_begin()->Get(uint32_t(p + 1));
        if (r0 > r1 || r1 > innerNodes || m0 > m1 || m1 > innerCount ||
            m1 - m0 != (r1 - r0) * g->first_patches()->Get(uint32_t(p))->slot_count()) {
            error = "a first-layer patch's inner table lies outside hub_inner";
            return false;
        }
        for (uint64_t i = r0; i < r1; ++i)
            if (g->hub_inner_node()->Get(uint32_t(i)) >= nodes) {
                error = "an inner row's node is out of range";
                return false;
            }
    }
    if (blob.innerRowsAtOpen) return true;  // zeros stand for them (checked by storedZerosAreZeros)
    vg_label_planes(reinterpret_cast<unsigned char*>(inner), innerCount, planes.data(), 0);
    const float inverseScale = 1.0f / g->hub_label_scale();
    for (uint32_t p = 0; p < S1; ++p) {
        const fb::PatchRecord* patch = g->first_patches()->Get(p);
        const uint32_t r0 = g->hub_inner_begin()->Get(p);
        const vg_label_sites sites{d.at(g->positions()->data()), d.at(g->node_vertex()->data()),
                                   g->hub_inner_node()->data() + r0, d.at(g->slots()->data()) + patch->slot_begin(),
                                   inverseScale};
        vg_code_label_table(inner, inner, g->hub_inner_matrix_begin()->Get(p), g->hub_inner_begin()->Get(p + 1) - r0,
                            patch->slot_count(), &sites, detours.data(), 1);
    }
    return true;
}

// Decodes the mesh topology's indices (schema/vorogeo_topology_coding.h): any bytes decode
// to some indices, which the readers check as in an uncoded blob.
bool decodeTopology(const Decoding& d, std::string& error) {
    const fb::Graph* g = d.g;
    if (!g->face_vertices() || !g->face_twin() || !g->vertex_halfedge() ||
        g->face_vertices()->size() != g->face_twin()->size()) {
        error = "coded topology without its arrays";
        return false;
    }
    vg_code_topology(d.at(g->face_vertices()->data()), d.at(g->face_twin()->data()), g->face_twin()->size(),
                     d.at(g->vertex_halfedge()->data()), g->vertex_halfedge()->size(), 1);
    return true;
}

// Sets the patch edges' lengths (stored as 0 in a coded blob) from the positions of their
// ends (schema/vorogeo_topology_coding.h), after checking the ranges it reads; the patches'
// node slots are checked by decodeLayers before.
bool decodePatchEdgeLengths(const Decoding& d, std::string& error) {
    const fb::Graph* g = d.g;
    const auto* edges = g->second_edges();
    const auto* patches = g->second_patches();
    if (!edges || edges->size() == 0) return true;
    static_assert(sizeof(fb::PatchEdge) == VG_PATCH_EDGE_BYTES, "PatchEdge layout");
    uint8_t* bytes = d.at(edges->Data());
    const float* positions = d.at(g->positions()->data());
    const uint32_t* nodeVertex = d.at(g->node_vertex()->data());
    for (uint32_t i = 0; i < patches->size(); ++i) {
        const fb::PatchRecord* p = patches->Get(i);
        const uint64_t begin = p->edge_begin(), end = i + 1 < patches->size() ? patches->Get(i + 1)->edge_begin() : edges->size();
        if (begin > end || end > edges->size()) {
            error = "a patch's edges lie outside their array";
            return false;
        }
        const uint32_t* slots = d.at(g->slots()->data()) + p->slot_begin();
        for (uint64_t e = begin; e < end; ++e) {
            const fb::PatchEdge* E = edges->Get(uint32_t(e));
            if (E->from() >= p->node_count() || E->to() >= p->node_count()) {
                error = "a patch edge's end is not a node slot of its patch";
                return false;
            }
            const float length = vg_patch_edge_length(positions, nodeVertex[slots[E->from()]], nodeVertex[slots[E->to()]]);
            std::memcpy(bytes + VG_PATCH_EDGE_BYTES * e + VG_PATCH_EDGE_LENGTH_AT, &length, sizeof length);
        }
    }
    return true;
}

// Decodes the distances (schema/vorogeo_distance_coding.h), after checking that every
// patch's slots, slot ids and matrix lie inside their arrays.
bool decodeLayers(const Decoding& d, std::string& error) {
    const fb::Graph* g = d.g;
    const uint64_t vertices = g->positions()->size() / 3, nodes = g->node_vertex()->size();
    const uint64_t slotCount = g->slots()->size();
    const float* positions = d.at(g->positions()->data());
    const uint32_t* nodeVertex = d.at(g->node_vertex()->data());
    for (uint64_t n = 0; n < nodes; ++n)
        if (nodeVertex[n] >= vertices) {
            error = "a node's vertex is out of range";
            return false;
        }
    auto decodeLayer = [&](const flatbuffers::Vector<const fb::PatchRecord*>* patches, const flatbuffers::Vector<uint8_t>* array,
                           bool firstLayer) {
        uint8_t* packed = d.at(array->data());
        const uint64_t capacity = vg_coding_entries(array->size());
        std::vector<unsigned char> planeScratch(VG_CODING_PLANE_SCRATCH);
        vg_code_planes(packed, capacity, planeScratch.data(), 1);
        for (const fb::PatchRecord* p : *patches) {
            const uint64_t S = p->slot_count(), n = p->node_count();
            const uint64_t entries = firstLayer ? S * S : n * S + (S - n) * (S > n ? S - n - 1 : 0) / 2;
            if (p->slot_begin() + S > slotCount || n > S || S > 65536 || (firstLayer && n != S) ||
                p->matrix_begin() > capacity || entries > capacity - p->matrix_begin()) {
                error = "a patch's slots or matrix lie outside their arrays";
                return false;
            }
            const uint32_t* slots = d.at(g->slots()->data()) + p->slot_begin();
            for (uint64_t i = 0; i < S; ++i)
                if (i < n ? slots[i] >= nodes : slots[i] >= vertices) {
                    error = "a patch slot is out of range";
                    return false;
                }
            const vg_coding_slots s{positions, slots, nodeVertex, uint32_t(n)};
            if (firstLayer)
                vg_code_first_matrix(packed, packed, p->matrix_begin(), uint32_t(S), p->scale(), &s, 1);
            else
                vg_code_second_matrix(packed, packed, p->matrix_begin(), uint32_t(S), uint32_t(n), p->scale(), &s, 1);
        }
        return true;
    };
    return decodeLayer(g->second_patches(), g->second_distances(), false) &&
           decodeLayer(g->first_patches(), g->first_distances(), true);
}

// What a coded blob must store as zeros, checked before anything else so that the reason
// is named (the runtime's refusal gives only a status): the patch edges' lengths, which
// readers compute, and inner rows left to vg_open.
bool storedZerosAreZeros(const BlobContents& blob, std::string& error) {
    const fb::Graph* g = blob.graph();
    if (g->second_edges())
        for (const fb::PatchEdge* e : *g->second_edges())
            if (e->length() != 0.0f) {
                error = "a coded blob stores a patch edge length (readers compute them)";
                return false;
            }
    if (blob.innerRowsAtOpen)  // zeros stand for them (schema/vorogeo_inner_rows.h)
        for (uint16_t entry : blob.hubInner)
            if (entry != 0) {
                error = "the inner rows left to the readers are not zeros";
                return false;
            }
    return true;
}

// Decodes a coded blob's arrays in place, so that `flatbuffer` holds plain values. The
// blob is first opened with the runtime, whose validation (every array's bounds, the
// decoded arrays apart from all others, every decoded index in range) the decoding here
// relies on; the tools check again what they read.
bool decodeBlob(const std::vector<uint8_t>& bytes, BlobContents& blob, std::string& error) {
    if (!storedZerosAreZeros(blob, error)) return false;
    {
        RuntimeGraph runtime;
        std::string refused;
        if (!runtime.open(bytes, refused)) {
            error = "the runtime refuses the blob: " + refused;
            return false;
        }
    }
    std::vector<uint8_t>& flatbuffer = blob.flatbuffer;
    // The index sequences first, as the runtime decodes them: in place, then the structure
    // verified again (what the runtime validated is the structure after them).
    forEachCodedSequence(fb::GetGraph(flatbuffer.data()), [&](const uint32_t* data, uint64_t size) {
        vg_code_sequence(reinterpret_cast<uint32_t*>(flatbuffer.data() + (reinterpret_cast<const uint8_t*>(data) - flatbuffer.data())),
                         size, 1);
    });
    const std::vector<uint8_t> plain = flatbuffer;
    {
        flatbuffers::Verifier verifier(plain.data(), plain.size());
        if (!fb::VerifyGraphBuffer(verifier)) {
            error = "a coded index sequence lies over the flatbuffer's structure";
            return false;
        }
    }
    const Decoding d{fb::GetGraph(plain.data()), plain.data(), flatbuffer.data()};
    const fb::Graph* g = d.g;
    if (!g->positions() || !g->slots() || !g->node_vertex() || !g->second_patches() || !g->first_patches() ||
        !g->second_distances() || !g->first_distances()) {
        error = "coded distances without the arrays they are decoded from";
        return false;
    }
    // The positions before the rest: the other arrays are predicted from them.
    vg_code_positions(d.at(g->positions()->Data()), g->positions()->size(), 1);
    if (!decodeLayers(d, error) || !decodeLabels(d, blob, error) || !decodeTopology(d, error) ||
        !decodePatchEdgeLengths(d, error))
        return false;
    // What the tools read next goes through the decoded buffer's own structure.
    flatbuffers::Verifier verifier(flatbuffer.data(), flatbuffer.size());
    if (!fb::VerifyGraphBuffer(verifier)) {
        error = "a coded array lies over the flatbuffer's structure";
        return false;
    }
    return true;
}

}  // namespace

bool unpackBlob(const std::vector<uint8_t>& bytes, BlobContents& out, std::string& error, bool decode) {
    if (bytes.size() < VG_CONTAINER_HEADER_SIZE) {
        error = "too short for a vorogeo blob (" + std::to_string(bytes.size()) + " bytes)";
        return false;
    }
    const unsigned char* h = bytes.data();
    if (std::memcmp(h, VG_CONTAINER_MAGIC, 8) != 0) {
        error = "not a vorogeo blob (bad magic)";
        return false;
    }
    out.formatVersion = vg_load_le32(h + 8);
    if (out.formatVersion != VG_FORMAT_VERSION) {
        error = "format version " + std::to_string(out.formatVersion) + " is not supported (this build reads version " +
                std::to_string(VG_FORMAT_VERSION) + ")";
        return false;
    }
    const uint32_t flags = vg_load_le32(h + 12);
    if (flags & ~(VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES | VG_FLAG_INNER_ROWS_AT_OPEN)) {
        error = "unknown flags " + std::to_string(flags);
        return false;
    }
    out.compressed = (flags & VG_FLAG_ZSTD) != 0;
    out.coded = (flags & VG_FLAG_CODED_DISTANCES) != 0;
    out.innerRowsAtOpen = (flags & VG_FLAG_INNER_ROWS_AT_OPEN) != 0;
    if (out.innerRowsAtOpen && !out.coded) {
        error = "inner rows left to the readers in a blob that is not coded";
        return false;
    }
    const uint64_t payload = vg_load_le64(h + 16), size = vg_load_le64(h + 24), tableBytes = vg_load_le64(h + 32);
    if (payload != bytes.size() - VG_CONTAINER_HEADER_SIZE) {
        error = "payload size " + std::to_string(payload) + " does not match the " +
                std::to_string(bytes.size() - VG_CONTAINER_HEADER_SIZE) + " bytes present (truncated or padded)";
        return false;
    }
    if (vg_checksum64(h + VG_CONTAINER_HEADER_SIZE, payload) != vg_load_le64(h + 40)) {
        error = "checksum mismatch (corrupted blob)";
        return false;
    }
    if (size > (uint64_t(1) << 31)) {
        error = "flatbuffer size " + std::to_string(size) + " is larger than 2 GiB";
        return false;
    }
    if (tableBytes % 64 != 0 || tableBytes > (uint64_t(1) << 48)) {
        error = "label table size " + std::to_string(tableBytes) + " is not a whole number of 64-byte blocks below 256 TiB";
        return false;
    }
    // Unpacked: the flatbuffer, then (with labels) zeros to a multiple of 64 bytes and the tables.
    const uint64_t unpacked = tableBytes ? vg_align64(size) + tableBytes : size;
    if (!out.compressed && unpacked != payload) {
        error = "uncompressed blob whose flatbuffer and tables differ from its payload";
        return false;
    }
    std::vector<uint8_t>& all = out.flatbuffer;  // cut to the flatbuffer below
    all.resize(size_t(unpacked));
    if (out.compressed) {
        const size_t n = ZSTD_decompress(all.data(), all.size(), h + VG_CONTAINER_HEADER_SIZE, payload);
        if (ZSTD_isError(n) || n != unpacked) {
            error = std::string("zstd frames do not decompress to the stated size") +
                    (ZSTD_isError(n) ? std::string(": ") + ZSTD_getErrorName(n) : std::string());
            return false;
        }
    } else if (unpacked) {
        std::memcpy(all.data(), h + VG_CONTAINER_HEADER_SIZE, size_t(unpacked));
    }
    {
        flatbuffers::Verifier verifier(all.data(), size_t(size));
        if (!fb::VerifyGraphBuffer(verifier)) {
            error = "flatbuffer fails verification (corrupted or not a vorogeo graph)";
            return false;
        }
    }
    const fb::Graph* g = fb::GetGraph(all.data());
    vg_label_tables at;
    if (!vg_label_tables_at(size, g->hub_columns_count(), g->hub_inner_count(), &at) || at.table_bytes != tableBytes) {
        error = "the label tables after the flatbuffer take " + std::to_string(tableBytes) +
                " bytes, not what their entry counts need";
        return false;
    }
    const uint16_t* tables = reinterpret_cast<const uint16_t*>(all.data() + at.columns_offset);
    out.hubColumns.assign(tables, tables + g->hub_columns_count());
    tables = reinterpret_cast<const uint16_t*>(all.data() + at.inner_offset);
    out.hubInner.assign(tables, tables + g->hub_inner_count());
    if (out.innerRowsAtOpen && (!g->hub_tree() || g->hub_tree()->size() == 0)) {
        error = "inner rows left to the readers in a blob without hub labels";
        return false;
    }
    all.resize(size_t(size));  // (g points into the old buffer from here)
    all.shrink_to_fit();
    return !out.coded || !decode || decodeBlob(bytes, out, error);
}

bool readBlobFile(const std::string& path, BlobContents& out, std::string& error, bool decode) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = path + ": cannot open";
        return false;
    }
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!unpackBlob(bytes, out, error, decode)) {
        error = path + ": " + error;
        return false;
    }
    return true;
}

}  // namespace vorogeo::tools
