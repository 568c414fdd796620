// AVX2 unpacking of packed 12-bit entries (vg_graph.h), shared by the one-to-all kernels
// (vg_field_kernels.cpp) and the distance decoder (vg_decode.cpp). x86-64 with GCC or clang
// only; every function carries the avx2 target, so callers pick it at run time.
#pragma once

#include <immintrin.h>
#include <stdint.h>

#define VG_AVX2 __attribute__((target("avx2")))

namespace vg {

// Sixteen consecutive entries of a packed 12-bit array as sixteen 16-bit lanes. An entry starts at
// bit 12k: an even one in the low 12 bits of bytes (3k/2, +1), an odd one in the high 12
// bits of the two bytes it ends in. A byte shuffle puts each entry's two bytes in a
// 16-bit lane, one multiply lifts the lanes whose entry sits low by 4 bits, and one shift
// right by 4 leaves every entry. A run starting at an odd entry reads from the byte that
// holds its high half, with the lane patterns swapped, so blocks always start at the
// run's first entry (and the caller's arrays are accessed at the same offsets for every
// row, which lets the CPU forward one row's stores to the next row's loads).
struct Unpacker {
    __m256i pick, lift;
    const uint8_t* p;  // the next block's first byte
};

VG_AVX2 inline Unpacker unpackerAt(const uint8_t* packed, uint64_t k0) {
    Unpacker u;
    if (k0 & 1) {  // entry k0 lies in the high 12 bits of the bytes after 3 (k0 - 1) / 2
        u.pick = _mm256_setr_epi8(0, 1, 2, 3, 3, 4, 5, 6, 6, 7, 8, 9, 9, 10, 11, 12,  //
                                  0, 1, 2, 3, 3, 4, 5, 6, 6, 7, 8, 9, 9, 10, 11, 12);
        u.lift = _mm256_setr_epi16(1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16);
        u.p = packed + 3 * (k0 >> 1) + 1;
    } else {
        u.pick = _mm256_setr_epi8(0, 1, 1, 2, 3, 4, 4, 5, 6, 7, 7, 8, 9, 10, 10, 11,  //
                                  0, 1, 1, 2, 3, 4, 4, 5, 6, 7, 7, 8, 9, 10, 10, 11);
        u.lift = _mm256_setr_epi16(16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1);
        u.p = packed + 3 * (k0 >> 1);
    }
    return u;
}

// The next sixteen entries (reads 28 bytes from u.p), and on to the following sixteen.
VG_AVX2 inline __m256i unpackWords(Unpacker& u) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(u.p));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(u.p + 12));
    const __m256i bytes = _mm256_inserti128_si256(_mm256_castsi128_si256(a), b, 1);
    u.p += 24;
    return _mm256_srli_epi16(_mm256_mullo_epi16(_mm256_shuffle_epi8(bytes, u.pick), u.lift), 4);
}

}  // namespace vg
