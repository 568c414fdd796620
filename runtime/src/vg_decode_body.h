// The decoder's body (vg_decode.cpp includes it twice: once as is, once compiled for
// AVX2 with VG_DECODE_BODY_AVX2 set, so that the AVX2 version runs start to end without
// switching between vector encodings, which costs more than the kernels on some CPUs).
// Not a header of its own: no include guard.

inline void predictRowPortable(const float* x, const float* y, const float* z, uint32_t i, uint32_t j0, uint32_t j1,
                        float scale, uint16_t* out) {
    const float a[3] = {x[i], y[i], z[i]};
    for (uint32_t j = j0; j < j1; ++j) {
        const float b[3] = {x[j], y[j], z[j]};
        out[j] = uint16_t(vg_predicted_quantum(a, b, scale));
    }
}

#if VG_DECODE_BODY_AVX2
// vg_predicted_quantum in eight lanes: the same operations in the same order; the minimum
// with 4094 first turns NaN into 4094 as the scalar comparison does. Whole vectors: it
// reads and writes up to seven entries past j1 (the scratch arrays' padding).
inline void predictRow(const float* x, const float* y, const float* z, uint32_t i, uint32_t j0, uint32_t j1, float scale,
                       uint16_t* out) {
    const __m256 ax = _mm256_set1_ps(x[i]), ay = _mm256_set1_ps(y[i]), az = _mm256_set1_ps(z[i]);
    const __m256 inverse = _mm256_set1_ps(1.0f / scale), top = _mm256_set1_ps(4094.0f), zero = _mm256_setzero_ps();
    const __m256 half = _mm256_set1_ps(0.5f);
    for (uint32_t j = j0; j < j1; j += 8) {
        const __m256 dx = _mm256_sub_ps(ax, _mm256_loadu_ps(x + j));
        const __m256 dy = _mm256_sub_ps(ay, _mm256_loadu_ps(y + j));
        const __m256 dz = _mm256_sub_ps(az, _mm256_loadu_ps(z + j));
        const __m256 sum = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
        __m256 q = _mm256_mul_ps(_mm256_sqrt_ps(sum), inverse);
        q = _mm256_max_ps(_mm256_min_ps(q, top), zero);
        const __m256i r = _mm256_cvttps_epi32(_mm256_add_ps(q, half));
        const __m128i packed = _mm_packus_epi32(_mm256_castsi256_si128(r), _mm256_extracti128_si256(r, 1));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + j), packed);
    }
}
#else
inline void predictRow(const float* x, const float* y, const float* z, uint32_t i, uint32_t j0, uint32_t j1, float scale,
                       uint16_t* out) {
    predictRowPortable(x, y, z, i, j0, j1, scale, out);
}
#endif

// Adds predictions[t] to the codes of entries k + t, t = 0 .. count - 1 (mod 4096): two
// entries (three bytes) at a time where the run is at an even entry.
inline void addRunPortable(uint8_t* packed, uint64_t k, const uint16_t* predictions, uint32_t count) {
    uint32_t t = 0;
    if (count > 0 && (k & 1u)) {
        vg_coding_apply(packed, k, predictions[0], 1);
        t = 1;
    }
    for (; t + 2 <= count; t += 2) {
        uint8_t* p = packed + ((3 * (k + t)) >> 1);
        const uint32_t word = uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16);
        const uint32_t a = (word + predictions[t]) & 0xFFFu;
        const uint32_t b = ((word >> 12) + predictions[t + 1]) & 0xFFFu;
        const uint32_t out = a | (b << 12);
        p[0] = uint8_t(out);
        p[1] = uint8_t(out >> 8);
        p[2] = uint8_t(out >> 16);
    }
    if (t < count) vg_coding_apply(packed, k + t, predictions[t], 1);
}

#if VG_DECODE_BODY_AVX2
// addRunPortable sixteen entries (24 bytes) at a time: unpacked into 16-bit lanes by one
// byte shuffle, summed, packed back by another; it reads 4 bytes past the 24 it writes,
// so the last stretch before `end` goes the portable way.
inline void addRun(uint8_t* packed, const uint8_t* end, uint64_t k, const uint16_t* predictions, uint32_t count) {
    uint32_t t = 0;
    if (count > 0 && (k & 1u)) {
        vg_coding_apply(packed, k, predictions[0], 1);
        t = 1;
    }
    const __m256i compact = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1,  //
                                             0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
    const __m256i together = _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 7, 7);
    Unpacker u = unpackerAt(packed, k + t);  // an even entry: pairs are whole 3-byte groups
    for (; t + 16 <= count; t += 16) {
        uint8_t* p = const_cast<uint8_t*>(u.p);
        if (end - p < 28) break;
        const __m256i sum = _mm256_and_si256(
            _mm256_add_epi16(unpackWords(u), _mm256_loadu_si256(reinterpret_cast<const __m256i*>(predictions + t))),
            _mm256_set1_epi16(0x0FFF));
        // a pair (even in the low, odd in the high half of a 32-bit lane) as its 24 bits
        const __m256i pair = _mm256_or_si256(_mm256_and_si256(sum, _mm256_set1_epi32(0xFFF)),
                                             _mm256_and_si256(_mm256_srli_epi32(sum, 4), _mm256_set1_epi32(0xFFF000)));
        const __m256i out = _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(pair, compact), together);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm256_castsi256_si128(out));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(p + 16), _mm256_extracti128_si256(out, 1));
    }
    addRunPortable(packed, k + t, predictions + t, count - t);
}
#else
inline void addRun(uint8_t* packed, const uint8_t*, uint64_t k, const uint16_t* predictions, uint32_t count) {
    addRunPortable(packed, k, predictions, count);
}
#endif

