#include "patch_geodesics.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>


#include "geodesic_exact.h"
#include "geodesic_wavefront.h"
#include "parallel.h"

namespace vorogeo {

double PatchMatrix::at(uint32_t i, uint32_t j) const {
    if (i == j) return 0.0;
    if (i > j) std::swap(i, j);
    return upper[upperIndex(rows, i, j)];
}

namespace {

template <class F>
void forEachFaceAround(const Mesh& mesh, uint32_t v, F&& f) {
    const int32_t start = mesh.vertexOut[v];
    if (start < 0) return;
    int32_t h = start;
    do {
        f(uint32_t(Mesh::faceOf(h)));
        h = mesh.nextAroundVertex(h);
    } while (h >= 0 && h != start);
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Local order of one patch: vertices shared with another patch of the layer first.
void orderPatch(const Patch& patch, const std::vector<uint8_t>& sharing, PatchMatrix& out) {
    std::vector<uint32_t> all(patch.border);
    all.insert(all.end(), patch.interior.begin(), patch.interior.end());
    std::sort(all.begin(), all.end());
    out.vertices.clear();
    for (uint32_t v : all)
        if (sharing[v] >= 2) out.vertices.push_back(v);
    out.nodeCount = uint32_t(out.vertices.size());
    for (uint32_t v : all)
        if (sharing[v] < 2) out.vertices.push_back(v);
}

// A thread's scratch for the exact runs of a layer.
struct RunScratch {
    WavefrontWorkspace workspace;
    std::vector<double> dist;
    std::vector<WavefrontWorkspace::Target> targets;
};

// Progress over `total` jobs of a parallel loop: about 200 calls, never overlapping.
class JobProgress {
public:
    JobProgress(const StageProgress& progress, const char* stage, size_t total)
        : progress_(progress), stage_(stage), total_(total), step_(std::max<size_t>(1, total / 200)) {}
    void oneDone() {
        const size_t n = ++done_;
        if (progress_ && (n % step_ == 0 || n == total_)) {
            std::lock_guard<std::mutex> lock(mutex_);
            progress_(stage_, double(n) / double(total_));
        }
    }

private:
    const StageProgress& progress_;
    const char* stage_;
    size_t total_, step_;
    std::atomic<size_t> done_{0};
    std::mutex mutex_;
};

// The order in which a patch's rows run when each runs to the rows after it: by
// decreasing upper bound (the first layer) or distance (the second) from an end row a
// (the row farthest from row 0; ties: the lower row), a last. The rows left to the run of a row r are then no farther from a than r, so
// within twice r's distance to a, and the rows near a run small.
std::vector<uint32_t> boundedRunOrder(const PatchMatrix& upperBounds) {
    const uint32_t n = upperBounds.rows;
    uint32_t end = 0;
    for (uint32_t j = 1; j < n; ++j)
        if (upperBounds.at(0, j) > upperBounds.at(0, end)) end = j;
    std::vector<uint32_t> order(n);
    for (uint32_t j = 0; j < n; ++j) order[j] = j;
    std::stable_sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) {
        return upperBounds.at(end, x) > upperBounds.at(end, y);
    });
    return order;
}

// A run to `targets`, done again whole if a bound missed one (only by rounding; never
// seen): every target then has its exact distance.
void runToTargetsOrWhole(WavefrontWorkspace& workspace, const ExactGeodesic& geo, uint32_t source,
                         const std::vector<WavefrontWorkspace::Target>& targets, std::vector<double>& dist) {
    workspace.runToTargets(geo, source, targets, dist);
    for (const WavefrontWorkspace::Target& t : targets)
        if (dist[t.vertex] == kInfinity) {
            workspace.run(geo, {source}, dist);
            return;
        }
}

// Every pair of one patch's rows from runs bounded by the rows run before them (the second
// layer, where no bounds are known in advance). Row 0 and the row `a` farthest from it run
// whole; the others run by decreasing distance from a, each to the rows after it, so the
// rows left to a run lie within its own distance of a, near its source, and the run does
// only the work between them. A pair (s, t) of later rows is bounded by the triangle
// through a row p that ran before both, d(p, s) + d(p, t), both exact already: p in {0, a}
// and s's nearest earlier row (a neighbour on the level sets of a, so the bound's slack is
// about two of its edges).
void runRowsBounded(const ExactGeodesic& geo, PatchMatrix& m, RunScratch& scratch) {
    WavefrontWorkspace& workspace = scratch.workspace;
    std::vector<double>& dist = scratch.dist;
    std::vector<WavefrontWorkspace::Target>& targets = scratch.targets;
    const uint32_t n = m.rows;
    std::vector<uint32_t> local(n);
    for (uint32_t r = 0; r < n; ++r) local[r] = uint32_t(geo.localVertex(m.vertices[r]));
    auto set = [&](uint32_t i, uint32_t j, double d) { m.upper[upperIndex(n, std::min(i, j), std::max(i, j))] = d; };
    std::vector<uint8_t> done(n, 0);  // rows whose pairs with every row are known
    auto runWhole = [&](uint32_t r) {
        workspace.run(geo, {local[r]}, dist);
        for (uint32_t j = 0; j < n; ++j)
            if (j != r && !done[j]) set(r, j, dist[local[j]]);
        done[r] = 1;
    };
    runWhole(0);
    uint32_t a = 0;
    for (uint32_t j = 1; j < n; ++j)
        if (m.at(0, j) > m.at(0, a)) a = j;
    if (n > 2 && a != 0) runWhole(a);  // with two rows, row 0 gave the only pair
    // Rows 0 and a have every pair now: the exact distances order the rest as the first
    // layer's bounds order its rows.
    std::vector<uint32_t> order = boundedRunOrder(m);
    order.erase(std::remove_if(order.begin(), order.end(), [&](uint32_t r) { return done[r] != 0; }), order.end());
    for (size_t k = 0; k + 1 < order.size(); ++k) {
        const uint32_t s = order[k];
        uint32_t nearest = m.at(a, s) < m.at(0, s) ? a : 0;  // s's nearest row among those run before it
        double toNearest = m.at(nearest, s);
        for (size_t q = 0; q < k; ++q)
            if (m.at(order[q], s) < toNearest) nearest = order[q], toNearest = m.at(order[q], s);
        const double viaZero = m.at(0, s), viaA = m.at(a, s);
        targets.clear();
        for (size_t q = k + 1; q < order.size(); ++q) {
            const uint32_t t = order[q];
            const double bound = std::min({viaZero + m.at(0, t), viaA + m.at(a, t), toNearest + m.at(nearest, t)});
            targets.push_back({local[t], bound * (1.0 + 1e-6)});
        }
        runToTargetsOrWhole(workspace, geo, local[s], targets, dist);
        for (size_t q = k + 1; q < order.size(); ++q) set(s, order[q], dist[local[order[q]]]);
    }
}

// Exact rows of every patch: one wavefront run per row (but the last), each giving the
// pairs with the rows after it, each run going to those rows only. Without `upperBounds`
// (the second layer) each patch is one job, its rows bounded by the rows run before them
// (runRowsBounded). With them (the first layer: the composed overlay, whose node paths are
// surface paths inside the grown patch and so never shorter than the exact distances),
// every row is a job of its own: the rows run in boundedRunOrder, each run to its pairs'
// rows, each bounded by its pair's bound (times 1 + 1e-6; runToTargets drops the windows that
// cannot reach any of them within it): the pairs left to a run lie close to its source,
// and the run does only the work between them (igea: 72% of the windows of a run bounded
// by the largest bound, the same distances). A pair the bound missed (never seen) is
// computed again unbounded.
void computeLayer(const Mesh& mesh, const std::vector<Patch>& patches, const std::vector<uint32_t>& facePatch,
                  bool nodesOnly, const PatchGeodesicsOptions& options, const char* stage,
                  const StageProgress& progress, std::vector<PatchMatrix>& out, uint64_t& runs,
                  const std::vector<PatchMatrix>* upperBounds = nullptr) {
    const std::vector<uint8_t> sharing = patchesPerVertex(mesh, facePatch);
    out.assign(patches.size(), PatchMatrix());
    std::vector<std::unique_ptr<ExactGeodesic>> domains(patches.size());
    parallelFor(patches.size(), [&](size_t p) {
        PatchMatrix& m = out[p];
        orderPatch(patches[p], sharing, m);
        m.rows = nodesOnly ? m.nodeCount : uint32_t(m.vertices.size());
        m.upper.assign(size_t(m.rows) * (m.rows > 0 ? m.rows - 1 : 0) / 2, kInfinity);
        if (m.rows >= 2) domains[p] = std::make_unique<ExactGeodesic>(mesh, growFaces(mesh, patches[p].faces, options.marginRings), true);
    });

    PerThread<RunScratch> scratch;
    if (!upperBounds) {
        // One job per patch (its rows depend on each other), the largest first.
        std::vector<uint32_t> byRows;
        for (uint32_t p = 0; p < patches.size(); ++p)
            if (out[p].rows >= 2) byRows.push_back(p);
        std::stable_sort(byRows.begin(), byRows.end(), [&](uint32_t x, uint32_t y) { return out[x].rows > out[y].rows; });
        for (uint32_t p : byRows) runs += out[p].rows - 1;
        JobProgress tick(progress, stage, byRows.size());
        parallelFor(byRows.size(), [&](size_t k) {
            runRowsBounded(*domains[byRows[k]], out[byRows[k]], scratch.local());
            tick.oneDone();
        });
        return;
    }
    // Per patch, the rows in the order they run (position k gives the pairs with positions
    // after k).
    std::vector<std::vector<uint32_t>> order(patches.size());
    parallelFor(patches.size(), [&](size_t p) { order[p] = boundedRunOrder((*upperBounds)[p]); });
    struct Job {
        uint32_t patch, row;  // row: the position in order[patch]
    };
    std::vector<Job> jobs;
    for (uint32_t p = 0; p < patches.size(); ++p)
        for (uint32_t r = 0; r + 1 < out[p].rows; ++r) jobs.push_back({p, r});
    // Long rows first: better balance at the end of the parallel loop.
    std::stable_sort(jobs.begin(), jobs.end(), [&](const Job& a, const Job& b) {
        return out[a.patch].rows - a.row > out[b.patch].rows - b.row;
    });
    runs += jobs.size();
    JobProgress tick(progress, stage, jobs.size());
    parallelFor(jobs.size(), [&](size_t k) {
        const Job job = jobs[k];
        PatchMatrix& m = out[job.patch];
        const ExactGeodesic& geo = *domains[job.patch];
        RunScratch& s = scratch.local();
        const std::vector<uint32_t>& rows = order[job.patch];
        const uint32_t source = rows[job.row];
        const uint32_t sourceVertex = uint32_t(geo.localVertex(m.vertices[source]));
        s.targets.clear();
        for (uint32_t k = job.row + 1; k < m.rows; ++k)
            s.targets.push_back({uint32_t(geo.localVertex(m.vertices[rows[k]])),
                                 (*upperBounds)[job.patch].at(source, rows[k]) * (1.0 + 1e-6)});
        runToTargetsOrWhole(s.workspace, geo, sourceVertex, s.targets, s.dist);
        for (uint32_t k = job.row + 1; k < m.rows; ++k) {
            const uint32_t target = rows[k];
            m.upper[upperIndex(m.rows, std::min(source, target), std::max(source, target))] =
                s.dist[size_t(geo.localVertex(m.vertices[target]))];
        }
        tick.oneDone();
    });
}

// Dijkstra over a small weighted graph in CSR form, stopping once `targets` are settled.
struct LocalGraph {
    std::vector<uint32_t> offsets, adj;
    std::vector<double> weight;
};

struct DijkstraScratch {
    std::vector<double> dist;
    std::vector<std::pair<double, uint32_t>> heap;
    std::vector<uint8_t> settled, isTarget;
};

void localDijkstra(const LocalGraph& g, uint32_t source, const std::vector<uint32_t>& targets, DijkstraScratch& s) {
    const size_t n = g.offsets.size() - 1;
    std::vector<double>& dist = s.dist;
    std::vector<std::pair<double, uint32_t>>& heap = s.heap;
    std::vector<uint8_t>& settled = s.settled;
    dist.assign(n, kInfinity);
    settled.assign(n, 0);
    s.isTarget.assign(n, 0);
    size_t remaining = targets.size();
    for (uint32_t t : targets) s.isTarget[t] = 1;
    heap.clear();
    dist[source] = 0;
    heap.push_back({0.0, source});
    auto greater = [](const std::pair<double, uint32_t>& a, const std::pair<double, uint32_t>& b) { return a > b; };
    while (!heap.empty() && remaining > 0) {
        std::pop_heap(heap.begin(), heap.end(), greater);
        const auto [d, u] = heap.back();
        heap.pop_back();
        if (settled[u]) continue;
        settled[u] = 1;
        if (s.isTarget[u]) --remaining;
        for (uint32_t k = g.offsets[u]; k < g.offsets[u + 1]; ++k) {
            const uint32_t v = g.adj[k];
            const double nd = d + g.weight[k];
            if (nd < dist[v]) {
                dist[v] = nd;
                heap.push_back({nd, v});
                std::push_heap(heap.begin(), heap.end(), greater);
            }
        }
    }
}

}  // namespace

