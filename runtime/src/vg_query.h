// Argument checks shared by every query entry point.
#pragma once

#include "vg_workspace.h"

namespace vg {

inline vg_status checkQuery(const vg_graph* graph, const vg_workspace* workspace, const void* out) {
    if (graph == nullptr || workspace == nullptr || out == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (workspace->graph != graph) return VG_ERR_WRONG_WORKSPACE;
    return VG_OK;
}

}  // namespace vg
