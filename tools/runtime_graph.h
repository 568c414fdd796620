// The runtime as the tools and tests use it: a blob file read into memory, opened with
// caller memory, and per-thread workspaces. Owns every byte the runtime is given.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vorogeo.h"

namespace vorogeo::tools {

// Heap memory aligned to 16 bytes (vectors of bytes give no alignment promise).
struct AlignedBytes {
    std::unique_ptr<uint64_t[]> words;
    size_t size = 0;
    void resize(size_t n) {
        words.reset(new uint64_t[(n + 7) / 8 + 1]);
        size = n;
    }
    unsigned char* data() const { return reinterpret_cast<unsigned char*>(words.get()); }
};

class RuntimeGraph {
public:
    // Reads and opens a blob; false with a one-line reason.
    bool load(const std::string& path, std::string& error);
    bool open(const std::vector<uint8_t>& blob, std::string& error);

    const vg_graph* graph() const { return graph_; }
    uint32_t vertexCount() const { return vg_vertex_count(graph_); }
    size_t blobBytes() const { return blob_.size; }
    double openSeconds() const { return openSeconds_; }

private:
    AlignedBytes blob_, memory_;
    const vg_graph* graph_ = nullptr;
    double openSeconds_ = 0;
};

// The optional endpoint table of a graph with hub labels (vg_endpoint_table_build): owns
// its memory; empty (no table) for a graph without labels.
class EndpointTable {
public:
    explicit EndpointTable(const vg_graph* graph);
    const vg_endpoint_table* get() const { return table_; }
    size_t bytes() const { return memory_.size; }
    double buildSeconds() const { return buildSeconds_; }

private:
    AlignedBytes memory_;
    const vg_endpoint_table* table_ = nullptr;
    double buildSeconds_ = 0;
};

class RuntimeWorkspace {
public:
    explicit RuntimeWorkspace(const RuntimeGraph& g) : RuntimeWorkspace(g.graph()) {}
    explicit RuntimeWorkspace(const vg_graph* graph);
    vg_workspace* get() const { return ws_; }

    float distance(uint32_t s, uint32_t t) const;  // aborts the program on a status error
    void setSearch(vg_search_mode mode) const;      // the point-to-point search of later queries
    void useTable(const EndpointTable& table) const;  // its label queries read the table (if any)
    std::vector<float> field(const std::vector<uint32_t>& sources) const;
    // The same into `out` (resized to the vertex count): a timing loop reuses one buffer, as
    // an engine would, rather than timing the allocation and first touch of a new one.
    void field(const std::vector<uint32_t>& sources, std::vector<float>& out) const;

private:
    const vg_graph* graph_;
    AlignedBytes memory_;
    vg_workspace* ws_ = nullptr;
};

}  // namespace vorogeo::tools