void composeFirstLayer(const Mesh& mesh, const Partition& partition, const std::vector<PatchMatrix>& second,
                       std::vector<PatchMatrix>& first, const StageProgress& progress) {
    const char* stage = "first-layer overlay";
    std::mutex progressMutex;
    size_t done = 0;
    if (progress) progress(stage, 0.0);
    const std::vector<uint8_t> sharing = patchesPerVertex(mesh, partition.faceFirst);
    std::vector<std::vector<uint32_t>> children(partition.first.size());
    for (uint32_t p = 0; p < partition.second.size(); ++p) children[partition.second[p].parent].push_back(p);
    first.assign(partition.first.size(), PatchMatrix());
    parallelFor(partition.first.size(), [&](size_t f) {
        PatchMatrix& m = first[f];
        orderPatch(partition.first[f], sharing, m);
        m.rows = m.nodeCount;
        m.upper.assign(size_t(m.rows) * (m.rows > 0 ? m.rows - 1 : 0) / 2, kInfinity);
        if (m.rows < 2) return;
        // Local ids for the second-layer nodes inside this first-layer patch.
        std::vector<uint32_t> nodes;
        for (uint32_t c : children[f]) nodes.insert(nodes.end(), second[c].vertices.begin(), second[c].vertices.begin() + second[c].nodeCount);
        std::sort(nodes.begin(), nodes.end());
        nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
        auto local = [&](uint32_t v) { return uint32_t(std::lower_bound(nodes.begin(), nodes.end(), v) - nodes.begin()); };
        LocalGraph g;
        g.offsets.assign(nodes.size() + 1, 0);
        for (uint32_t c : children[f]) {
            const PatchMatrix& s = second[c];
            for (uint32_t i = 0; i < s.nodeCount; ++i) g.offsets[local(s.vertices[i]) + 1] += s.nodeCount - 1;
        }
        for (size_t i = 0; i < nodes.size(); ++i) g.offsets[i + 1] += g.offsets[i];
        g.adj.resize(g.offsets.back());
        g.weight.resize(g.offsets.back());
        std::vector<uint32_t> fill(g.offsets.begin(), g.offsets.end() - 1);
        for (uint32_t c : children[f]) {
            const PatchMatrix& s = second[c];
            for (uint32_t i = 0; i < s.nodeCount; ++i) {
                const uint32_t a = local(s.vertices[i]);
                for (uint32_t j = 0; j < s.nodeCount; ++j) {
                    if (i == j) continue;
                    g.adj[fill[a]] = local(s.vertices[j]);
                    g.weight[fill[a]++] = s.at(i, j);
                }
            }
        }
        std::vector<uint32_t> rowLocal(m.rows);
        for (uint32_t i = 0; i < m.rows; ++i) rowLocal[i] = local(m.vertices[i]);
        DijkstraScratch scratch;
        std::vector<uint32_t> targets;
        for (uint32_t i = 0; i + 1 < m.rows; ++i) {
            targets.assign(rowLocal.begin() + i + 1, rowLocal.end());
            localDijkstra(g, rowLocal[i], targets, scratch);
            for (uint32_t j = i + 1; j < m.rows; ++j) m.upper[upperIndex(m.rows, i, j)] = scratch.dist[rowLocal[j]];
        }
        if (progress) {
            std::lock_guard<std::mutex> lock(progressMutex);
            progress(stage, double(++done) / double(first.size()));
        }
    });
}

