// The flatbuffer arrays that a coded blob (VG_FLAG_CODED_DISTANCES, format 11) stores as
// sequences of differences (vg_code_sequence in vorogeo_topology_coding.h), listed once for
// the baker, which codes them, and the runtime and tools, which decode them. C++ (it walks
// the generated flatbuffer API); the coding itself is the plain C header's.
#pragma once

#include "vorogeo_generated.h"

namespace vorogeo {

// Calls visit(data, size) for each such array of g that is present and not empty, in a
// fixed order. Every array's place and length are read before the first visit: decoding
// one array in place may rewrite another's length field (a crafted blob can lay one over
// the other's), and a length read after that could send the next visit past the buffer.
template <class Visit>
void forEachCodedSequence(const fb::Graph* g, Visit&& visit) {
    const flatbuffers::Vector<uint32_t>* arrays[] = {g->node_vertex(),     g->slots(),           g->node_edge(),
                                                     g->node_second_begin(), g->node_first_begin(), g->node_edge_begin(),
                                                     g->hub_exit_list_begin()};
    constexpr size_t kArrays = sizeof arrays / sizeof arrays[0];
    const uint32_t* data[kArrays];
    uint32_t size[kArrays];
    for (size_t i = 0; i < kArrays; ++i) {
        data[i] = arrays[i] ? arrays[i]->data() : nullptr;
        size[i] = arrays[i] ? arrays[i]->size() : 0;
    }
    for (size_t i = 0; i < kArrays; ++i)
        if (size[i] > 0) visit(data[i], uint64_t(size[i]));
}

}  // namespace vorogeo
