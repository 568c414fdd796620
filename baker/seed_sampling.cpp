#include "seed_sampling.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>

#include "mesh_stats.h"

namespace vorogeo {

VertexGraph::VertexGraph(const Mesh& mesh) {
    const uint32_t nv = mesh.vertexCount();
    // Every undirected edge once from each side: a half-edge gives tail -> head, and a
    // boundary half-edge (no twin) also head -> tail.
    offset.assign(nv + 1, 0);
    for (uint32_t h = 0; h < mesh.halfedgeCount(); ++h) {
        ++offset[mesh.tail(int32_t(h)) + 1];
        if (mesh.twin[h] < 0) ++offset[mesh.head(int32_t(h)) + 1];
    }
    for (uint32_t v = 0; v < nv; ++v) offset[v + 1] += offset[v];
    neighbor.resize(offset[nv]);
    length.resize(offset[nv]);
    std::vector<uint32_t> fill(offset.begin(), offset.end() - 1);
    auto add = [&](uint32_t a, uint32_t b) {
        neighbor[fill[a]] = b;
        length[fill[a]++] = distance(mesh.positions[a], mesh.positions[b]);
    };
    for (uint32_t h = 0; h < mesh.halfedgeCount(); ++h) {
        const uint32_t a = mesh.tail(int32_t(h)), b = mesh.head(int32_t(h));
        add(a, b);
        if (mesh.twin[h] < 0) add(b, a);
    }
}

uint32_t componentCount(const std::vector<uint32_t>& vertexComponent) {
    uint32_t n = 0;
    for (uint32_t c : vertexComponent)
        if (c != kNoComponent) n = std::max(n, c + 1);
    return n;
}

namespace {

std::vector<uint32_t> usedVertices(const Mesh& mesh) {
    std::vector<uint32_t> used;
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.vertexOut[v] >= 0) used.push_back(v);
    return used;
}

void checkCount(uint32_t count, uint32_t components, size_t used) {
    if (count < components || count > used)
        throw std::invalid_argument("seed count " + std::to_string(count) + " outside [" +
                                    std::to_string(components) + ", " + std::to_string(used) + "]");
}

}  // namespace

std::vector<uint32_t> farthestPointSeeds(const Mesh& mesh, const VertexGraph& graph, uint32_t count, Random& rng,
                                         bool mirrorBoundary) {
    const std::vector<uint32_t> used = usedVertices(mesh);
    checkCount(count, componentCount(vertexComponents(mesh)), used.size());
    const double inf = std::numeric_limits<double>::infinity();
    // Edge weights: length over the mean length of the edges at both ends.
    const uint32_t nv = graph.vertexCount();
    std::vector<double> meanEdge(nv, 0.0), weight(graph.length.size());
    for (uint32_t v = 0; v < nv; ++v) {
        double sum = 0;
        for (uint32_t i = graph.offset[v]; i < graph.offset[v + 1]; ++i) sum += graph.length[i];
        if (graph.offset[v + 1] > graph.offset[v]) meanEdge[v] = sum / double(graph.offset[v + 1] - graph.offset[v]);
    }
    for (uint32_t v = 0; v < nv; ++v)
        for (uint32_t i = graph.offset[v]; i < graph.offset[v + 1]; ++i) {
            const double scale = 0.5 * (meanEdge[v] + meanEdge[graph.neighbor[i]]);
            weight[i] = scale > 0 ? graph.length[i] / scale : 1.0;
        }
    using Item = std::pair<double, uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    // Pruned Dijkstra: only vertices whose distance drops are visited.
    auto spread = [&](std::vector<double>& dist) {
        while (!queue.empty()) {
            const auto [d, v] = queue.top();
            queue.pop();
            if (d > dist[v]) continue;
            for (uint32_t i = graph.offset[v]; i < graph.offset[v + 1]; ++i) {
                const double nd = d + weight[i];
                const uint32_t w = graph.neighbor[i];
                if (nd < dist[w]) {
                    dist[w] = nd;
                    queue.push({nd, w});
                }
            }
        }
    };
    std::vector<double> dist(mesh.vertexCount(), inf);  // to the nearest seed
    std::vector<double> wall(mesh.vertexCount(), inf);  // twice the distance to the boundary
    if (mirrorBoundary) {
        for (uint32_t v : used)
            if (mesh.boundaryVertex[v]) {
                wall[v] = 0.0;
                queue.push({0.0, v});
            }
        spread(wall);
        for (double& w : wall) w *= 2.0;
    }
    std::vector<uint32_t> seeds;
    while (seeds.size() < count) {
        // A component without a seed first: its vertex farthest from the boundary, or a
        // random vertex if it has no boundary. Then the vertex farthest from seeds and walls.
        uint32_t unreached = 0, unwalled = 0;
        for (uint32_t v : used)
            if (dist[v] == inf) ++unreached, unwalled += wall[v] == inf;
        uint32_t next = 0;
        double best = -1.0;
        if (unwalled > 0) {
            uint32_t pick = randomIndex(rng, unwalled);
            for (uint32_t v : used)
                if (dist[v] == inf && wall[v] == inf && pick-- == 0) {
                    next = v;
                    break;
                }
        } else {
            for (uint32_t v : used) {
                if (unreached > 0 && dist[v] < inf) continue;
                const double d = std::min(dist[v], wall[v]);
                if (d > best) best = d, next = v;
            }
        }
        seeds.push_back(next);
        dist[next] = 0.0;
        queue.push({0.0, next});
        spread(dist);
    }
    return seeds;
}

std::vector<uint32_t> randomSeeds(const Mesh& mesh, uint32_t count, Random& rng) {
    std::vector<uint32_t> used = usedVertices(mesh);
    const std::vector<uint32_t> comp = vertexComponents(mesh);
    const uint32_t components = componentCount(comp);
    checkCount(count, components, used.size());
    std::vector<std::vector<uint32_t>> byComponent(components);
    for (uint32_t v : used) byComponent[comp[v]].push_back(v);
    std::vector<uint32_t> seeds;
    std::vector<uint8_t> taken(mesh.vertexCount(), 0);
    for (const auto& vs : byComponent) {
        const uint32_t v = vs[randomIndex(rng, uint32_t(vs.size()))];
        seeds.push_back(v);
        taken[v] = 1;
    }
    std::vector<uint32_t> pool;
    for (uint32_t v : used)
        if (!taken[v]) pool.push_back(v);
    // Partial Fisher-Yates shuffle: the first draws of a uniform random permutation.
    for (uint32_t i = 0; seeds.size() < count; ++i) {
        const uint32_t j = i + randomIndex(rng, uint32_t(pool.size()) - i);
        std::swap(pool[i], pool[j]);
        seeds.push_back(pool[i]);
    }
    return seeds;
}

}  // namespace vorogeo
