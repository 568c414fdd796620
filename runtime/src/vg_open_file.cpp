// vg_open_file / vg_close_file: the convenience path for hosts that just have a file. The
// file is mapped read-only; an uncompressed blob stays mapped and is used in place, a
// compressed one is decompressed into memory from the caller's allocator and unmapped.
// Without mmap (non-POSIX hosts) the file is read into allocator memory instead.
#include <stdio.h>

#include "vg_graph.h"

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#define VG_HAVE_MMAP 1
#else
#define VG_HAVE_MMAP 0
#endif

namespace {

// The file's bytes, mapped or read; `owned` is allocator memory to free afterwards.
struct FileBytes {
    const void* data = nullptr;
    size_t size = 0;
    void* mapping = nullptr;
    void* owned = nullptr;
};

vg_status readFile(const char* path, const vg_allocator& a, FileBytes& out) {
#if VG_HAVE_MMAP
    (void)a;
    const int fd = open(path, O_RDONLY);
    if (fd < 0) return VG_ERR_IO;
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return VG_ERR_IO;
    }
    out.size = size_t(st.st_size);
    if (out.size == 0) {  // mmap refuses empty files; an empty blob is just truncated
        close(fd);
        return VG_ERR_TRUNCATED;
    }
    void* m = mmap(nullptr, out.size, PROT_READ, MAP_PRIVATE, fd, 0);
    close(fd);
    if (m == MAP_FAILED) return VG_ERR_IO;
    out.mapping = m;
    out.data = m;
    return VG_OK;
#else
    FILE* f = fopen(path, "rb");
    if (!f) return VG_ERR_IO;
    if (fseek(f, 0, SEEK_END) != 0) {
        fclose(f);
        return VG_ERR_IO;
    }
    const long n = ftell(f);
    if (n <= 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return n == 0 ? VG_ERR_TRUNCATED : VG_ERR_IO;
    }
    out.owned = a.alloc(a.user, size_t(n));
    if (!out.owned) {
        fclose(f);
        return VG_ERR_OUT_OF_MEMORY;
    }
    const bool ok = fread(out.owned, 1, size_t(n), f) == size_t(n);
    fclose(f);
    if (!ok) {
        a.free(a.user, out.owned);
        out.owned = nullptr;
        return VG_ERR_IO;
    }
    out.data = out.owned;
    out.size = size_t(n);
    return VG_OK;
#endif
}

void release(const vg_allocator& a, FileBytes& bytes) {
#if VG_HAVE_MMAP
    if (bytes.mapping) munmap(bytes.mapping, bytes.size);
#endif
    if (bytes.owned) a.free(a.user, bytes.owned);
    bytes = FileBytes{};
}

}  // namespace

extern "C" vg_status vg_open_file(const char* path, const vg_allocator* allocator, const vg_graph** out_graph) {
    if (out_graph == nullptr) return VG_ERR_INVALID_ARGUMENT;
    *out_graph = nullptr;
    if (path == nullptr || allocator == nullptr || allocator->alloc == nullptr || allocator->free == nullptr)
        return VG_ERR_INVALID_ARGUMENT;
    const vg_allocator a = *allocator;
    FileBytes bytes;
    vg_status st = readFile(path, a, bytes);
    if (st != VG_OK) return st;

    size_t need = 0;
    st = vg_open_size(bytes.data, bytes.size, &need);
    if (st != VG_OK) {
        release(a, bytes);
        return st;
    }
    void* memory = a.alloc(a.user, need);
    if (!memory) {
        release(a, bytes);
        return VG_ERR_OUT_OF_MEMORY;
    }
    const vg_graph* graph = nullptr;
    st = vg_open(bytes.data, bytes.size, memory, need, &graph);
    if (st != VG_OK) {
        a.free(a.user, memory);
        release(a, bytes);
        return st;
    }
    // Keep the file bytes only while the graph points into them (uncompressed, in place).
    const unsigned char* fb = reinterpret_cast<const unsigned char*>(graph->positions);
    const unsigned char* lo = static_cast<const unsigned char*>(bytes.data);
    const bool inPlace = fb >= lo && fb < lo + bytes.size;
    vg_graph* g = const_cast<vg_graph*>(graph);
    g->fileAllocator = a;
    g->fileMemory = memory;
    if (inPlace) {
        g->fileMapping = bytes.mapping ? bytes.mapping : bytes.owned;
        g->fileMappingSize = bytes.mapping ? bytes.size : 0;
    } else {
        release(a, bytes);
    }
    *out_graph = graph;
    return VG_OK;
}

extern "C" void vg_close_file(const vg_graph* graph) {
    if (graph == nullptr || graph->fileMemory == nullptr) return;
    const vg_allocator a = graph->fileAllocator;
    void* memory = graph->fileMemory;
    void* mapping = graph->fileMapping;
    const size_t mappingSize = graph->fileMappingSize;
#if VG_HAVE_MMAP
    if (mapping) munmap(mapping, mappingSize);
#else
    if (mapping) a.free(a.user, mapping);
    (void)mappingSize;
#endif
    a.free(a.user, memory);
}
