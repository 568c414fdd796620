/* vorogeo runtime: fast approximate geodesic distances on a baked triangle mesh.
 *
 * C99 API over a .vgeo blob written by `vorogeo bake`. The library never allocates memory
 * (the caller supplies every byte it uses, or an allocator callback on the convenience
 * path vg_open_file), never throws, and has no global state.
 *
 * Typical use:
 *
 *     size_t need;
 *     vg_open_size(blob, blob_size, &need);             // bytes the graph handle needs
 *     void* mem = my_alloc(need);
 *     const vg_graph* g;
 *     if (vg_open(blob, blob_size, mem, need, &g) != VG_OK) ...;
 *     void* wmem = my_alloc(vg_workspace_size(g));      // one workspace per thread
 *     vg_workspace* ws;
 *     vg_workspace_init(g, wmem, vg_workspace_size(g), &ws);
 *     float d;
 *     vg_distance(g, ws, source, target, &d);
 *
 * Ownership and lifetimes. A vg_graph lives inside the memory given to vg_open and points
 * into it; for an uncompressed blob it also points into the blob itself (zero copy), so
 * both must outlive the graph. Nothing needs closing: freeing that memory ends the graph.
 * A vg_workspace lives inside its memory and belongs to the graph it was made for.
 *
 * Thread safety. A graph is immutable after vg_open: any number of threads may query one
 * graph at once, each with its own workspace. A workspace is used by one query at a time.
 *
 * Distances are in mesh units. Two vertices with no path between them (different
 * connected components, or a vertex used by no triangle) are at distance +infinity
 * (the float INFINITY), in every query. Vertex ids are the mesh's input vertex indices. */
#ifndef VOROGEO_H
#define VOROGEO_H

#include <stddef.h>
#include <stdint.h>

/* Exported symbols of the shared library (everything else stays hidden). */
#if defined(__GNUC__) || defined(__clang__)
#define VG_API __attribute__((visibility("default")))
#else
#define VG_API
#endif

/* Library version (this header's). CMake checks that it matches the project version. */
#define VG_VERSION_MAJOR 0
#define VG_VERSION_MINOR 1
#define VG_VERSION_PATCH 0
#define VG_VERSION_NUMBER ((VG_VERSION_MAJOR << 16) | (VG_VERSION_MINOR << 8) | VG_VERSION_PATCH)
/* Blob format this library reads. Independent of the library version: it changes only
 * when the bytes of a .vgeo file change meaning (docs/FORMAT.md). */
#define VG_BLOB_FORMAT_VERSION 12

