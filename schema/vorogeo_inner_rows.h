/* Hub-label inner rows that a blob leaves to its readers (container flag
 * VG_FLAG_INNER_ROWS_AT_OPEN), shared by the baker and the runtime. Plain C99.
 *
 * Why: a first-layer patch's inner rows (hub_inner of schema/vorogeo.fbs) are shortest
 * distances inside its second-layer node graph, which the blob holds anyway; stored, they
 * are a fifth of a labelled blob (igea: ~41 of 184 bytes per vertex). A reader that
 * computes them spends CPU at open instead (one label-correcting search per 16 columns).
 *
 * Such a blob stores the table as zeros (it compresses to almost nothing), and every reader
 * computes entry (r, k) of first-layer patch f as the baker does: the shortest distance in
 * double precision from slot k's node to inner node r, over the node x node blocks of f's
 * second-layer patches (a row's entry j of patch q adds quantum * (double)q.scale, the
 * product exact in a double, the sums rounded in the path's order, so any search order
 * ends at the same bits), rounded to a float, then to steps with vg_label_steps. A slot
 * whose node is merged away starts at distance 0 at its own rows (as a query endpoint
 * does) and is no row's column.
 *
 * A reader keeps a patch's search in fixed memory, so a blob with this flag keeps within
 * the limits below (the baker refuses to write one that does not; vg_open refuses one). */
#ifndef VOROGEO_INNER_ROWS_H
#define VOROGEO_INNER_ROWS_H

#include <math.h>
#include <stdint.h>

#include "vorogeo_label_coding.h"

/* Per first-layer patch: inner rows plus slots whose node is merged away. */
#define VG_INNER_AT_OPEN_MAX_NODES 16384u
/* Per first-layer patch: its second-layer patches, and their node slots together. */
#define VG_INNER_AT_OPEN_MAX_CHILDREN 4096u
#define VG_INNER_AT_OPEN_MAX_CHILD_NODES 65536u

/* A distance in 16-bit steps of `scale` (labels and inner rows alike): round to nearest,
 * at most 65534; 65535 ("no path") for +inf or NaN. */
static inline uint16_t vg_label_steps(double distance, float scale) {
    double steps;
    if (!(distance - distance == 0.0)) return (uint16_t)VG_LABEL_NO_PATH;
    steps = floor(distance / (double)scale + 0.5);
    return steps < 65534.0 ? (uint16_t)steps : (uint16_t)65534u;
}

#endif
