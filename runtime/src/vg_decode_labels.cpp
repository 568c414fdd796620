// Prediction-coded hub-label tables decoded in place (vg_decode_labels.h).
#include "vg_decode_labels.h"

#if defined(__SSE2__)
#define VG_LABELS_SSE2 1
#include <emmintrin.h>
#else
#define VG_LABELS_SSE2 0
#endif

namespace vg {
namespace {

constexpr uint32_t kMaxColumns = 65536;  // vg_validate bounds a first-layer patch's slots by this
constexpr int32_t kMissing = INT32_MIN;

struct Scratch {
    float* x;           // the columns' positions
    float* y;
    float* z;
    int32_t* chord;     // the row's straight-line steps
    int32_t* detours;   // two rows: value - chord, kMissing for "no path"
    unsigned char* planes;
};

Scratch carve(void* memory) {
    float* f = static_cast<float*>(memory);
    int32_t* i = reinterpret_cast<int32_t*>(f + 3 * kMaxColumns);
    return Scratch{f, f + kMaxColumns, f + 2 * kMaxColumns, i, i + kMaxColumns,
                   reinterpret_cast<unsigned char*>(i + 3 * kMaxColumns)};
}

inline uint32_t deltaOf(uint32_t code) {
    const uint32_t half = code >> 1;
    return (code & 1u) ? 65534u - half : half;  // odd: 65535 - (code + 1) / 2
}

inline int32_t chordOf(float px, float py, float pz, float x, float y, float z, float inverse) {
    const float dx = px - x, dy = py - y, dz = pz - z;
    const float sum = (dx * dx + dy * dy) + dz * dz;
    float v = __builtin_sqrtf(sum) * inverse;
    v = v < 65534.0f ? v : 65534.0f;
    v = v > 0.0f ? v : 0.0f;
    return int32_t(v + 0.5f);
}

// The straight-line steps of row r against every column, as vg_label_chord computes them
// (the same operations in the same order, four at a time where SSE2 is there: its minimum
// and maximum pick like the ternaries, NaN included).
void chordRow(const vg_label_sites& s, uint32_t r, uint32_t cols, const Scratch& m) {
    const float* p = s.positions + 3 * uint64_t(s.node_vertex[s.row_nodes[r]]);
    const float px = p[0], py = p[1], pz = p[2], inverse = s.inverse_scale;
    uint32_t c = 0;
#if VG_LABELS_SSE2
    const __m128 vx = _mm_set1_ps(px), vy = _mm_set1_ps(py), vz = _mm_set1_ps(pz), vi = _mm_set1_ps(inverse);
    const __m128 top = _mm_set1_ps(65534.0f), zero = _mm_setzero_ps(), half = _mm_set1_ps(0.5f);
    for (; c + 4 <= cols; c += 4) {
        const __m128 dx = _mm_sub_ps(vx, _mm_loadu_ps(m.x + c));
        const __m128 dy = _mm_sub_ps(vy, _mm_loadu_ps(m.y + c));
        const __m128 dz = _mm_sub_ps(vz, _mm_loadu_ps(m.z + c));
        const __m128 sum = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
        __m128 v = _mm_mul_ps(_mm_sqrt_ps(sum), vi);
        v = _mm_max_ps(_mm_min_ps(v, top), zero);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(m.chord + c), _mm_cvttps_epi32(_mm_add_ps(v, half)));
    }
#endif
    for (; c < cols; ++c) m.chord[c] = chordOf(px, py, pz, m.x[c], m.y[c], m.z[c], inverse);
}

// vg_label_planes(..., 0): each chunk's low and high bytes back into 16-bit entries.
void joinPlanes(unsigned char* bytes, uint64_t count, unsigned char* scratch) {
    for (uint64_t begin = 0; begin < count; begin += VG_LABEL_CHUNK) {
        const uint32_t n = uint32_t(count - begin < VG_LABEL_CHUNK ? count - begin : VG_LABEL_CHUNK);
        unsigned char* chunk = bytes + 2 * begin;
        for (uint32_t i = 0; i < 2 * n; ++i) scratch[i] = chunk[i];
        const unsigned char* low = scratch;
        const unsigned char* high = scratch + n;
        uint32_t i = 0;
#if VG_LABELS_SSE2
        for (; i + 16 <= n; i += 16) {
            const __m128i l = _mm_loadu_si128(reinterpret_cast<const __m128i*>(low + i));
            const __m128i h = _mm_loadu_si128(reinterpret_cast<const __m128i*>(high + i));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(chunk + 2 * i), _mm_unpacklo_epi8(l, h));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(chunk + 2 * i + 16), _mm_unpackhi_epi8(l, h));
        }
#endif
        for (; i < n; ++i) {
            chunk[2 * i] = low[i];
            chunk[2 * i + 1] = high[i];
        }
    }
}

}  // namespace

