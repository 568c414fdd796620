// libFuzzer target: a blob is untrusted input. Opens the input with the runtime and, when
// it is accepted, runs every query kind on it, with vertex numbers and bounds taken from
// the input too. The first byte chooses how the rest is presented:
//   0: the whole blob as a file holds it (header, checksum, payload);
//   1: a payload (4 bytes little-endian: the flatbuffer's size, then the flatbuffer and
//      the label tables after it), sealed here in an uncompressed container with a matching
//      checksum, so that mutations reach the verifier and the meaning checks instead of the
//      checksum;
//   2: the same, zstd-compressed;
//   3: the same, zstd-compressed and flagged as prediction-coded (the runtime decodes the
//      distance arrays of whatever flatbuffer passes validation);
//   4: the same flagged as coded, uncompressed;
//   5: the same, zstd-compressed, coded and flagged as leaving the inner rows to vg_open
//      (the runtime computes them for whatever labelled flatbuffer passes validation).
// The tools' reader (tools/blob_reader.h, behind `vorogeo info`) reads every input too,
// and may accept a coded blob only if the runtime does.
// Nothing may crash, read out of bounds or trip UBSan; every status must be a known one.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "blob_reader.h"
#include "blob_writer.h"
#include "vorogeo.h"
#include "vorogeo_container.h"

