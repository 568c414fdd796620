#include "graph_prune.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "geodesic_exact.h"

namespace vorogeo {

namespace {

struct Membership {
    uint32_t patch, row;
};

struct Candidate {
    double error;
    uint32_t u, v;  // mesh vertex ids, u < v
    bool operator>(const Candidate& o) const {
        if (error != o.error) return error > o.error;
        if (u != o.u) return u > o.u;
        return v > o.v;
    }
};

class LayerPruner {
public:
    LayerPruner(const Mesh& mesh, std::vector<PatchMatrix>& layer, std::vector<uint8_t>& inactive)
        : mesh_(mesh), layer_(layer), inactive_(inactive) {
        nodeIndex_.assign(mesh.vertexCount(), -1);
        for (uint32_t p = 0; p < layer.size(); ++p)
            for (uint32_t i = 0; i < layer[p].nodeCount; ++i) {
                const uint32_t v = layer[p].vertices[i];
                if (nodeIndex_[v] < 0) {
                    nodeIndex_[v] = int32_t(members_.size());
                    members_.emplace_back();
                    neighbours_.emplace_back();
                }
                members_[nodeIndex_[v]].push_back({p, i});
            }
        // Mesh edges between nodes, each once (from its lower vertex).
        for (const Tri& t : mesh.faces)
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = t[k], b = t[(k + 1) % 3];
                if (nodeIndex_[a] < 0 || nodeIndex_[b] < 0) continue;
                neighbours_[nodeIndex_[a]].push_back(b);
                neighbours_[nodeIndex_[b]].push_back(a);
            }
        for (auto& n : neighbours_) {
            std::sort(n.begin(), n.end());
            n.erase(std::unique(n.begin(), n.end()), n.end());
        }
    }

    size_t nodeCount() const { return members_.size(); }

    void run(double delta, PruneStats& stats) {
        for (uint32_t u = 0; u < mesh_.vertexCount(); ++u)
            if (nodeIndex_[u] >= 0)
                for (uint32_t v : neighbours_[nodeIndex_[u]])
                    if (u < v) push(u, v);
        while (!heap_.empty()) {
            const Candidate c = heap_.top();
            heap_.pop();
            if (c.error >= delta) break;
            if (inactive_[c.u] || inactive_[c.v]) continue;
            const double now = error(c.u, c.v);
            if (now > c.error) {  // rows changed since it was queued
                heap_.push({now, c.u, c.v});
                continue;
            }
            merge(c.u, c.v);
            ++stats.prunedNodes;
        }
    }

private:
    // Patches of both, in the same order, if the pair is eligible.
    bool eligible(uint32_t u, uint32_t v) const {
        const auto& a = members_[nodeIndex_[u]];
        const auto& b = members_[nodeIndex_[v]];
        if (a.size() > 2 || a.size() != b.size()) return false;
        for (size_t i = 0; i < a.size(); ++i)
            if (a[i].patch != b[i].patch) return false;
        return true;
    }

    double error(uint32_t u, uint32_t v) const {
        const auto& a = members_[nodeIndex_[u]];
        const auto& b = members_[nodeIndex_[v]];
        double sum = 0;
        size_t count = 0;
        for (size_t m = 0; m < a.size(); ++m) {
            const PatchMatrix& P = layer_[a[m].patch];
            for (uint32_t k = 0; k < P.nodeCount; ++k) {
                if (k == a[m].row || k == b[m].row || inactive_[P.vertices[k]]) continue;
                const double wu = P.at(a[m].row, k), wv = P.at(b[m].row, k);
                if (std::isinf(wu) || std::isinf(wv)) continue;
                sum += std::fabs(wu - wv);
                ++count;
            }
        }
        return count == 0 ? kInfinity : sum / double(count);
    }

