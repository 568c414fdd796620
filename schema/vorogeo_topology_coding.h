/* Delta coding of the blob's mesh topology (face_vertices, face_twin, vertex_halfedge of
 * schema/vorogeo.fbs) in a blob whose container has VG_FLAG_CODED_DISTANCES, shared by the
 * baker (encoder), the runtime and the tools (decoders). Plain C99, no dependencies.
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
 * A valid index is below 2^31, so no coded difference is 0xFFFFFFFF. */
#ifndef VOROGEO_TOPOLOGY_CODING_H
#define VOROGEO_TOPOLOGY_CODING_H

#include <stdint.h>

#define VG_TOPOLOGY_NONE 0xFFFFFFFFu

static inline uint32_t vg_topology_zigzag(uint32_t difference) {
    return (difference << 1) ^ (0u - (difference >> 31));
}

static inline uint32_t vg_topology_unzigzag(uint32_t code) { return (code >> 1) ^ (0u - (code & 1u)); }

/* Codes (decode = 0) or decodes (decode = 1) the three arrays in place. */
static inline void vg_code_topology(uint32_t* face_vertices, uint32_t* face_twin, uint64_t halfedges,
                                    uint32_t* vertex_halfedge, uint64_t vertices, int decode) {
    uint64_t i;
    if (decode) {
        uint32_t previous = 0;
        for (i = 0; i < halfedges; ++i) {
            previous += vg_topology_unzigzag(face_vertices[i]);
            face_vertices[i] = previous;
        }
    } else {
        for (i = halfedges; i-- > 0;) face_vertices[i] = vg_topology_zigzag(face_vertices[i] - (i ? face_vertices[i - 1] : 0u));
    }
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
