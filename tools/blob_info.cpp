#include "blob_info.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "blob_reader.h"
#include "vorogeo_container.h"

namespace vorogeo::tools {

bool looksLikeBlob(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    return in.read(magic, 8) && std::memcmp(magic, VG_CONTAINER_MAGIC, 8) == 0;
}

int printBlobInfo(const std::string& path, bool json) {
    BlobContents blob;
    std::string error;
    if (!readBlobFile(path, blob, error, /*decode=*/false)) {  // what is printed is stored uncoded
        std::fprintf(stderr, "vorogeo info: %s\n", error.c_str());
        return 1;
    }
    const fb::Graph* g = blob.graph();
    auto size = [](const auto* v) { return v ? size_t(v->size()) : size_t(0); };
    size_t secondPruned = 0;
    if (g->node_flags())
        for (uint8_t f : *g->node_flags()) secondPruned += f & 1;
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    const size_t fileBytes = size_t(in.tellg());
    const uint32_t V = g->vertex_count();
    size_t hubs = 0;
    if (g->hub_tree())
        for (const auto* t : *g->hub_tree()) hubs += t->hub_count();
    const size_t tableBytes = 2 * (blob.hubColumns.size() + blob.hubInner.size());  // uint16 entries
    if (json) {
        std::printf("{\"blob\":\"%s\",\"format_version\":%u,\"compressed\":%s,\"coded_distances\":%s,\"bytes\":%zu,\"flatbuffer_bytes\":%zu,"
                    "\"bytes_per_vertex\":%.2f,\"vertices\":%u,\"nodes\":%zu,\"nodes_pruned_second\":%zu,"
                    "\"first_patches\":%zu,\"second_patches\":%zu,\"first_layer_node_slots\":%zu,"
                    "\"seed\":%llu,\"n1\":%u,\"n2\":%u,\"delta\":%g,\"margin_rings\":%u,\"bbox_diagonal\":%g,"
                    "\"label_table_bytes\":%zu,\"hubs\":%zu,\"hub_label_entries\":%zu,\"hub_inner_entries\":%zu,\"inner_rows_at_open\":%s,"
                    "\"hub_exit_list_entries\":%zu}\n",
                    path.c_str(), blob.formatVersion, blob.compressed ? "true" : "false", blob.coded ? "true" : "false",
                    fileBytes,
                    blob.flatbuffer.size(), V ? double(fileBytes) / V : 0.0, V, size(g->node_vertex()), secondPruned,
                    size(g->first_patches()), size(g->second_patches()), size(g->node_first()),
                    (unsigned long long)g->seed(), g->n1(), g->n2(), double(g->delta()), g->margin_rings(),
                    double(g->bbox_diagonal()), tableBytes, hubs,
                    size_t(g->hub_columns_count()), size_t(g->hub_inner_count()),
                    blob.innerRowsAtOpen ? "true" : "false", size(g->hub_exit_lists()));
        return 0;
    }
    std::printf("%s: vorogeo blob, format version %u, %s, %zu bytes (%.1f per vertex; flatbuffer %zu bytes%s)\n",
                path.c_str(), blob.formatVersion,
                blob.compressed ? (blob.coded ? "zstd, prediction-coded distances" : "zstd") : "uncompressed", fileBytes,
                V ? double(fileBytes) / V : 0.0, blob.flatbuffer.size(),
                tableBytes ? (", label tables " + std::to_string(tableBytes) + " bytes").c_str() : "");
    std::printf("  vertices        %u\n", V);
    std::printf("  patches         %zu first layer, %zu second layer\n", size(g->first_patches()),
                size(g->second_patches()));
    std::printf("  graph nodes     %zu (%zu merged away in the second layer; %zu first-layer slots)\n",
                size(g->node_vertex()), secondPruned, size(g->node_first()));
    std::printf("  baked with      seed %llu, n1 %s, n2 %s, delta %g, margin rings %u\n", (unsigned long long)g->seed(),
                g->n1() ? std::to_string(g->n1()).c_str() : "auto", g->n2() ? std::to_string(g->n2()).c_str() : "auto",
                double(g->delta()), g->margin_rings());
    if (hubs > 0) {
        std::printf("  hub labels      %zu hubs, %zu tree nodes, %zu label entries (blocks padded to 16), %zu inner entries%s\n",
                    hubs, size(g->hub_tree()), size_t(g->hub_columns_count()), size_t(g->hub_inner_count()),
                    blob.innerRowsAtOpen ? " (computed at open)" : "");
        if (g->hub_exit_lists())
            std::printf("  exit lists      %zu entries in %zu lists (%.1f per list)\n", size(g->hub_exit_lists()),
                        size(g->hub_exit_list_begin()) - 1,
                        double(size(g->hub_exit_lists())) / double(std::max<size_t>(1, size(g->hub_exit_list_begin()) - 1)));
        else
            std::printf("  exit lists      none (label queries read every exit's rows)\n");
    }
    else
        std::printf("  hub labels      none (point-to-point queries search)\n");
    return 0;
}

}  // namespace vorogeo::tools