namespace {

constexpr size_t kMaxOpenMemory = size_t(64) << 20;  // the harness's budget, not a runtime limit

void check(vg_status st) {
    if (st < VG_OK || st > VG_ERR_PATH_FAILED) std::abort();
}

// Reads little pieces of the input to steer the queries; zeros once it runs out.
struct Steer {
    const uint8_t* p;
    size_t n, at = 0;
    uint32_t u32() {
        uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v = (v << 8) | (at < n ? p[at++] : 0);
        return v;
    }
};

// A vertex number: mostly valid, sometimes just out of range or far beyond it.
uint32_t vertex(Steer& s, uint32_t V) {
    const uint32_t r = s.u32();
    if (r % 16 == 0) return V + r % 3;
    if (r % 16 == 1) return 0xFFFFFFFFu;
    return V ? r % V : r;
}

// A surface point: mostly valid, sometimes a face out of range or weights that are NaN,
// negative or off a sum of 1.
vg_point point(Steer& s, uint32_t F) {
    const uint32_t r = s.u32();
    vg_point p;
    p.face = r % 16 == 0 ? F + r % 3 : (F ? s.u32() % F : s.u32());
    const float a = float(s.u32() % 1001) / 1000.0f, b = float(s.u32() % 1001) / 1000.0f * (1.0f - a);
    p.bary[0] = a;
    p.bary[1] = b;
    p.bary[2] = 1.0f - a - b;
    if (r % 16 == 1) p.bary[r % 3] = NAN;
    if (r % 16 == 2) p.bary[0] -= 0.01f;
    return p;
}

float bound(Steer& s) {
    const float pick[] = {0.0f, 1e-6f, 0.5f, 1.0f, 10.0f, INFINITY, -1.0f, NAN};
    return pick[s.u32() % 8];
}

void queryEverything(const vg_graph* g, const uint8_t* data, size_t size) {
    const size_t wsBytes = vg_workspace_size(g);
    std::vector<unsigned char> wsMemory(wsBytes + 1);
    vg_workspace* ws = nullptr;
    // An odd address: the workspace accepts any alignment.
    if (vg_workspace_init(g, wsMemory.data() + 1, wsBytes, &ws) != VG_OK) std::abort();
    const uint32_t V = vg_vertex_count(g);
    Steer steer{data, size};
    float d = 0;
    for (int i = 0; i < 4; ++i) {
        const uint32_t a = vertex(steer, V), b = vertex(steer, V);
        // Both point-to-point searches, in turn (without reading the input, so that the
        // recorded findings still steer the queries they did).
        if (vg_workspace_set_search(ws, (i & 1) ? VG_SEARCH_DIRECTED : VG_SEARCH_BIDIRECTIONAL) != VG_OK) std::abort();
        check(vg_distance(g, ws, a, b, &d));
        check(vg_distance_within(g, ws, a, b, bound(steer), &d));
    }
    uint32_t set[5];
    for (uint32_t& v : set) v = vertex(steer, V);
    size_t index = 0;
    check(vg_nearest(g, ws, set[0], set + 1, 4, &index, &d));
    std::vector<float> field(V);
    std::vector<uint32_t> labels(V);
    check(vg_distance_field(g, ws, set, 2, field.data()));
    const vg_status whole = vg_distance_field_nearest(g, ws, set + 1, 4, field.data(), labels.data());
    check(whole);
    if (whole == VG_OK)
        for (uint32_t i = 0; i < V; ++i)
            if (std::isnan(field[i]) || field[i] < 0) std::abort();  // distances are never NaN or negative
    // Surface points: every query kind.
    const uint32_t F = vg_face_count(g);
    vg_point pts[6];
    for (vg_point& p : pts) p = point(steer, F);
    check(vg_point_distance(g, ws, &pts[0], &pts[1], &d));
    check(vg_point_distance_within(g, ws, &pts[1], &pts[2], bound(steer), &d));
    check(vg_point_nearest(g, ws, &pts[0], pts + 1, 5, &index, &d));
    size_t kIndex[3], found = 0;
    float kDist[3];
    check(vg_point_k_nearest(g, ws, &pts[0], pts + 1, 5, 3, kIndex, kDist, &found));
    std::vector<float> pointField(V);
    std::vector<uint32_t> pointLabels(V);
    const vg_status fieldStatus = vg_point_distance_field(g, ws, pts, 2, pointField.data(), pointLabels.data());
    check(fieldStatus);
    if (fieldStatus == VG_OK)
        for (uint32_t i = 0; i < V; ++i)
            if (std::isnan(pointField[i]) || pointField[i] < 0) std::abort();
    float xyz[3];
    check(vg_point_position(g, &pts[3], xyz));
    // Paths: size query, then a buffer that may be too small; every point inside the mesh.
    size_t count = 0;
    check(vg_path(g, ws, &pts[4], &pts[5], nullptr, 0, &count, &d));
    std::vector<vg_path_point> path(std::min<size_t>(count, 1 + steer.u32() % 4096));
    size_t written = 0;
    const vg_status pathStatus = vg_path(g, ws, &pts[4], &pts[5], path.data(), path.size(), &written, &d);
    check(pathStatus);
    if (pathStatus == VG_OK)
        for (size_t i = 0; i < written; ++i)
            if (path[i].point.face >= F) std::abort();
    vg_point at;
    check(vg_vertex_point(g, vertex(steer, V), &at));

    // The time-sliced query fails the same way, or gives the same bits.
    std::vector<float> sliced(V);
    std::vector<uint32_t> slicedLabels(V);
    if (vg_distance_field_begin(g, ws, set + 1, 4, sliced.data(), slicedLabels.data()) != whole) std::abort();
    if (whole != VG_OK) return;
    int done = 0;
    for (uint64_t calls = 0; !done; ++calls) {
        if (vg_distance_field_step(g, ws, 1 + steer.u32() % 64, &done) != VG_OK || calls > (uint64_t(1) << 32))
            std::abort();
    }
    if (V && (std::memcmp(sliced.data(), field.data(), V * sizeof(float)) != 0 || slicedLabels != labels)) std::abort();

    // On two workspaces (the second at another odd address), its tasks in turn or the
    // second first: the same bits again.
    std::vector<unsigned char> secondMemory(wsBytes + 3);
    vg_workspace* second = nullptr;
    if (vg_workspace_init(g, secondMemory.data() + 3, wsBytes, &second) != VG_OK) std::abort();
    vg_workspace* const both[2] = {ws, second};
    std::vector<float> parallel(V);
    std::vector<uint32_t> parallelLabels(V);
    const vg_parallel_for backwards = [](void*, uint32_t count, vg_task task, void* context) {
        for (uint32_t i = count; i-- > 0;) task(context, i);
    };
    const bool inTurn = steer.u32() % 2 == 0;
    if (vg_distance_field_parallel(g, both, 2, set + 1, 4, parallel.data(), parallelLabels.data(),
                                   inTurn ? nullptr : backwards, nullptr) != VG_OK)
        std::abort();
    if (V && (std::memcmp(parallel.data(), field.data(), V * sizeof(float)) != 0 || parallelLabels != labels))
        std::abort();
}

// A blob with hub labels: its endpoint table, built into memory at an odd address, then
// label queries that read it (pairs inside one first-layer patch meet through its node
// distances). Steered by its own reader, so that the queries above stay as recorded.
void queryWithTable(const vg_graph* g, const uint8_t* data, size_t size) {
    const size_t tableBytes = vg_endpoint_table_size(g);
    if (tableBytes == 0 || tableBytes > kMaxOpenMemory) return;
    std::vector<unsigned char> tableMemory(tableBytes + 1);
    const vg_endpoint_table* table = nullptr;
    const vg_status built = vg_endpoint_table_build(g, tableMemory.data() + 1, tableBytes, &table);
    check(built);
    if (built != VG_OK) {
        if (table != nullptr) std::abort();
        return;
    }
    const size_t wsBytes = vg_workspace_size(g);
    std::vector<unsigned char> wsMemory(wsBytes);
    vg_workspace* ws = nullptr;
    if (vg_workspace_init(g, wsMemory.data(), wsBytes, &ws) != VG_OK) std::abort();
    if (vg_workspace_use_endpoint_table(ws, table) != VG_OK) std::abort();
    const uint32_t V = vg_vertex_count(g);
    Steer steer{data, size};
    float d = 0, back = 0;
    for (int i = 0; i < 8; ++i) {
        const uint32_t a = vertex(steer, V), b = vertex(steer, V);
        const vg_status st = vg_distance(g, ws, a, b, &d);
        check(st);
        if (st == VG_OK && (std::isnan(d) || d < 0)) std::abort();
        check(vg_distance(g, ws, b, a, &back));
        check(vg_distance_within(g, ws, a, b, bound(steer), &d));
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const uint8_t mode = data[0] % 6;
    const size_t skip = mode == 0 ? 1 : 5;
    if (size < skip) return 0;
    std::vector<uint8_t> rest(data + skip, data + size);
    const uint32_t flags[6] = {0,
                               0,
                               VG_FLAG_ZSTD,
                               VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES,
                               VG_FLAG_CODED_DISTANCES,
                               VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES | VG_FLAG_INNER_ROWS_AT_OPEN};
    const uint64_t flatbufferSize = mode == 0 ? 0 : vg_load_le32(data + 1);
    std::vector<uint8_t> blob = mode == 0 ? rest : vorogeo::sealContainer(rest, flags[mode], 1, flatbufferSize);
    if (mode != 0 && rest.empty()) return 0;

    // 16-byte aligned copy, as a host's mapping or asset buffer would be.
    std::vector<uint64_t> words(blob.size() / 8 + 2);
    unsigned char* bytes = reinterpret_cast<unsigned char*>(words.data());
    if (!blob.empty()) std::memcpy(bytes, blob.data(), blob.size());
    size_t need = 0;
    check(vg_open_size(bytes, blob.size(), &need));
    if (need == 0 || need > kMaxOpenMemory) return 0;
    std::vector<unsigned char> memory(need);
    const vg_graph* g = nullptr;
    const vg_status st = vg_open(bytes, blob.size(), memory.data(), need, &g);
    check(st);
    {
        vorogeo::tools::BlobContents contents;
        std::string error;
        const bool read = vorogeo::tools::unpackBlob(blob, contents, error);
        if (read != error.empty()) std::abort();  // a reason exactly when refused
        if (read && contents.coded && st != VG_OK) std::abort();
    }
    if (st != VG_OK) {
        if (g != nullptr) std::abort();
        return 0;
    }
    queryEverything(g, data, size);
    queryWithTable(g, data, size);
    return 0;
}
