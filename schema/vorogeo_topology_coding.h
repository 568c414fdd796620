/* Delta coding of the blob's mesh topology (face_vertices, face_twin, vertex_halfedge of
 * schema/vorogeo.fbs) and positions, and the patch edge lengths the readers compute, in a
 * blob whose container has VG_FLAG_CODED_DISTANCES, shared by the baker (encoder), the
 * runtime and the tools (decoders). Plain C99, no dependencies.
 *
 * Why: these are 32-bit indices that zstd keeps large (igea: 28 bytes per vertex of 52),
 * but in a mesh stored with any locality a face's corner is close to the corner before it,
 * a half-edge's twin close to the half-edge, and a vertex's outgoing half-edge close to six
 * times the vertex id (two faces per vertex). Their differences, zigzag-coded, are mostly
 * small and compress 2-5x.
 *
 * Coding (arithmetic modulo 2^32, so that any bytes decode to some indices, which the
 * readers then validate as they validate an uncoded blob):
 *   face_vertices[h]   -> zigzag(face_vertices[h] - face_vertices[h - 1]), the one before
 *                         h = 0 being 0;
 *   face_twin[h]       -> zigzag(face_twin[h] - h), 0xFFFFFFFF (no twin) kept;
 *   vertex_halfedge[v] -> zigzag(vertex_halfedge[v] - 6 v), 0xFFFFFFFF (unused vertex) kept.
 * A valid index is below 2^31, so no coded difference is 0xFFFFFFFF.
 *
 * Sequences (format 11): node_vertex, slots, node_edge, the offsets node_second_begin,
 * node_first_begin, node_edge_begin and (with hub labels) hub_exit_list_begin are coded
 * as face_vertices is (vg_code_sequence): increasing or locally close indices, whose
 * differences compress 2-30x (igea: 6.1 -> 2.4 bytes per vertex together).
 *
 * Positions (format 11): vg_code_positions below.
 *
 * Patch edge lengths (format 11): in such a blob every second_edges entry's length is
 * stored as 0, and a reader sets it to vg_patch_edge_length of the edge's two node
 * vertices. The baker computes the lengths with the same function, so the bits are the
 * ones it would have stored; as stored floats they took 4.4 of igea's ~200 bytes per
 * vertex, as zeros next to nothing. */
#ifndef VOROGEO_TOPOLOGY_CODING_H
#define VOROGEO_TOPOLOGY_CODING_H

#include <stdint.h>
#include <string.h>
#if !defined(__GNUC__) && !defined(__clang__)
#include <math.h>
#endif

#define VG_TOPOLOGY_NONE 0xFFFFFFFFu

/* A second_edges entry (schema/vorogeo.fbs struct PatchEdge: from, to as ushort, length
 * as float): its bytes, and where its length lies among them. */
#define VG_PATCH_EDGE_BYTES 8u
#define VG_PATCH_EDGE_LENGTH_AT 4u

static inline uint32_t vg_topology_zigzag(uint32_t difference) {
    return (difference << 1) ^ (0u - (difference >> 31));
}

static inline uint32_t vg_topology_unzigzag(uint32_t code) { return (code >> 1) ^ (0u - (code & 1u)); }

/* Codes (decode = 0) or decodes (decode = 1) `count` floats of `positions` (x, y, z per
 * vertex) in place: each float's bits become the zigzag-coded difference, modulo 2^32, from
 * the bits of the same coordinate of the vertex before (0 before the first). Neighbouring
 * vertices of a mesh file lie close together, so their coordinates share sign, exponent and
 * leading mantissa bits (igea: 7.9 -> 6.2 bytes per vertex). Bytes are moved with memcpy,
 * so the array may be seen as floats elsewhere. */
static inline void vg_code_positions(void* positions, uint64_t count, int decode) {
    unsigned char* p = (unsigned char*)positions;
    uint64_t i;
    uint32_t x, before;
    if (decode) {
        for (i = 0; i < count; ++i) {
            memcpy(&x, p + 4 * i, 4);
            before = 0;
            if (i >= 3) memcpy(&before, p + 4 * (i - 3), 4);
            x = before + vg_topology_unzigzag(x);
            memcpy(p + 4 * i, &x, 4);
        }
    } else {
        for (i = count; i-- > 0;) {
            memcpy(&x, p + 4 * i, 4);
            before = 0;
            if (i >= 3) memcpy(&before, p + 4 * (i - 3), 4);
            x = vg_topology_zigzag(x - before);
            memcpy(p + 4 * i, &x, 4);
        }
    }
}

/* The length of the mesh edge between vertices a and b: the distance of their stored float
 * positions, in float arithmetic, the square root correctly rounded. Written out term by
 * term, so that every reader and the baker give the same bits (each builds it with
 * -ffp-contract=off: a fused multiply-add would round differently). */
static inline float vg_patch_edge_length(const float* positions, uint32_t a, uint32_t b) {
    const float* pa = positions + 3 * (uint64_t)a;
    const float* pb = positions + 3 * (uint64_t)b;
    const float dx = pa[0] - pb[0], dy = pa[1] - pb[1], dz = pa[2] - pb[2];
    const float xx = dx * dx, yy = dy * dy, zz = dz * dz;
    const float sum = (xx + yy) + zz;
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_sqrtf(sum);
#else
    return sqrtf(sum);
#endif
}

/* Codes (decode = 0) or decodes (decode = 1) n indices in place: each becomes the
 * zigzag-coded difference from the one before (0 before the first). */
static inline void vg_code_sequence(uint32_t* a, uint64_t n, int decode) {
    uint64_t i;
    if (decode) {
        uint32_t previous = 0;
        for (i = 0; i < n; ++i) {
            previous += vg_topology_unzigzag(a[i]);
            a[i] = previous;
        }
    } else {
        for (i = n; i-- > 0;) a[i] = vg_topology_zigzag(a[i] - (i ? a[i - 1] : 0u));
    }
}

/* Codes (decode = 0) or decodes (decode = 1) the three arrays in place. */
static inline void vg_code_topology(uint32_t* face_vertices, uint32_t* face_twin, uint64_t halfedges,
                                    uint32_t* vertex_halfedge, uint64_t vertices, int decode) {
    uint64_t i;
    vg_code_sequence(face_vertices, halfedges, decode);
    for (i = 0; i < halfedges; ++i) {
        const uint32_t x = face_twin[i];
        if (x == VG_TOPOLOGY_NONE) continue;
        face_twin[i] = decode ? (uint32_t)i + vg_topology_unzigzag(x) : vg_topology_zigzag(x - (uint32_t)i);
    }
    for (i = 0; i < vertices; ++i) {
        const uint32_t x = vertex_halfedge[i];
        if (x == VG_TOPOLOGY_NONE) continue;
        vertex_halfedge[i] = decode ? 6u * (uint32_t)i + vg_topology_unzigzag(x) : vg_topology_zigzag(x - 6u * (uint32_t)i);
    }
}

#endif /* VOROGEO_TOPOLOGY_CODING_H */
