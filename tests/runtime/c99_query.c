/* A plain C99 host of the runtime: loads a .vgeo file into its own memory, opens it,
 * and asks every query kind, checking the answers are coherent. Also opens the file
 * through vg_open_file with a malloc-based allocator. Exit status 0 on success. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "vorogeo.h"

static void* host_alloc(void* user, size_t size) {
    (void)user;
    return malloc(size);
}

static void host_free(void* user, void* memory) {
    (void)user;
    free(memory);
}

static int fail(const char* what, vg_status status) {
    fprintf(stderr, "c99_query: %s: %s\n", what, vg_status_string(status));
    return 1;
}

int main(int argc, char** argv) {
    FILE* file;
    long size;
    unsigned char* blob;
    void* memory;
    void* ws_memory;
    size_t need, ws_size, index;
    const vg_graph* graph = NULL;
    const vg_graph* mapped = NULL;
    vg_workspace* ws = NULL;
    vg_allocator allocator;
    vg_status st;
    uint32_t vertices, targets[3];
    float d, back, *field;

    if (argc != 2) {
        fprintf(stderr, "usage: c99_query BLOB.vgeo\n");
        return 2;
    }
    file = fopen(argv[1], "rb");
    if (!file) return fail("cannot open the blob", VG_ERR_IO);
    fseek(file, 0, SEEK_END);
    size = ftell(file);
    fseek(file, 0, SEEK_SET);
    blob = (unsigned char*)malloc((size_t)size);
    if (!blob || fread(blob, 1, (size_t)size, file) != (size_t)size) return fail("cannot read the blob", VG_ERR_IO);
    fclose(file);

    st = vg_open_size(blob, (size_t)size, &need);
    if (st != VG_OK) return fail("vg_open_size", st);
    memory = malloc(need);
    st = vg_open(blob, (size_t)size, memory, need, &graph);
    if (st != VG_OK) return fail("vg_open", st);
    ws_size = vg_workspace_size(graph);
    ws_memory = malloc(ws_size);
    st = vg_workspace_init(graph, ws_memory, ws_size, &ws);
    if (st != VG_OK) return fail("vg_workspace_init", st);

    vertices = vg_vertex_count(graph);
    printf("vorogeo %s: %u vertices, %u graph nodes, handle %lu bytes, workspace %lu bytes\n", vg_version_string(),
           (unsigned)vertices, (unsigned)vg_node_count(graph), (unsigned long)need, (unsigned long)ws_size);
    st = vg_distance(graph, ws, 0, vertices - 1, &d);
    if (st != VG_OK) return fail("vg_distance", st);
    st = vg_distance(graph, ws, vertices - 1, 0, &back);
    if (st != VG_OK) return fail("vg_distance", st);
    if (!(d > 0.0f) || isinf(d) || d != back) {
        fprintf(stderr, "c99_query: d(0, last) = %g but d(last, 0) = %g\n", d, back);
        return 1;
    }
    {
        /* With hub labels, the optional endpoint table: the same answer, bit for bit. */
        const size_t table_size = vg_endpoint_table_size(graph);
        if (table_size > 0) {
            const vg_endpoint_table* table = NULL;
            void* table_memory = malloc(table_size);
            st = vg_endpoint_table_build(graph, table_memory, table_size, &table);
            if (st != VG_OK) return fail("vg_endpoint_table_build", st);
            st = vg_workspace_use_endpoint_table(ws, table);
            if (st != VG_OK) return fail("vg_workspace_use_endpoint_table", st);
            st = vg_distance(graph, ws, 0, vertices - 1, &back);
            if (st != VG_OK) return fail("vg_distance (endpoint table)", st);
            if (back != d) {
                fprintf(stderr, "c99_query: d(0, last) = %g, with the endpoint table %g\n", d, back);
                return 1;
            }
            st = vg_workspace_use_endpoint_table(ws, NULL);
            if (st != VG_OK) return fail("vg_workspace_use_endpoint_table (NULL)", st);
            free(table_memory);
            printf("endpoint table: %lu bytes\n", (unsigned long)table_size);
        }
    }
    /* The thesis's bidirectional search answers the same pair within the unfolding. */
    st = vg_workspace_set_search(ws, VG_SEARCH_BIDIRECTIONAL);
    if (st != VG_OK) return fail("vg_workspace_set_search", st);
    st = vg_distance(graph, ws, 0, vertices - 1, &back);
    if (st != VG_OK) return fail("vg_distance (bidirectional)", st);
    if (fabsf(back - d) > 0.02f * d) {
        fprintf(stderr, "c99_query: d(0, last) = %g directed but %g bidirectional\n", d, back);
        return 1;
    }
    st = vg_workspace_set_search(ws, VG_SEARCH_DIRECTED);
    if (st != VG_OK) return fail("vg_workspace_set_search", st);
    field = (float*)malloc(sizeof(float) * vertices);
    st = vg_distance_field(graph, ws, targets, 0, field);
    if (st != VG_OK) return fail("vg_distance_field", st);
    targets[0] = 0;
    st = vg_distance_field(graph, ws, targets, 1, field);
    if (st != VG_OK) return fail("vg_distance_field", st);
    if (field[0] != 0.0f || fabsf(field[vertices - 1] - d) > 0.02f * d) {
        fprintf(stderr, "c99_query: the field disagrees with the point-to-point distance\n");
        return 1;
    }
    targets[0] = vertices - 1;
    targets[1] = vertices / 2;
    targets[2] = 1;
    st = vg_nearest(graph, ws, 0, targets, 3, &index, &d);
    if (st != VG_OK) return fail("vg_nearest", st);
    if (index >= 3) return fail("vg_nearest found nothing", VG_ERR_INVALID_ARGUMENT);
    st = vg_distance(graph, ws, 0, vertices, &d);
    if (st != VG_ERR_INVALID_VERTEX) return fail("an out-of-range vertex was accepted", st);
    {
        /* The path between vertex 0 and the last vertex: size query, then the points. */
        vg_point from, to;
        vg_path_point* path;
        size_t count = 0;
        float path_distance = 0.0f;
        if (vg_vertex_point(graph, 0, &from) != VG_OK || vg_vertex_point(graph, vertices - 1, &to) != VG_OK)
            return fail("vg_vertex_point", VG_ERR_INVALID_VERTEX);
        st = vg_path(graph, ws, &from, &to, NULL, 0, &count, &path_distance);
        if (st != VG_OK || count < 2) return fail("vg_path (size query)", st);
        path = (vg_path_point*)malloc(sizeof(vg_path_point) * count);
        st = vg_path(graph, ws, &from, &to, path, count, &count, &path_distance);
        if (st != VG_OK) return fail("vg_path", st);
        printf("path from 0 to %u: %lu points, distance %g\n", (unsigned)(vertices - 1), (unsigned long)count,
               path_distance);
        free(path);
    }
    printf("d(0, %u) = %g; nearest of {%u, %u, %u} to 0 is #%lu\n", (unsigned)(vertices - 1), back,
           (unsigned)targets[0], (unsigned)targets[1], (unsigned)targets[2], (unsigned long)index);

    allocator.alloc = host_alloc;
    allocator.free = host_free;
    allocator.user = NULL;
    st = vg_open_file(argv[1], &allocator, &mapped);
    if (st != VG_OK) return fail("vg_open_file", st);
    if (vg_vertex_count(mapped) != vertices) return fail("vg_open_file: another graph", VG_ERR_CORRUPT_CONTENT);
    vg_close_file(mapped);

    free(field);
    free(ws_memory);
    free(memory);
    free(blob);
    printf("c99_query: ok\n");
    return 0;
}
