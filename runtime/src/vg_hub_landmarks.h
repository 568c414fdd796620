// Landmark distances of the hubs in the hub labels' own metric, computed at workspace init.
//
// A label query drops the blocks of hubs that no path within its upper bound can pass, by
// lower bounds |l(h) - l(x)| from landmark distances l. Such a bound holds for the labels'
// distances only if l is 1-Lipschitz in their metric: the shortest paths over the
// first-layer patch matrices between first-layer nodes (baker/hub_labels.cpp). The blob's
// landmark table is taken over the second layer, up to 1.5% longer, so the bounds from it
// had to be shrunk by 2%. Here the table's values at the hubs are lowered until no
// first-layer matrix entry is undercut (l(b) <= l(a) + w(a, b)): the largest such function
// below the table, close to it, and a sound bound with no shrink.
// Internal to the runtime.
#pragma once

#include "vg_graph.h"
#include "vg_layout.h"

namespace vg {

// What the computation needs besides its output, carved by the workspace's layout.
struct HubLandmarkScratch {
    float* distance;  // per hub kHubLandmarkLanes landmarks' current values
    float* key;       // per hub: its queue key
    uint32_t* heap;   // binary heap of hubs
    uint32_t* heapAt; // per hub: its heap position, kNone when not queued
    uint16_t* pending;  // per hub: the lanes lowered since it last relaxed
    uint32_t* hubNode;  // per hub: its node
};
constexpr uint32_t kHubLandmarkLanes = 16;  // landmarks per pass

// Takes the scratch from L (measuring when L.base is null); empty without labels.
HubLandmarkScratch takeHubLandmarkScratch(const vg_graph& g, Layout& L);

// out[h * landmarkCount + k]: hub h's distance to landmark k in the labels' metric, in
// landmark steps rounded down (kLandmarkUnreachable: none). When some first-layer node is
// no hub (a graph pruned at bake), the labels' metric has paths through nodes without a
// hub number: every entry is then kLandmarkUnreachable, no landmark bound.
void computeHubLandmarks(const vg_graph& g, const HubLandmarkScratch& scratch, uint16_t* out);

}  // namespace vg