#ifdef __cplusplus
extern "C" {
#endif

/* Status codes returned by every fallible call. 0 is success. */
typedef enum vg_status {
    VG_OK = 0,
    VG_ERR_INVALID_ARGUMENT = 1,    /* NULL pointer, zero size or a value out of its range */
    VG_ERR_BUFFER_TOO_SMALL = 2,    /* caller memory smaller than the size query said */
    VG_ERR_TRUNCATED = 3,           /* the blob is shorter than its header says */
    VG_ERR_BAD_MAGIC = 4,           /* not a .vgeo blob */
    VG_ERR_UNSUPPORTED_VERSION = 5, /* a format version this library does not read */
    VG_ERR_UNSUPPORTED_FLAGS = 6,   /* unknown flags, or compressed while built without zstd */
    VG_ERR_CHECKSUM = 7,            /* payload bytes do not match the header's checksum */
    VG_ERR_DECOMPRESSION = 8,       /* the zstd frames are corrupt or of the wrong size */
    VG_ERR_CORRUPT_STRUCTURE = 9,   /* the flatbuffer fails verification (or its arrays overlap where decoded) */
    VG_ERR_CORRUPT_CONTENT = 10,    /* an index out of range or inconsistent counts */
    VG_ERR_INVALID_VERTEX = 11,     /* a vertex id >= vg_vertex_count() */
    VG_ERR_WRONG_WORKSPACE = 12,    /* the workspace was made for another graph */
    VG_ERR_IO = 13,                 /* vg_open_file could not open, read or map the file */
    VG_ERR_OUT_OF_MEMORY = 14,      /* the allocator callback returned NULL */
    VG_ERR_NO_SLICED_QUERY = 15,    /* vg_distance_field_step without a live sliced query */
    VG_ERR_INVALID_POINT = 16,      /* face out of range, or barycentric weights NaN, negative
                                       or not summing to 1 (beyond VG_BARY_TOLERANCE) */
    VG_ERR_PATH_FAILED = 17,        /* vg_path could not trace a path on the surface (a defect:
                                       never seen in the tests; please report the blob and points) */
    VG_ERR_NO_HUB_LABELS = 18       /* the graph has no hub labels (bake --hub-labels) */
} vg_status;

/* Human-readable, static, never NULL. Unknown codes give "unknown status". */
VG_API const char* vg_status_string(vg_status status);

/* Library version, for example "0.1.0"; static storage. */
VG_API const char* vg_version_string(void);
/* Library version as (major << 16) | (minor << 8) | patch. */
VG_API unsigned vg_version_number(void);
/* Blob format version the library reads (VG_BLOB_FORMAT_VERSION of the library's build). */
VG_API unsigned vg_blob_format_version(void);
/* 1 when this build opens zstd-compressed blobs, 0 when built without zstd. */
VG_API int vg_supports_compression(void);

/* ------------------------------------------------------------------ opening */

typedef struct vg_graph vg_graph;

/* Bytes of caller memory vg_open needs for this blob: the handle, plus for a compressed
 * blob the decompressed graph and the decompression context (and, for its coded
 * distances, the decoder's scratch: docs/FORMAT.md). Reads only the 48-byte header (and,
 * compressed, the headers of the zstd frames, whose stated sizes add up to the unpacked
 * size); errors as vg_open for a bad header. */
VG_API vg_status vg_open_size(const void* blob, size_t blob_size, size_t* out_memory_size);

/* Checks the blob (header, checksum, decompression, flatbuffers verifier, every index
 * and count), decodes coded distances, computes the hub-label inner rows of a blob baked
 * with --inner-rows-at-open (igea: ~0.4 s more, one thread), and builds a graph handle
 * inside `memory` (any alignment, at least vg_open_size bytes). On error *out_graph is
 * NULL and nothing refers to the memory.
 * On Linux it first asks for transparent huge pages in the whole 2 MB pages of `memory`
 * (madvise MADV_HUGEPAGE; a hint, nothing outside `memory` is touched): memory not yet
 * written (fresh from malloc or mmap) then costs far fewer TLB misses per query. */
VG_API vg_status vg_open(const void* blob, size_t blob_size, void* memory, size_t memory_size,
                  const vg_graph** out_graph);

/* Allocator for the convenience path: alloc returns size bytes (NULL on failure), free
 * releases them. `user` is passed through. */
typedef struct vg_allocator {
    void* (*alloc)(void* user, size_t size);
    void (*free)(void* user, void* memory);
    void* user;
} vg_allocator;

/* Opens a .vgeo file: an uncompressed blob is mapped read-only (zero copy, where the
 * platform has mmap), a compressed one is read and decompressed into memory from
 * `allocator` (required). Release with vg_close_file. */
VG_API vg_status vg_open_file(const char* path, const vg_allocator* allocator, const vg_graph** out_graph);
/* Releases a graph from vg_open_file (mapping and memory). NULL is ignored. */
VG_API void vg_close_file(const vg_graph* graph);

/* Facts about an open graph. */
VG_API uint32_t vg_vertex_count(const vg_graph* graph);
VG_API uint32_t vg_node_count(const vg_graph* graph);
/* Length of the diagonal of the mesh's bounding box, the natural unit of error. */
VG_API float vg_bbox_diagonal(const vg_graph* graph);
/* Hub labels in the blob (bake --hub-labels): 1 if present, 0 if not (or graph is NULL). */
VG_API int vg_has_hub_labels(const vg_graph* graph);

/* ------------------------------------------------------------------ workspaces */

typedef struct vg_workspace vg_workspace;

/* Bytes of one workspace for this graph (per-thread scratch of every query). */
VG_API size_t vg_workspace_size(const vg_graph* graph);
/* Builds a workspace inside `memory` (any alignment, at least vg_workspace_size bytes);
 * asks for huge pages in it as vg_open does, and writes all of it once, so that no query
 * pays for a page's first touch. */
VG_API vg_status vg_workspace_init(const vg_graph* graph, void* memory, size_t memory_size,
                            vg_workspace** out_workspace);

/* An endpoint table: optional, for faster hub-label queries at a memory cost. A label
 * query otherwise works out each endpoint's distances to the first-layer nodes of its
 * patch from the inner rows of its patch's ~55 border nodes, and meets next to the target
 * through those rows again; the table holds the first per vertex and the rows per
 * second-layer patch column by column, so that a query reads one row per endpoint, the
 * columns of the exits that can matter, and takes its landmark distances as stored: the
 * same bits. It also holds each first-layer patch's node-to-node distances, through which
 * two vertices inside one first-layer patch (which the labels alone do not answer) meet
 * without a search: those answers differ from the searches' (closer to the exact
 * distances on igea's golden pairs), and are still symmetric. igea (134K vertices):
 * 204 MB, built in ~1.6 s (x16: 3.8 GB, ~50 s), label queries p50 about -30% (-20%
 * between other work's turns), pairs inside one patch ~27 us instead of ~40
 * (BENCHMARKS.md). Built once per
 * graph into caller memory, immutable: any number of workspaces and threads may read it.
 * It must outlive the workspaces that use it; vg_workspace_use_endpoint_table(ws, NULL)
 * detaches it. */
typedef struct vg_endpoint_table vg_endpoint_table;
/* Bytes the table needs for this graph; 0 when the graph has no hub labels (or is NULL). */
VG_API size_t vg_endpoint_table_size(const vg_graph* graph);
/* Builds the table inside `memory` (any alignment, at least vg_endpoint_table_size bytes);
 * one thread. VG_ERR_NO_HUB_LABELS for a graph without labels; VG_ERR_CORRUPT_CONTENT for
 * labels whose inner rows miss a first-layer node (no baker writes such a blob). A
 * first-layer patch too large for the node distances' fixed search (the limits a blob
 * whose inner rows vg_open computes keeps) gets none: its pairs are searched. */
VG_API vg_status vg_endpoint_table_build(const vg_graph* graph, void* memory, size_t memory_size,
                                         const vg_endpoint_table** out_table);
/* Lets the workspace's label queries read `table` (NULL: stop reading one);
 * VG_ERR_WRONG_WORKSPACE when the table was built for another graph. Not concurrently
 * with a query on the same workspace. */
VG_API vg_status vg_workspace_use_endpoint_table(vg_workspace* workspace, const vg_endpoint_table* table);

/* How a workspace's point-to-point queries (vg_distance, vg_distance_within,
 * vg_point_distance, vg_point_distance_within) find their answer (vg_path always searches
 * bidirectionally: the route it traces from the meeting point pulls tauter):
 * VG_SEARCH_HUB_LABELS (set by vg_workspace_init): two vertices in different first-layer
 *   patches are answered from the blob's hub labels (bake --hub-labels) in microseconds,
 *   without a search; everything else (no labels in the blob, surface points, pairs in
 *   one first-layer patch) as VG_SEARCH_DIRECTED.
 * VG_SEARCH_DIRECTED: A* from the source with the whole lower bound to the target as its
 *   potential. A short pair (one first-layer patch, or closer than a tenth of the
 *   bounding-box diagonal) is also searched from the target and gets the shorter answer.
 * VG_SEARCH_BIDIRECTIONAL: the thesis's bidirectional A* (3.7.1), for comparison.
 * All three answer on the same graph; they differ only in which unfolded border crossings
 * they meet and in how distances are rounded (BENCHMARKS.md has them side by side). The
 * mode stays until changed; like every workspace call, not concurrently with a query on
 * the same workspace. */
typedef enum vg_search_mode {
    VG_SEARCH_DIRECTED = 0,
    VG_SEARCH_BIDIRECTIONAL = 1,
    VG_SEARCH_HUB_LABELS = 2
} vg_search_mode;
VG_API vg_status vg_workspace_set_search(vg_workspace* workspace, vg_search_mode mode);

/* ------------------------------------------------------------------ queries */

/* Geodesic distance between two vertices: an A* search over the two-layer graph of the
 * thesis (3.7.1; directed or bidirectional, vg_workspace_set_search); two vertices of one
 * second-layer patch are answered by a lookup, refined only when a path through the graph
 * is shorter. */
VG_API vg_status vg_distance(const vg_graph* graph, vg_workspace* workspace, uint32_t source,
                      uint32_t target, float* out_distance);

/* As vg_distance, but gives up as soon as the distance must exceed max_distance:
 * *out_distance is the distance when it is at most max_distance, else +infinity. */
VG_API vg_status vg_distance_within(const vg_graph* graph, vg_workspace* workspace, uint32_t source,
                             uint32_t target, float max_distance, float* out_distance);

/* Distance from the nearest of `source_count` sources to every vertex (thesis 3.7.2):
 * out_distances has vg_vertex_count() floats. On x86-64 the inner loops use AVX2 where
 * the CPU has it (vg_open checks); the result is the same bits either way. */
VG_API vg_status vg_distance_field(const vg_graph* graph, vg_workspace* workspace,
                            const uint32_t* sources, size_t source_count, float* out_distances);

/* As vg_distance_field, and also which source is nearest to each vertex (a geodesic
 * Voronoi labelling): out_nearest[v] is an index into `sources` (the first listing of a
 * vertex given twice), or source_count where no source is reachable. out_nearest has
 * vg_vertex_count() entries; NULL makes this vg_distance_field. */
VG_API vg_status vg_distance_field_nearest(const vg_graph* graph, vg_workspace* workspace,
                                    const uint32_t* sources, size_t source_count,
                                    float* out_distances, uint32_t* out_nearest);

/* The same query time-sliced, for hosts that spread it over frames (as Detour's sliced
 * path search): vg_distance_field_begin checks the arguments and starts it; every
 * vg_distance_field_step does at most `max_steps` units of work (one unit: one patch
 * searched, 256 node distances written, one patch filled, or one source's own patches
 * written; each bounded by the size of a patch) and sets *out_done to 1 once out_distances (and out_nearest, if given)
 * hold bit for bit what vg_distance_field_nearest gives; further steps do nothing. Until
 * then the caller keeps `sources` and the outputs alive and does not read them, and the
 * workspace belongs to the sliced query: any other query on it abandons the sliced one
 * (its next step returns VG_ERR_NO_SLICED_QUERY). */
VG_API vg_status vg_distance_field_begin(const vg_graph* graph, vg_workspace* workspace,
                                  const uint32_t* sources, size_t source_count,
                                  float* out_distances, uint32_t* out_nearest);
VG_API vg_status vg_distance_field_step(const vg_graph* graph, vg_workspace* workspace,
                                 uint32_t max_steps, int* out_done);

/* The same query on several threads (a job system's workers). The call seeds the search on
 * workspaces[0] (the query's own), then calls parallel_for(user_context, workspace_count,
 * task, task_context) once: the caller's scheduler must call task(task_context, i) once for
 * every i < workspace_count, on any threads in any order, and return when all have
 * returned (so that their writes are seen by this thread afterwards, as any job system's
 * wait gives). The first task to start runs the search over the patches' nodes and tells,
 * as it goes, which patches' node distances are final; the others fill those patches
 * meanwhile, each with a workspace of its own as scratch, and all share the rest of the fill
 * after the search. A task waits only for a search that is running, so a scheduler that
 * runs the tasks one after another is fine too (parallel_for NULL: this thread runs them
 * in turn). The outputs are bit for bit vg_distance_field_nearest's.
 * The workspaces are distinct, of this graph, and belong to the call until it returns (a
 * sliced query on any of them is abandoned). VG_ERR_INVALID_ARGUMENT for none, a NULL or a
 * repeated one. igea: ~1.5x on two threads (BENCHMARKS.md). */
typedef void (*vg_task)(void* task_context, uint32_t index);
typedef void (*vg_parallel_for)(void* user_context, uint32_t count, vg_task task, void* task_context);
VG_API vg_status vg_distance_field_parallel(const vg_graph* graph, vg_workspace* const* workspaces,
                                            uint32_t workspace_count, const uint32_t* sources,
                                            size_t source_count, float* out_distances,
                                            uint32_t* out_nearest, vg_parallel_for parallel_for,
                                            void* user_context);

/* Which of `target_count` targets is geodesically nearest to `source`: its index in
 * `targets` (the first such index when a vertex is listed twice) and its distance.
 * When no target is reachable: index = target_count and distance = +infinity. */
VG_API vg_status vg_nearest(const vg_graph* graph, vg_workspace* workspace, uint32_t source,
                     const uint32_t* targets, size_t target_count, size_t* out_index,
                     float* out_distance);

/* ------------------------------------------------------------------ surface points */

/* A point on the surface: face index (0 .. vg_face_count() - 1) and barycentric weights of
 * the face's three vertices (vg_face_vertices order). Weights must be finite, at least
 * -VG_BARY_TOLERANCE and sum to 1 within VG_BARY_TOLERANCE (they are then clamped to >= 0
 * and renormalised); otherwise a query returns VG_ERR_INVALID_POINT. A weight of 1 (within
 * 1e-6) makes the point that vertex, so vertex and point queries agree there. */
typedef struct vg_point {
    uint32_t face;
    float bary[3];
} vg_point;
#define VG_BARY_TOLERANCE 1e-4f

VG_API uint32_t vg_face_count(const vg_graph* graph);
/* The three vertex ids of a face (counter-clockwise). */
VG_API vg_status vg_face_vertices(const vg_graph* graph, uint32_t face, uint32_t out_vertices[3]);
/* A point at vertex `vertex` (one of its faces, weight 1 on it); VG_ERR_INVALID_VERTEX for a
 * vertex out of range or used by no face. */
VG_API vg_status vg_vertex_point(const vg_graph* graph, uint32_t vertex, vg_point* out_point);
/* Position of a point in mesh coordinates. */
VG_API vg_status vg_point_position(const vg_graph* graph, const vg_point* point, float out_xyz[3]);

/* vg_distance / vg_distance_within between surface points. */
VG_API vg_status vg_point_distance(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                                   const vg_point* target, float* out_distance);
VG_API vg_status vg_point_distance_within(const vg_graph* graph, vg_workspace* workspace,
                                          const vg_point* source, const vg_point* target,
                                          float max_distance, float* out_distance);

/* vg_distance_field_nearest from surface points: distance to every vertex and, when
 * out_nearest is not NULL, the index of the nearest source (source_count where none). */
VG_API vg_status vg_point_distance_field(const vg_graph* graph, vg_workspace* workspace,
                                         const vg_point* sources, size_t source_count,
                                         float* out_distances, uint32_t* out_nearest);
/* The same on several threads, as vg_distance_field_parallel (the same bits as
 * vg_point_distance_field). */
VG_API vg_status vg_point_distance_field_parallel(const vg_graph* graph, vg_workspace* const* workspaces,
                                                  uint32_t workspace_count, const vg_point* sources,
                                                  size_t source_count, float* out_distances,
                                                  uint32_t* out_nearest, vg_parallel_for parallel_for,
                                                  void* user_context);

/* vg_nearest between surface points (ties: the lowest index). */
VG_API vg_status vg_point_nearest(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                                  const vg_point* targets, size_t target_count, size_t* out_index,
                                  float* out_distance);

/* The k targets nearest to `source`, closest first (ties: lower index first), with their
 * distances: out_indices and out_distances have room for k entries; *out_found is
 * min(k, number of reachable targets), and entries past it are target_count / +infinity.
 * One search for all of them, stopped as soon as the k-th is known: far cheaper than k
 * separate queries. Vertices enter as points through vg_vertex_point. */
VG_API vg_status vg_point_k_nearest(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                                    const vg_point* targets, size_t target_count, size_t k,
                                    size_t* out_indices, float* out_distances, size_t* out_found);

/* ------------------------------------------------------------------ geodesic paths */

/* One vertex of a path polyline: where it lies (a point inside a face, on an edge: the
 * weight of the opposite corner is 0, or at a vertex: weight 1 on it) and its position. */
typedef struct vg_path_point {
    vg_point point;
    float position[3];
} vg_path_point;

/* The geodesic path between two surface points: a polyline from source to target that
 * runs across faces and through vertices, consecutive points always on one common face.
 * It follows the route of the point-to-point search (vg_point_distance) through the patch
 * borders, traced face by face down the stored distances, and is then pulled taut: the
 * faces it crosses are unfolded into the plane and the shortest way through them replaces
 * the trace (a few passes; where it bends round a vertex, the next pass tries the other
 * side). *out_distance is the length of the returned polyline, which can differ a little
 * from vg_point_distance's answer for the same points (BENCHMARKS.md has the spread, and
 * both against exact geodesics: on igea the path is 0.016% longer than the geodesic on
 * average, the search's distance 0.065% off). A path of more points than the workspace
 * holds (vg_workspace_size reserves 2 per face, at most 16,384) comes back as traced, not
 * pulled taut, with vg_point_distance's answer.
 *
 * Size query first: with out_points NULL and capacity 0 the call returns VG_OK and sets
 * *out_count to the number of points needed. With a buffer of `capacity` points it writes
 * *out_count points, or returns VG_ERR_BUFFER_TOO_SMALL with *out_count = the number
 * needed (buffer contents then unspecified). The count depends only on graph and points,
 * never on the capacity. A source equal to the target gives one point; points in different
 * components give *out_count = 0 and +infinity. Uses the workspace like any query. */
VG_API vg_status vg_path(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                         const vg_point* target, vg_path_point* out_points, size_t capacity, size_t* out_count,
                         float* out_distance);

#ifdef __cplusplus
}
#endif

#endif /* VOROGEO_H */
