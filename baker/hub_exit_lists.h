// Which exits a hub-label query needs, per second-layer patch and block of hubs.
//
// A query from vertex x in second-layer patch Q (of first-layer patch P) reaches hub h of
// block b through the exits of P (its first-layer nodes that are hubs):
//
//     d(x, h) = min over exits e of d(x, e) + label(e, h),
//     d(x, e) = min over the nodes n of Q of d(x, n) + inner(n, e),
//
// so d(x, h) = min over n of d(x, n) + min over e of (inner(n, e) + label(e, h)). The
// inner minimum depends on n and h only: the exits that attain it for some node n of Q
// and some hub h of b are all the query needs in block b, whatever x is. The same holds
// backwards on the target's side. Every exit is the best for some node of P (itself, for
// one), but a patch of ~55 nodes needs ~20 of a first-layer patch's ~270 exits per block
// (igea), so a query reads that many label rows per block instead of every exit's.
#pragma once

#include <cstdint>
#include <vector>

#include "hub_labels.h"

namespace vorogeo {

// Fills labels.exitPatchBegin, exitListBegin and exitLists (HubLabels; vorogeo.fbs
// hub_exit_*) from the labels and inner rows already in `labels`, for the graph in
// `flatbuffer` (a verified Graph buffer). Leaves them empty when some first-layer patch
// has more exits than a 16-bit index holds (the runtime then reads every exit).
// Deterministic for any number of threads, with or without AVX2 (`allowAvx2` false: the
// portable loop, for the tests): the same lists bit for bit.
void computeHubExitLists(const std::vector<uint8_t>& flatbuffer, HubLabels& labels, bool allowAvx2 = true);

}  // namespace vorogeo
