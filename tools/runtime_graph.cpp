#include "runtime_graph.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "timing.h"

namespace vorogeo::tools {

bool RuntimeGraph::load(const std::string& path, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open blob " + path;
        return false;
    }
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!open(bytes, error)) {
        error = path + ": " + error;
        return false;
    }
    return true;
}

bool RuntimeGraph::open(const std::vector<uint8_t>& blob, std::string& error) {
    graph_ = nullptr;
    blob_.resize(blob.size());
    if (!blob.empty()) std::memcpy(blob_.data(), blob.data(), blob.size());
    Stopwatch watch;
    size_t need = 0;
    vg_status st = vg_open_size(blob_.data(), blob_.size, &need);
    if (st == VG_OK) {
        memory_.resize(need);
        st = vg_open(blob_.data(), blob_.size, memory_.data(), need, &graph_);
    }
    openSeconds_ = watch.seconds();
    if (st != VG_OK) {
        error = vg_status_string(st);
        return false;
    }
    return true;
}

RuntimeWorkspace::RuntimeWorkspace(const vg_graph* graph) : graph_(graph) {
    const size_t n = vg_workspace_size(graph_);
    memory_.resize(n);
    if (vg_workspace_init(graph_, memory_.data(), n, &ws_) != VG_OK) {
        std::fprintf(stderr, "vorogeo: cannot create a runtime workspace\n");
        std::abort();
    }
}

EndpointTable::EndpointTable(const vg_graph* graph) {
    const size_t n = vg_endpoint_table_size(graph);
    if (n == 0) return;  // no hub labels: nothing to build
    memory_.resize(n);
    const auto start = std::chrono::steady_clock::now();
    const vg_status st = vg_endpoint_table_build(graph, memory_.data(), n, &table_);
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (st != VG_OK) {
        std::fprintf(stderr, "vorogeo: vg_endpoint_table_build: %s\n", vg_status_string(st));
        std::abort();
    }
}

void RuntimeWorkspace::useTable(const EndpointTable& table) const {
    const vg_status st = vg_workspace_use_endpoint_table(ws_, table.get());
    if (st != VG_OK) {
        std::fprintf(stderr, "vorogeo: vg_workspace_use_endpoint_table: %s\n", vg_status_string(st));
        std::abort();
    }
}

void RuntimeWorkspace::setSearch(vg_search_mode mode) const {
    const vg_status st = vg_workspace_set_search(ws_, mode);
    if (st != VG_OK) {
        std::fprintf(stderr, "vorogeo: vg_workspace_set_search(%d): %s\n", int(mode), vg_status_string(st));
        std::abort();
    }
}

float RuntimeWorkspace::distance(uint32_t s, uint32_t t) const {
    float d = 0;
    const vg_status st = vg_distance(graph_, ws_, s, t, &d);
    if (st != VG_OK) {
        std::fprintf(stderr, "vorogeo: vg_distance(%u, %u): %s\n", s, t, vg_status_string(st));
        std::abort();
    }
    return d;
}

std::vector<float> RuntimeWorkspace::field(const std::vector<uint32_t>& sources) const {
    std::vector<float> out;
    field(sources, out);
    return out;
}

void RuntimeWorkspace::field(const std::vector<uint32_t>& sources, std::vector<float>& out) const {
    out.resize(vg_vertex_count(graph_));
    const vg_status st = vg_distance_field(graph_, ws_, sources.data(), sources.size(), out.data());
    if (st != VG_OK) {
        std::fprintf(stderr, "vorogeo: vg_distance_field: %s\n", vg_status_string(st));
        std::abort();
    }
}

}  // namespace vorogeo::tools
