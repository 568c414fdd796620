// Accepting a flatbuffer as a graph: the flatbuffers verifier (structure), then every
// index and count the queries rely on (meaning), then the raw views of vg_graph.
#pragma once

#include <stddef.h>

#include "vg_graph.h"

namespace vg {

// The hub-label tables that follow a flatbuffer in an unpacked payload
// (schema/vorogeo_container.h): `size` bytes from `bytes`, 64-byte aligned after the
// flatbuffer's end; {nullptr, 0} without labels.
struct Tables {
    const unsigned char* bytes;
    uint64_t size;
};

// `flatbuffer` must be 8-byte aligned. Fills `graph` only on VG_OK. With `codedTopology`
// (a coded blob in memory the caller owns) the mesh topology's indices are decoded in place
// (schema/vorogeo_topology_coding.h) before they are checked.
vg_status verifyAndBind(const unsigned char* flatbuffer, size_t size, const Tables& tables, vg_graph& graph,
                        bool codedTopology = false);

}  // namespace vg
