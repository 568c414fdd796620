// Point-to-point distance between two vertices inside one first-layer patch, from the
// endpoint table's node distances (vg_patch_pairs.cpp). Internal to the runtime.
#pragma once

#include "vg_workspace.h"

namespace vg {

// d(s, t) for vertices s != t whose second-layer patches all lie in one first-layer patch
// (neither of them a hub), when the workspace reads an endpoint table: true with *out set
// (+inf beyond maxDistance); false, nothing done, for any other pair or when the patch's
// node distances give no path (a search then answers).
bool patchPairDistance(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, float maxDistance, float* out);

// The workspace's lists for it: each end's nodes (padded to whole vectors), and each
// end's node slots (at most kMaxSidePatches patches of the largest node count).
uint32_t patchPairListCapacity(const vg_graph& g);
uint32_t patchPairSlotCapacity(const vg_graph& g);

}  // namespace vg