// The slots' positions, and zeros in the padding that whole vectors read past them.
inline void loadSlots(const vg_graph& g, const Patch& p, const Scratch& s) {
    const vg_coding_slots slots{g.positions, g.slots + p.slotBegin, g.nodeVertex, p.nodeCount};
    for (uint32_t i = 0; i < p.slotCount; ++i) {
        const float* q = vg_coding_position(&slots, i);
        s.x[i] = q[0];
        s.y[i] = q[1];
        s.z[i] = q[2];
    }
    for (uint32_t i = p.slotCount; i < p.slotCount + 8; ++i) s.x[i] = s.y[i] = s.z[i] = 0.0f;
}

// Entries [from, from + count) of a packed array into out.
inline void gatherRunPortable(const uint8_t* packed, uint64_t from, uint32_t count, uint16_t* out) {
    for (uint32_t c = 0; c < count; ++c) out[c] = uint16_t(vg_coding_get(packed, from + c));
}

#if VG_DECODE_BODY_AVX2
// A whole tile row at once where the bytes allow.
inline void gatherRun(const uint8_t* packed, const uint8_t* end, uint64_t from, uint32_t count, uint16_t* out) {
    Unpacker u = unpackerAt(packed, from);
    if (count != kTile || end - u.p < 28) return gatherRunPortable(packed, from, count, out);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), unpackWords(u));
}
#else
inline void gatherRun(const uint8_t* packed, const uint8_t*, uint64_t from, uint32_t count, uint16_t* out) {
    gatherRunPortable(packed, from, count, out);
}
#endif

// A square block (rows x rows from packed index `begin`) row by row: the lower half from
// its decoded mirrors, the diagonal from its convention, the upper half from predictions.
inline void decodeBlock(uint8_t* packed, const uint8_t* end, uint64_t begin, uint32_t rows, uint32_t diagonal,
                 const Scratch& s, float scale) {
    uint16_t* prediction = s.prediction;
    for (uint32_t i0 = 0; i0 < rows; i0 += kTile) {
        const uint32_t i1 = rows - i0 < kTile ? rows : i0 + kTile;
        // Rows above this tile of rows, in its columns: decoded already, read once each.
        const uint32_t above = i0 < kTileRows ? i0 : kTileRows;
        for (uint32_t j = 0; j < above; ++j)
            gatherRun(packed, end, begin + uint64_t(j) * rows + i0, i1 - i0, s.tile + j * kTile);
        for (uint32_t i = i0; i < i1; ++i) {
            const uint32_t c = i - i0;
            for (uint32_t j = 0; j < above; ++j) prediction[j] = s.tile[j * kTile + c];
            for (uint32_t j = above; j < i; ++j) prediction[j] = uint16_t(vg_coding_get(packed, begin + uint64_t(j) * rows + i));
            prediction[i] = uint16_t(diagonal);
            predictRow(s.x, s.y, s.z, i, i + 1, rows, scale, prediction);
            addRun(packed, end, begin + uint64_t(i) * rows, prediction, rows);
        }
    }
}

inline void decodeAll(const vg_graph& g, void* scratch) {
    // The arrays are the caller's memory (a decompressed or copied flatbuffer).
    uint8_t* second = const_cast<uint8_t*>(g.secondDistances);
    uint8_t* first = const_cast<uint8_t*>(g.firstDistances);
    // Their byte planes back to packed codes first, a chunk at a time through the scratch.
    vg_code_planes(second, vg_coding_entries(uint64_t(g.secondDistancesEnd - second)), static_cast<uint8_t*>(scratch), 1);
    vg_code_planes(first, vg_coding_entries(uint64_t(g.firstDistancesEnd - first)), static_cast<uint8_t*>(scratch), 1);
    const Scratch s = carve(scratch);
    for (uint32_t pi = 0; pi < g.secondCount; ++pi) {
        const Patch& p = g.second[pi];
        const uint32_t S = p.slotCount, n = p.nodeCount;
        loadSlots(g, p, s);
        decodeBlock(second, g.secondDistancesEnd, p.matrixBegin, n, VG_CODING_NO_PATH, s, p.scale);
        uint64_t k = p.matrixBegin + uint64_t(n) * n;
        for (uint32_t i = 0; i < n; ++i, k += S - n) {
            predictRow(s.x, s.y, s.z, i, n, S, p.scale, s.prediction);
            addRun(second, g.secondDistancesEnd, k, s.prediction + n, S - n);
        }
        for (uint32_t i = n; i < S; ++i) {
            predictRow(s.x, s.y, s.z, i, i + 1, S, p.scale, s.prediction);
            addRun(second, g.secondDistancesEnd, k, s.prediction + i + 1, S - i - 1);
            k += S - i - 1;
        }
    }
    for (uint32_t pi = 0; pi < g.firstCount; ++pi) {
        const Patch& p = g.first[pi];
        loadSlots(g, p, s);
        decodeBlock(first, g.firstDistancesEnd, p.matrixBegin, p.slotCount, 0u, s, p.scale);
    }
}

