// Proves that the runtime never allocates: replaces malloc, calloc, realloc, free,
// aligned allocation and every operator new/delete with counting versions, bakes a blob
// (allocation allowed), then counts the calls made while the runtime opens it with caller
// memory and answers every query kind. Exit status 0 only when that count is zero.
#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <new>
#include <vector>

#include "bake.h"
#include "generators.h"
#include "vorogeo.h"

extern "C" void* __libc_malloc(size_t);
extern "C" void* __libc_calloc(size_t, size_t);
extern "C" void* __libc_realloc(void*, size_t);
extern "C" void* __libc_memalign(size_t, size_t);
extern "C" void __libc_free(void*);

namespace {
// Only the main thread counts (TBB workers from the bake may still be parked).
thread_local bool counting = false;
unsigned long long calls = 0;
void count() {
    if (counting) ++calls;
}
}  // namespace

extern "C" void* malloc(size_t n) {
    count();
    return __libc_malloc(n);
}
extern "C" void* calloc(size_t a, size_t b) {
    count();
    return __libc_calloc(a, b);
}
extern "C" void* realloc(void* p, size_t n) {
    count();
    return __libc_realloc(p, n);
}
extern "C" void free(void* p) {
    if (p) count();
    __libc_free(p);
}
extern "C" void* aligned_alloc(size_t a, size_t n) {
    count();
    return __libc_memalign(a, n);
}
extern "C" void* memalign(size_t a, size_t n) {
    count();
    return __libc_memalign(a, n);
}
extern "C" int posix_memalign(void** out, size_t a, size_t n) {
    count();
    *out = __libc_memalign(a, n);
    return *out ? 0 : 12;
}
void* operator new(size_t n) { return malloc(n); }
void* operator new[](size_t n) { return malloc(n); }
void* operator new(size_t n, const std::nothrow_t&) noexcept { return malloc(n); }
void* operator new[](size_t n, const std::nothrow_t&) noexcept { return malloc(n); }
void* operator new(size_t n, std::align_val_t a) { return memalign(size_t(a), n); }
void* operator new[](size_t n, std::align_val_t a) { return memalign(size_t(a), n); }
void operator delete(void* p) noexcept { free(p); }
void operator delete[](void* p) noexcept { free(p); }
void operator delete(void* p, size_t) noexcept { free(p); }
void operator delete[](void* p, size_t) noexcept { free(p); }
void operator delete(void* p, std::align_val_t) noexcept { free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { free(p); }
void operator delete(void* p, size_t, std::align_val_t) noexcept { free(p); }
void operator delete[](void* p, size_t, std::align_val_t) noexcept { free(p); }

namespace {

bool check(vg_status st, const char* what) {
    if (st != VG_OK) std::fprintf(stderr, "alloc_check: %s: %s\n", what, vg_status_string(st));
    return st == VG_OK;
}

// Opens `blob` with caller memory and runs every query kind; returns the allocation calls.
bool runAll(const std::vector<uint8_t>& blobBytes, const char* label) {
    std::vector<uint64_t> blob(blobBytes.size() / 8 + 1);  // 8-byte aligned copy, in place
    std::copy(blobBytes.begin(), blobBytes.end(), reinterpret_cast<uint8_t*>(blob.data()));
    std::vector<unsigned char> memory(64u << 20), wsMemory(64u << 20);
    std::vector<float> field(1u << 20);
    std::vector<uint32_t> labels(1u << 20);
    const uint32_t targets[4] = {3, 77, 555, 1200};
    bool ok = true;

    calls = 0;
    counting = true;
    size_t need = 0;
    const vg_graph* g = nullptr;
    vg_workspace* ws = nullptr;
    ok = ok && check(vg_open_size(blob.data(), blobBytes.size(), &need), "vg_open_size");
    ok = ok && need <= memory.size() && check(vg_open(blob.data(), blobBytes.size(), memory.data(), need, &g), "vg_open");
    const size_t wsBytes = ok ? vg_workspace_size(g) : 0;
    ok = ok && wsBytes <= wsMemory.size() && check(vg_workspace_init(g, wsMemory.data(), wsBytes, &ws), "workspace");
    float d = 0, sum = 0;
    size_t index = 0;
    // Both point-to-point searches; the directed one (the default) stays set afterwards.
    for (vg_search_mode mode : {VG_SEARCH_BIDIRECTIONAL, VG_SEARCH_DIRECTED}) {
        ok = ok && check(vg_workspace_set_search(ws, mode), "vg_workspace_set_search");
        for (uint32_t i = 0; ok && i < 200; ++i) {
            ok = check(vg_distance(g, ws, (i * 7919u) % vg_vertex_count(g), (i * 104729u) % vg_vertex_count(g), &d),
                       "vg_distance");
            sum += d;
        }
        ok = ok && check(vg_distance_within(g, ws, 1, 1500, 0.5f, &d), "vg_distance_within");
    }
    ok = ok && check(vg_distance_field(g, ws, targets, 4, field.data()), "vg_distance_field");
    ok = ok && check(vg_distance_field_nearest(g, ws, targets, 4, field.data(), labels.data()),
                     "vg_distance_field_nearest");
    ok = ok && check(vg_nearest(g, ws, 10, targets, 4, &index, &d), "vg_nearest");
    ok = ok && check(vg_distance_field_begin(g, ws, targets, 4, field.data(), labels.data()), "vg_distance_field_begin");
    for (int done = 0; ok && !done;) ok = check(vg_distance_field_step(g, ws, 64, &done), "vg_distance_field_step");
    // Two workspaces, the second in the upper half of the workspace buffer; its tasks in turn.
    vg_workspace* second = nullptr;
    ok = ok && 2 * wsBytes <= wsMemory.size() &&
         check(vg_workspace_init(g, wsMemory.data() + wsMemory.size() / 2, wsBytes, &second), "second workspace");
    vg_workspace* const both[2] = {ws, second};
    ok = ok && check(vg_distance_field_parallel(g, both, 2, targets, 4, field.data(), labels.data(), nullptr, nullptr),
                     "vg_distance_field_parallel");
    // Surface points (points declared before counting started: nothing here may allocate).
    const uint32_t F = ok ? vg_face_count(g) : 0;
    vg_point pts[4];
    for (uint32_t i = 0; i < 4; ++i) pts[i] = vg_point{(i * 2654435761u) % (F ? F : 1), {0.2f, 0.3f, 0.5f}};
    ok = ok && F > 0 && check(vg_point_distance(g, ws, &pts[0], &pts[1], &d), "vg_point_distance");
    ok = ok && check(vg_point_distance_within(g, ws, &pts[1], &pts[2], 0.5f, &d), "vg_point_distance_within");
    ok = ok && check(vg_point_distance_field(g, ws, pts, 2, field.data(), labels.data()), "vg_point_distance_field");
    ok = ok && check(vg_point_nearest(g, ws, &pts[0], pts + 1, 3, &index, &d), "vg_point_nearest");
    size_t kIndex[2], found = 0;
    float kDist[2];
    ok = ok && check(vg_point_k_nearest(g, ws, &pts[3], pts, 3, 2, kIndex, kDist, &found), "vg_point_k_nearest");
    vg_path_point path[256];
    size_t pathCount = 0;
    ok = ok && check(vg_path(g, ws, &pts[0], &pts[2], nullptr, 0, &pathCount, &d), "vg_path (size query)");
    const vg_status pathStatus = vg_path(g, ws, &pts[0], &pts[2], path, 256, &pathCount, &d);
    ok = ok && (pathStatus == VG_OK || pathStatus == VG_ERR_BUFFER_TOO_SMALL || check(pathStatus, "vg_path"));
    ok = ok && check(vg_vertex_point(g, 5, &pts[0]), "vg_vertex_point");
    vg_status_string(VG_ERR_CHECKSUM);
    vg_version_string();
    counting = false;

    std::printf("%s: %llu allocation calls while opening and answering %s (checksum of answers %.6f)\n", label,
                calls, ok ? "every query kind" : "(stopped by an error)", double(sum));
    return ok && calls == 0;
}

}  // namespace

int main() {
    // The harness must see allocations, or a zero below would prove nothing.
    counting = true;
    calls = 0;
    delete new std::vector<int>(10);
    counting = false;
    if (calls < 2) {
        std::fprintf(stderr, "alloc_check: the replaced allocator did not count (%llu calls)\n", calls);
        return 1;
    }
    vorogeo::BakeOptions o;
    vorogeo::BakeReport report;
    const vorogeo::Mesh mesh = vorogeo::bumpyTorus(60, 30);
    const std::vector<uint8_t> compressed = vorogeo::bakeMesh(mesh, o, report, nullptr);
    o.compress = false;
    const std::vector<uint8_t> plain = vorogeo::bakeMesh(mesh, o, report, nullptr);
    const bool a = runAll(compressed, "compressed blob");
    const bool b = runAll(plain, "uncompressed blob (in place)");
    return a && b ? 0 : 1;
}
