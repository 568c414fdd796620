// Landmark distances of the hubs in the hub labels' own metric (vorogeo.fbs hub_landmarks).
//
// A label query drops the blocks of hubs that no path within its upper bound can pass, by
// lower bounds |l(h) - l(x)| from landmark distances l. Such a bound holds for the labels'
// distances only if l is 1-Lipschitz in their metric: shortest paths over the first-layer
// patch matrices (the overlay the labels are computed on). The landmark table is taken over
// the second layer, up to 1.5% longer, so bounds from it would have to be shrunk. Here the
// table's values at the first-layer nodes are lowered until no matrix entry undercuts
// them (l(b) <= l(a) + w(a, b)): the largest such function below the table, close to it,
// and a bound that needs no shrink.
#pragma once

#include <cstdint>
#include <vector>

#include "vorogeo_generated.h"

namespace vorogeo {

// The first-layer matrices as the label stage unpacks them (hub_labels.cpp).
struct FirstLayerOverlay {
    const std::vector<uint64_t>& quantaBegin;  // patches + 1 offsets into quanta
    const std::vector<uint16_t>& quanta;       // per patch its slot x slot matrix
    const std::vector<double>& scale;          // per patch: distance per quantum
    const std::vector<uint32_t>& slotNode;     // per slot (of the graph's slot list): its node
    uint32_t noPath;                           // the quantum that means "no path"
};

// Per hub (hubNode: its node) and landmark of graph g, hub-major: the distance in landmark
// steps, rounded down (so that steps times the landmark's scale, as the runtime computes
// it, is never above it), at most 65534; 65535 where neither the table nor any path gives
// one. Empty without landmarks. One search per landmark, in parallel: the same bytes for
// any thread count.
std::vector<uint16_t> hubLandmarkSteps(const fb::Graph& g, const FirstLayerOverlay& overlay,
                                       const std::vector<uint32_t>& hubNode);

}  // namespace vorogeo
