// Point-to-point distance from hub labels (bake --hub-labels; baker/hub_labels.h has the
// construction and why it is exact on the graph): s's patch row and its first-layer
// patch's inner rows give s's distance to that patch's first-layer nodes; their labels
// give s's distance to every hub on the patch's tree path; t's side reads the same rows
// backwards and meets s's distances next to t, at t's patch nodes and across the mesh
// edges between them (the unfolded crossings of the directed search). No search, no
// queue: a few ten thousand additions over contiguous rows.
// Internal to the runtime.
#pragma once

#include "vg_workspace.h"

namespace vg {

// The distance between vertices s and t (+inf beyond maxDistance) into *out. False, with
// *out untouched, when the blob has no labels or s and t share a first-layer patch (a
// shortest path may stay inside it, which only the endpoint table's node distances,
// vg_patch_pairs.h, or the search see). `prune` false reads
// every label of both patches (the reference the tests compare the pruned reads with).
// `generalMeeting` meets next to t through the search labels and node edge lists even
// where t lies inside one second-layer patch, which otherwise takes slot-local arrays and
// the patch's edge list (the same numbers; the tests compare the two). `meetEveryBlock`
// takes the upper bound's hub-to-hub part from every block of the hubs' common tree path
// rather than only those whose lower bounds could still lower it (the same bound; the
// tests compare the two); `upperBound`, if given, receives the upper bound the reads were
// pruned with (+inf: none).
bool hubDistance(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, float maxDistance, float* out,
                 bool prune = true, bool generalMeeting = false, bool meetEveryBlock = false,
                 float* upperBound = nullptr);

// The same reads for s and t in one first-layer patch (or one of them a hub on its
// border), which hubDistance refuses: the paths that leave the patch through its nodes
// (a hub end's own node among them), not those that stay inside, which
// patchPairDistance takes from the endpoint table and combines with these
// (vg_patch_pairs.h). `beaten` is the distance inside the patch: the reads are pruned to
// the paths that could be shorter, and *out is exact only below it (at or above it, some
// length at least as long as the full reads' answer, or +inf). False, nothing done, for
// any other pair (two hubs among them).
bool hubLeavingDistance(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, float beaten, float* out);

// Vertex x's fewest label steps to a first-layer node of its patch (every path that leaves
// the patch is at least this long, up to the steps' rounding); 65535 when it reaches none,
// 0 when the labels do not answer for x or x is a hub.
uint16_t hubBorderSteps(const vg_graph& g, vg_workspace& ws, uint32_t x);

// Vertex x's landmark distances as a label query takes them, in the labels' metric (a
// hub's own, else through its first-layer patch's nodes), into out[landmarkCount], and
// how far each may be off beyond the landmark steps' rounding; -1 when the labels do not
// answer for x. For the tests.
float hubEndpointLandmarks(const vg_graph& g, vg_workspace& ws, uint32_t x, float* out);

// The lower bound a label query takes from vertex x to the hubs of bounded block `block`
// (0 <= block < the workspace's block count), with the kernels g selects (AVX2 or
// portable), or with `sphereOnly` the one it tries first, from the block's sphere alone
// (the workspace's copy, shrunk as the query does); -1 when the labels do not answer for x or the blob has no block
// bounds. For the tests.
float hubBlockBound(const vg_graph& g, vg_workspace& ws, uint32_t x, uint32_t block, bool sphereOnly = false);

// Vertex x's distances in label steps to the first-layer nodes of its patch, as a label
// query takes them (from the workspace's endpoint table where it has one), into
// out[slot count of that patch]; that count, 0 when the labels do not answer for x. For
// the tests.
uint32_t hubEndpointSteps(const vg_graph& g, vg_workspace& ws, uint32_t x, uint16_t* out);

// Fills an endpoint table laid out for g (vg_endpoint_table.h): every interior vertex's
// steps as innerSteps works them out, and every second-layer patch's columns.
void fillEndpointTable(const vg_graph& g, vg_endpoint_table& table);

// True when first-layer node `node` is a slot of first-layer patch `first`.
bool hubInPatch(const vg_graph& g, uint32_t node, uint32_t first);

// The longest node edge of vertex t's second-layer patches (the workspace's per-patch
// figure, filled at init): how far an unfolded crossing next to t may undercut the better
// of its two node paths.
float nodeEdgeReach(const vg_graph& g, const vg_workspace& ws, uint32_t t);

// Row of `node` among the inner rows of first-layer patch `first` (binary search of its
// sorted node list), kNone if absent.
uint32_t innerRow(const vg_graph& g, uint32_t first, uint32_t node);

}  // namespace vg
