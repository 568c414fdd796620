// The hub-label inner rows of a blob that leaves them to its readers
// (VG_FLAG_INNER_ROWS_AT_OPEN, schema/vorogeo_inner_rows.h), computed at vg_open into the
// zeroed table, with the baker's numbers bit for bit.
#pragma once

#include <stddef.h>

#include "vg_graph.h"

namespace vg {

// Scratch for computeInnerRows, 64-byte aligned (its parts are aligned from its start): fixed, the format bounding a patch's
// search (~3.5 MB).
size_t innerRowsScratchSize();

// Fills g's hubInner (memory the caller owns), a first-layer patch at a time; avx2: the
// CPU runs AVX2 (the same numbers either way). g must have passed verifyAndBind with
// labels, its distances decoded. VG_ERR_CORRUPT_CONTENT for a table that is not zeros, a
// patch past the format's limits or a slot node that no inner row holds (no baker writes
// any of these).
vg_status computeInnerRows(const vg_graph& g, bool avx2, void* scratch);

// True when first-layer patch f's search keeps within the fixed scratch (the limits of
// vorogeo_inner_rows.h, which a blob with its inner rows stored need not keep).
bool searchFits(const vg_graph& g, uint32_t f);

// The distances between first-layer patch f's inner-row nodes over its second-layer node
// graph, by the same search: out[a * R + b] from row node a to row node b (R: f's inner
// rows; +inf: no path), summed in floats (they end as 16-bit steps of the patch's longest
// distance, far coarser than a float's rounding). The searches take the
// sources kLanes at a time in `order` (R inner rows): neighbours together drop their lanes
// together. The same scratch as computeInnerRows; the same errors.
vg_status computeNodeDistances(const vg_graph& g, uint32_t f, bool avx2, void* scratch, const uint32_t* order,
                               float* out);

}  // namespace vg