std::vector<uint8_t> patchesPerVertex(const Mesh& mesh, const std::vector<uint32_t>& facePatch) {
    std::vector<uint8_t> count(mesh.vertexCount(), 0);
    std::vector<uint32_t> seen;
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        seen.clear();
        forEachFaceAround(mesh, v, [&](uint32_t f) { seen.push_back(facePatch[f]); });
        std::sort(seen.begin(), seen.end());
        count[v] = uint8_t(std::min<size_t>(255, std::unique(seen.begin(), seen.end()) - seen.begin()));
    }
    return count;
}

std::vector<uint32_t> growFaces(const Mesh& mesh, const std::vector<uint32_t>& faces, uint32_t rings) {
    std::vector<uint32_t> result(faces);
    std::sort(result.begin(), result.end());
    std::vector<uint32_t> verts;
    for (uint32_t r = 0; r < rings; ++r) {
        verts.clear();
        for (uint32_t f : result)
            for (uint32_t v : mesh.faces[f]) verts.push_back(v);
        std::sort(verts.begin(), verts.end());
        verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
        std::vector<uint32_t> grown(result);
        for (uint32_t v : verts) forEachFaceAround(mesh, v, [&](uint32_t f) { grown.push_back(f); });
        std::sort(grown.begin(), grown.end());
        grown.erase(std::unique(grown.begin(), grown.end()), grown.end());
        if (grown.size() == result.size()) break;
        result.swap(grown);
    }
    return result;
}

PatchGeodesics computePatchGeodesics(const Mesh& mesh, const Partition& partition,
                                     const PatchGeodesicsOptions& options, const StageProgress& progress) {
    PatchGeodesics result;
    auto t0 = std::chrono::steady_clock::now();
    computeLayer(mesh, partition.second, partition.faceSecond, false, options, "second-layer geodesics", progress,
                 result.second, result.stats.sourceRuns);
    result.stats.secondLayerSeconds = secondsSince(t0);
    t0 = std::chrono::steady_clock::now();
    if (options.firstLayer == PatchGeodesicsOptions::FirstLayer::Exact) {
        std::vector<PatchMatrix> composed;  // the bounds of the exact runs
        composeFirstLayer(mesh, partition, result.second, composed, progress);
        computeLayer(mesh, partition.first, partition.faceFirst, true, options, "first-layer geodesics", progress,
                     result.first, result.stats.sourceRuns, &composed);
    } else
        composeFirstLayer(mesh, partition, result.second, result.first, progress);
    result.stats.firstLayerSeconds = secondsSince(t0);
    for (const auto* layer : {&result.first, &result.second})
        for (const PatchMatrix& m : *layer) result.stats.storedDistances += m.upper.size();
    return result;
}

}  // namespace vorogeo
