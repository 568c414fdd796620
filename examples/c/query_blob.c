/* Maps a .vgeo blob and answers each kind of query, the way an engine would: the blob in
 * memory the host owns, the graph in memory the host gives, one workspace per thread.
 *   query_blob BLOB.vgeo */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "vorogeo.h"

static void* read_file(const char* path, size_t* size) {
    FILE* f = fopen(path, "rb");
    void* data = NULL;
    long n;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0) {
        data = malloc((size_t)n);
        if (data && fread(data, 1, (size_t)n, f) != (size_t)n) {
            free(data);
            data = NULL;
        }
        *size = (size_t)n;
    }
    fclose(f);
    return data;
}

static int check(vg_status st, const char* what) {
    if (st != VG_OK) fprintf(stderr, "query_blob: %s: %s\n", what, vg_status_string(st));
    return st == VG_OK;
}

int main(int argc, char** argv) {
    size_t blob_size = 0, need = 0, ws_size, i;
    void *blob, *graph_memory, *ws_memory;
    const vg_graph* g = NULL;
    vg_workspace* ws = NULL;
    uint32_t n, target, targets[3];
    float d = 0, within = 0, farthest = 0, *field;
    size_t nearest = 0;
    if (argc != 2) {
        fprintf(stderr, "usage: query_blob BLOB.vgeo\n");
        return 2;
    }
    blob = read_file(argv[1], &blob_size);
    if (!blob) {
        fprintf(stderr, "query_blob: cannot read %s\n", argv[1]);
        return 1;
    }
    printf("vorogeo %s, blob format %u\n", vg_version_string(), vg_blob_format_version());
    if (!check(vg_open_size(blob, blob_size, &need), "vg_open_size")) return 1;
    graph_memory = malloc(need);
    if (!graph_memory || !check(vg_open(blob, blob_size, graph_memory, need, &g), "vg_open")) return 1;
    ws_size = vg_workspace_size(g);
    ws_memory = malloc(ws_size);
    if (!ws_memory || !check(vg_workspace_init(g, ws_memory, ws_size, &ws), "vg_workspace_init")) return 1;

    n = vg_vertex_count(g);
    target = n / 2;
    if (!check(vg_distance(g, ws, 0, target, &d), "vg_distance")) return 1;
    printf("distance 0 -> %u = %.5f\n", target, d);
    if (!check(vg_distance_within(g, ws, 0, target, d * 0.5f, &within), "vg_distance_within")) return 1;
    printf("within half of it: %s\n", isinf(within) ? "no" : "yes");
    field = (float*)malloc(sizeof(float) * n);
    if (!field || !check(vg_distance_field(g, ws, targets, 0, field), "vg_distance_field")) return 1;
    targets[0] = 0;
    if (!check(vg_distance_field(g, ws, targets, 1, field), "vg_distance_field")) return 1;
    for (i = 0; i < n; ++i)
        if (isfinite(field[i]) && field[i] > farthest) farthest = field[i];
    printf("farthest vertex from 0: %.5f\n", farthest);
    targets[0] = n - 1;
    targets[1] = target;
    targets[2] = n / 3;
    if (!check(vg_nearest(g, ws, 0, targets, 3, &nearest, &d), "vg_nearest")) return 1;
    printf("nearest of 3 targets: index %u at %.5f\n", (unsigned)nearest, d);
    free(field);
    free(ws_memory);
    free(graph_memory); /* ends the graph: nothing else to close */
    free(blob);
    return 0;
}
