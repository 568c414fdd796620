// Carving caller memory into arrays, one after another, each start aligned: the same calls
// measure the bytes needed (base null) and then hand out the arrays, so that a size query
// and the carving cannot disagree. Internal to the runtime.
#pragma once

#include <stddef.h>
#include <stdint.h>

namespace vg {

struct Layout {
    unsigned char* base;  // nullptr while only measuring
    size_t align;         // a power of two
    size_t used = 0;

    template <class T>
    T* take(uint64_t count) {
        used = (used + align - 1) & ~(align - 1);
        T* p = base ? reinterpret_cast<T*>(base + used) : nullptr;
        used += size_t(count * sizeof(T));
        return p;
    }
};

}  // namespace vg