    void push(uint32_t u, uint32_t v) {
        if (u > v) std::swap(u, v);
        if (inactive_[u] || inactive_[v] || !eligible(u, v)) return;
        const double e = error(u, v);
        if (std::isfinite(e)) heap_.push({e, u, v});
    }

    void merge(uint32_t u, uint32_t v) {
        const auto& a = members_[nodeIndex_[u]];
        const auto& b = members_[nodeIndex_[v]];
        for (size_t m = 0; m < a.size(); ++m) {
            PatchMatrix& P = layer_[a[m].patch];
            const uint32_t i = a[m].row, j = b[m].row;
            for (uint32_t k = 0; k < P.nodeCount; ++k) {
                if (k == i || k == j || inactive_[P.vertices[k]]) continue;
                const double wu = P.at(i, k), wv = P.at(j, k);
                const double mean = (std::isinf(wu) || std::isinf(wv)) ? kInfinity : 0.5 * (wu + wv);
                P.upper[i < k ? upperIndex(P.rows, i, k) : upperIndex(P.rows, k, i)] = mean;
            }
        }
        inactive_[v] = 1;
        std::vector<uint32_t>& nu = neighbours_[nodeIndex_[u]];
        for (uint32_t q : neighbours_[nodeIndex_[v]])
            if (q != u && !inactive_[q]) {
                nu.push_back(q);
                push(u, q);
            }
        std::sort(nu.begin(), nu.end());
        nu.erase(std::unique(nu.begin(), nu.end()), nu.end());
    }

    const Mesh& mesh_;
    std::vector<PatchMatrix>& layer_;
    std::vector<uint8_t>& inactive_;
    std::vector<int32_t> nodeIndex_;
    std::vector<std::vector<Membership>> members_;  // per node, sorted by patch
    std::vector<std::vector<uint32_t>> neighbours_;  // per node: adjacent node vertices
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>> heap_;
};

uint64_t layerEdges(const std::vector<PatchMatrix>& layer, const std::vector<uint8_t>& inactive) {
    uint64_t edges = 0;
    for (const PatchMatrix& P : layer) {
        uint64_t active = 0;
        for (uint32_t i = 0; i < P.nodeCount; ++i) active += inactive[P.vertices[i]] ? 0 : 1;
        edges += active * (active > 0 ? active - 1 : 0) / 2;
    }
    return edges;
}

// Drops merged-away nodes from node-only matrices.
void compactLayer(std::vector<PatchMatrix>& layer, const std::vector<uint8_t>& inactive) {
    for (PatchMatrix& P : layer) {
        std::vector<uint32_t> keep;
        for (uint32_t i = 0; i < P.nodeCount; ++i)
            if (!inactive[P.vertices[i]]) keep.push_back(i);
        if (keep.size() == P.nodeCount) continue;
        PatchMatrix out;
        out.nodeCount = out.rows = uint32_t(keep.size());
        for (uint32_t i : keep) out.vertices.push_back(P.vertices[i]);
        out.upper.resize(size_t(out.rows) * (out.rows > 0 ? out.rows - 1 : 0) / 2);
        for (uint32_t a = 0; a < out.rows; ++a)
            for (uint32_t b = a + 1; b < out.rows; ++b) out.upper[upperIndex(out.rows, a, b)] = P.at(keep[a], keep[b]);
        P = std::move(out);
    }
}

}  // namespace

PruneStats pruneLayer(const Mesh& mesh, std::vector<PatchMatrix>& layer, double delta, bool compact,
                      std::vector<uint8_t>& inactive) {
    inactive.assign(mesh.vertexCount(), 0);
    PruneStats stats;
    LayerPruner pruner(mesh, layer, inactive);
    stats.nodes = pruner.nodeCount();
    stats.edges = layerEdges(layer, inactive);
    if (delta > 0) pruner.run(delta, stats);
    stats.prunedEdges = stats.edges - layerEdges(layer, inactive);
    if (compact) compactLayer(layer, inactive);
    return stats;
}

}  // namespace vorogeo
