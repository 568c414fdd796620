// Surface-point helpers of the public API: faces, points at vertices, positions.
#include "vg_point.h"

extern "C" uint32_t vg_face_count(const vg_graph* graph) { return graph ? graph->faceCount : 0; }

extern "C" vg_status vg_face_vertices(const vg_graph* graph, uint32_t face, uint32_t out_vertices[3]) {
    if (graph == nullptr || out_vertices == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (face >= graph->faceCount) return VG_ERR_INVALID_POINT;
    for (int k = 0; k < 3; ++k) out_vertices[k] = graph->faceVertices[3 * uint64_t(face) + k];
    return VG_OK;
}

extern "C" vg_status vg_vertex_point(const vg_graph* graph, uint32_t vertex, vg_point* out_point) {
    if (graph == nullptr || out_point == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (vertex >= graph->vertexCount || graph->vertexHalfedge[vertex] == vg::kNone) return VG_ERR_INVALID_VERTEX;
    const uint32_t h = graph->vertexHalfedge[vertex];
    out_point->face = h / 3;
    for (uint32_t k = 0; k < 3; ++k) out_point->bary[k] = k == h % 3 ? 1.0f : 0.0f;
    return VG_OK;
}

extern "C" vg_status vg_point_position(const vg_graph* graph, const vg_point* point, float out_xyz[3]) {
    if (graph == nullptr || point == nullptr || out_xyz == nullptr) return VG_ERR_INVALID_ARGUMENT;
    vg::Endpoint e;
    if (vg::resolvePoint(*graph, *point, e) != VG_OK) return VG_ERR_INVALID_POINT;
    for (int i = 0; i < 3; ++i) out_xyz[i] = e.position[i];
    return VG_OK;
}
