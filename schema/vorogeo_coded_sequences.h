// The flatbuffer arrays that a coded blob (VG_FLAG_CODED_DISTANCES, format 11) stores as
// sequences of differences (vg_code_sequence in vorogeo_topology_coding.h), listed once for
// the baker, which codes them, and the runtime and tools, which decode them. C++ (it walks
// the generated flatbuffer API); the coding itself is the plain C header's.
#pragma once

#include "vorogeo_generated.h"

namespace vorogeo {

// Calls visit(array) for each such array of g that is present, in a fixed order.
template <class Visit>
void forEachCodedSequence(const fb::Graph* g, Visit&& visit) {
    const flatbuffers::Vector<uint32_t>* arrays[] = {g->node_vertex(),     g->slots(),           g->node_edge(),
                                                     g->node_second_begin(), g->node_first_begin(), g->node_edge_begin(),
                                                     g->hub_exit_list_begin()};
    for (const flatbuffers::Vector<uint32_t>* a : arrays)
        if (a != nullptr && a->size() > 0) visit(a);
}

}  // namespace vorogeo
