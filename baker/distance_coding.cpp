#include "distance_coding.h"

#include "vorogeo_distance_coding.h"
#include "vorogeo_generated.h"

namespace vorogeo {

void codeDistances(std::vector<uint8_t>& flatbuffer) {
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
}

}  // namespace vorogeo
