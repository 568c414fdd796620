#include "distance_coding.h"

#include <cstring>
#include <stdexcept>

#include "vorogeo_coded_sequences.h"
#include "vorogeo_container.h"
#include "vorogeo_distance_coding.h"
#include "vorogeo_label_coding.h"
#include "vorogeo_topology_coding.h"
#include "vorogeo_generated.h"

namespace vorogeo {

namespace {

// hub_columns and hub_inner (schema/vorogeo_label_coding.h), where they follow the
// flatbuffer in the payload: each table coded in place (an entry is read before it is
// overwritten, and the prediction takes its neighbours from the coder's own row buffers),
// then every array split into byte planes.
void codeLabels(std::vector<uint8_t>& payload, uint64_t flatbufferSize, const fb::Graph* g, bool codeInner) {
    const auto* tree = g->hub_tree();
    if (!tree || tree->size() == 0) return;
    vg_label_tables at;
    if (!vg_label_tables_at(flatbufferSize, g->hub_columns_count(), g->hub_inner_count(), &at) ||
        at.payload_size != payload.size())
        throw std::runtime_error("codeDistances: the payload does not hold the flatbuffer's label tables");
    uint16_t* columns = reinterpret_cast<uint16_t*>(payload.data() + at.columns_offset);
    uint16_t* inner = reinterpret_cast<uint16_t*>(payload.data() + at.inner_offset);
    std::vector<int32_t> detours;
    std::vector<unsigned char> planeScratch(2 * VG_LABEL_CHUNK);

    detours.resize(2 * 16);
    for (uint32_t t = 0; t < tree->size(); ++t) {
        const uint64_t blocks = (uint64_t(tree->Get(t)->hub_count()) + 15) / 16;
        if (blocks == 0) continue;
        const uint64_t begin = g->hub_column_begin()->Get(t), end = g->hub_column_begin()->Get(t + 1);
        const uint64_t rows = (end - begin) / (16 * blocks);
        for (uint64_t k = 0; k < blocks; ++k)
            vg_code_label_table(columns, columns, begin + k * rows * 16, uint32_t(rows), 16, nullptr, detours.data(), 0);
    }
    vg_label_planes(reinterpret_cast<unsigned char*>(columns), g->hub_columns_count(), planeScratch.data(), 1);
    if (!codeInner) return;

    const uint32_t* slots = g->slots()->data();
    for (uint32_t p = 0; p < g->first_patches()->size(); ++p) {
        const fb::PatchRecord* patch = g->first_patches()->Get(p);
        const uint32_t rowBegin = g->hub_inner_begin()->Get(p), rows = g->hub_inner_begin()->Get(p + 1) - rowBegin;
        const uint32_t cols = patch->slot_count();
        const vg_label_sites sites{g->positions()->data(), g->node_vertex()->data(), g->hub_inner_node()->data() + rowBegin,
                                   slots + patch->slot_begin(), 1.0f / g->hub_label_scale()};
        detours.resize(2 * size_t(cols));
        vg_code_label_table(inner, inner, g->hub_inner_matrix_begin()->Get(p), rows, cols, &sites, detours.data(), 0);
    }
    vg_label_planes(reinterpret_cast<unsigned char*>(inner), g->hub_inner_count(), planeScratch.data(), 1);
}

}  // namespace

void codeDistances(std::vector<uint8_t>& payload, uint64_t flatbufferSize, bool codeInner) {
    std::vector<uint8_t>& flatbuffer = payload;  // (its first flatbufferSize bytes)
    if (flatbufferSize > payload.size()) flatbufferSize = payload.size();
    const fb::Graph* g = fb::GetGraph(flatbuffer.data());
    const float* positions = g->positions()->data();
    const uint32_t* slots = g->slots()->data();
    const uint32_t* nodeVertex = g->node_vertex()->data();
    // The arrays live inside the buffer: code them there, with their uncoded copies as
    // the mirrors' reference.
    auto arrayIn = [&](const flatbuffers::Vector<uint8_t>* v) {
        return flatbuffer.data() + (v->data() - flatbuffer.data());
    };
    uint8_t* second = arrayIn(g->second_distances());
    uint8_t* first = arrayIn(g->first_distances());
    const std::vector<uint8_t> secondPlain(second, second + g->second_distances()->size());
    const std::vector<uint8_t> firstPlain(first, first + g->first_distances()->size());
    for (const fb::PatchRecord* p : *g->second_patches()) {
        const vg_coding_slots s{positions, slots + p->slot_begin(), nodeVertex, p->node_count()};
        vg_code_second_matrix(secondPlain.data(), second, p->matrix_begin(), p->slot_count(), p->node_count(),
                              p->scale(), &s, 0);
    }
    for (const fb::PatchRecord* p : *g->first_patches()) {
        const vg_coding_slots s{positions, slots + p->slot_begin(), nodeVertex, p->slot_count()};
        vg_code_first_matrix(firstPlain.data(), first, p->matrix_begin(), p->slot_count(), p->scale(), &s, 0);
    }
    // Both arrays' codes in byte planes (vorogeo_distance_coding.h).
    std::vector<uint8_t> scratch(VG_CODING_PLANE_SCRATCH);
    vg_code_planes(second, vg_coding_entries(g->second_distances()->size()), scratch.data(), 0);
    vg_code_planes(first, vg_coding_entries(g->first_distances()->size()), scratch.data(), 0);
    codeLabels(payload, flatbufferSize, g, codeInner);
    auto indicesAt = [&](const uint32_t* p) {
        return reinterpret_cast<uint32_t*>(flatbuffer.data() + (reinterpret_cast<const uint8_t*>(p) - flatbuffer.data()));
    };
    vg_code_topology(indicesAt(g->face_vertices()->data()), indicesAt(g->face_twin()->data()), g->face_twin()->size(),
                     indicesAt(g->vertex_halfedge()->data()), g->vertex_halfedge()->size(), 0);
    // Patch edge lengths are not stored: readers compute them (vorogeo_topology_coding.h).
    static_assert(sizeof(fb::PatchEdge) == VG_PATCH_EDGE_BYTES, "PatchEdge layout");
    if (g->second_edges() && g->second_edges()->size() > 0) {
        uint8_t* edges = flatbuffer.data() + (g->second_edges()->Data() - flatbuffer.data());
        for (uint64_t e = 0; e < g->second_edges()->size(); ++e)
            std::memset(edges + VG_PATCH_EDGE_BYTES * e + VG_PATCH_EDGE_LENGTH_AT, 0, sizeof(float));
    }
    // Last: every coding above predicts from the plain positions and reads the plain
    // indices.
    forEachCodedSequence(g, [&](const uint32_t* data, uint64_t size) { vg_code_sequence(indicesAt(data), size, 0); });
    vg_code_positions(flatbuffer.data() + (reinterpret_cast<const uint8_t*>(positions) - flatbuffer.data()),
                      g->positions()->size(), 0);
}

}  // namespace vorogeo