size_t labelDecodeScratchSize() {
    return 3 * size_t(kMaxColumns) * sizeof(float) + 3 * size_t(kMaxColumns) * sizeof(int32_t) + 2 * VG_LABEL_CHUNK;
}

void decodeLabelTable(uint16_t* table, uint32_t rows, uint32_t cols, const vg_label_sites* sites, void* scratch) {
    const Scratch m = carve(scratch);
    if (sites)
        for (uint32_t c = 0; c < cols; ++c) {
            const float* p = sites->positions + 3 * uint64_t(sites->node_vertex[sites->col_nodes[c]]);
            m.x[c] = p[0];
            m.y[c] = p[1];
            m.z[c] = p[2];
        }
    else
        for (uint32_t c = 0; c < cols; ++c) m.chord[c] = 0;
    int32_t* above = m.detours;
    int32_t* here = m.detours + kMaxColumns;
    bool aboveWhole = true;  // no "no path" in the row above (row -1: detours 0)
    for (uint32_t c = 0; c < cols; ++c) above[c] = 0;
    for (uint32_t r = 0; r < rows; ++r) {
        uint16_t* row = table + uint64_t(r) * cols;
        if (sites) chordRow(*sites, r, cols, m);
        bool whole = aboveWhole;
        for (uint32_t c = 0; c < cols && whole; ++c) whole = row[c] != VG_LABEL_NO_PATH;
        if (whole) {
            // value = chord + above + (sum of the deltas so far), modulo 65535.
            uint32_t sum = 0;
            for (uint32_t c = 0; c < cols; ++c) {
                sum += deltaOf(row[c]);
                sum -= sum >= 65535u ? 65535u : 0u;
                // chord + above + sum is in (-65535, 3 * 65535)
                const uint32_t v = uint32_t(m.chord[c] + above[c] + int32_t(sum) + 65535) % 65535u;
                row[c] = uint16_t(v);
                here[c] = int32_t(v) - m.chord[c];
            }
        } else {
            int32_t left = kMissing;
            for (uint32_t c = 0; c < cols; ++c) {
                const int32_t a = r ? above[c] : kMissing;
                const int32_t al = r && c ? above[c - 1] : kMissing;
                const uint32_t value = vg_label_decode(row[c], m.chord[c] + vg_label_predict_detour(a, left, al));
                row[c] = uint16_t(value);
                left = value == VG_LABEL_NO_PATH ? kMissing : int32_t(value) - m.chord[c];
                here[c] = left;
            }
            whole = true;
            for (uint32_t c = 0; c < cols && whole; ++c) whole = here[c] != kMissing;
        }
        aboveWhole = whole;
        int32_t* t = above;
        above = here;
        here = t;
    }
}

void decodeLabels(const vg_graph& g, bool inner, void* scratch) {
    if (g.hubTreeCount == 0) return;
    const Scratch m = carve(scratch);
    uint16_t* columns = const_cast<uint16_t*>(g.hubColumns);
    joinPlanes(reinterpret_cast<unsigned char*>(columns), g.hubColumnBegin[g.hubTreeCount], m.planes);
    for (uint32_t t = 0; t < g.hubTreeCount; ++t) {
        const HubTreeNode& n = g.hubTree[t];
        const uint64_t rows = uint64_t(hubSubtreeEnd(g.hubTree, g.hubTreeCount, g.hubCount, t)) - n.hubBegin;
        const uint64_t blocks = hubBlocksOf(n);
        for (uint64_t k = 0; k < blocks; ++k)
            decodeLabelTable(columns + g.hubColumnBegin[t] + k * rows * kHubBlock, uint32_t(rows), kHubBlock, nullptr,
                             scratch);
    }
    if (!inner) return;
    uint16_t* table = const_cast<uint16_t*>(g.hubInner);
    joinPlanes(reinterpret_cast<unsigned char*>(table), g.hubInnerMatrixBegin[g.firstCount], m.planes);
    const float inverseScale = 1.0f / g.hubLabelScale;
    for (uint32_t p = 0; p < g.firstCount; ++p) {
        const Patch& patch = g.first[p];
        const uint32_t rowBegin = g.hubInnerBegin[p];
        const vg_label_sites sites{g.positions, g.nodeVertex, g.hubInnerNode + rowBegin, g.slots + patch.slotBegin,
                                   inverseScale};
        decodeLabelTable(table + g.hubInnerMatrixBegin[p], g.hubInnerBegin[p + 1] - rowBegin, patch.slotCount, &sites,
                         scratch);
    }
}

}  // namespace vg
