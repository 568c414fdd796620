#include "vg_huge_pages.h"

#include <stdint.h>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace vg {

void adviseHugePages(void* memory, size_t size) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr uintptr_t kHugePage = uintptr_t(2) << 20;
    const uintptr_t begin = (reinterpret_cast<uintptr_t>(memory) + kHugePage - 1) & ~(kHugePage - 1);
    const uintptr_t end = (reinterpret_cast<uintptr_t>(memory) + size) & ~(kHugePage - 1);
    // Only pages wholly inside the caller's buffer: its neighbours are none of our business.
    if (memory != nullptr && begin < end && begin >= reinterpret_cast<uintptr_t>(memory))
        (void)madvise(reinterpret_cast<void*>(begin), size_t(end - begin), MADV_HUGEPAGE);
#else
    (void)memory;
    (void)size;
#endif
}

}  // namespace vg
