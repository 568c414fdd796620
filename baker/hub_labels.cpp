#include "hub_labels.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <utility>

#include "hub_exit_lists.h"
#include "hub_label_runs.h"
#include "hub_landmarks.h"
#include "parallel.h"
#include "quad_heap.h"
#include "vorogeo_distance_coding.h"
#include "vorogeo_inner_rows.h"
#include "vorogeo_generated.h"

namespace vorogeo {

namespace {

constexpr uint32_t kNo = UINT32_MAX;
constexpr uint32_t kNoPath = VG_CODING_NO_PATH;
// The largest label or inner entry takes this many steps, so that the runtime's 16-bit
// sums of a label and a distance inside a patch stay below 65535 ("no path"). A step is
// then about the quantum of the second-layer matrices the labels are summed from (12 bits
// per patch): finer steps only store rounding noise (igea, accurate+labels: 40,000 steps
// gave the same golden errors, 0.0157% / 0.466%, for 15.4 more bytes per vertex), coarser
// ones start to show (10,000: 0.0171% / 0.509%). BENCHMARKS.md, session 38.
constexpr double kLargestLabelStep = 20000.0;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The parts of the graph buffer the labels are made of.
struct View {
    const fb::Graph* g;
    uint32_t nodes, firstCount, secondCount;

    const fb::PatchRecord& first(uint32_t p) const { return *g->first_patches()->Get(p); }
    const fb::PatchRecord& second(uint32_t p) const { return *g->second_patches()->Get(p); }
    uint32_t slot(uint64_t k) const { return g->slots()->Get(uint32_t(k)); }
    bool active(uint32_t node) const { return (g->node_flags()->Get(node) & 1u) == 0; }
    uint32_t firstQuantum(uint64_t k) const { return vg_coding_get(g->first_distances()->data(), k); }
    uint32_t secondQuantum(uint64_t k) const { return vg_coding_get(g->second_distances()->data(), k); }
};

// Dijkstra over node ids, reused across runs by one thread. Nodes settle by distance, then
// node id (what a binary heap of (distance, node) pairs with lazy deletion gives, so the
// labels are those of such a heap bit for bit). Every label is valid at all times
// (the nodes a run touched are reset at the next begin), so relaxing an edge is one load
// and one comparison; a settled node is never lowered (lengths are not negative). The
// queue is an indexed 4-ary heap with one entry per node, lowered in place, instead of
// one entry per improvement.
struct Dijkstra {
    std::vector<double> dist;
    std::vector<uint32_t> via;
    std::vector<uint32_t> touched;
    QuadHeap queue;

    void begin(size_t n) {
        if (dist.size() != n) {
            dist.assign(n, kInf);
            via.assign(n, kNo);
            queue.reset(n);
            touched.clear();
        }
        for (uint32_t u : touched) {
            dist[u] = kInf;
            via[u] = kNo;
        }
        touched.clear();
        queue.clear();
    }
    bool before(uint32_t a, uint32_t b) const { return dist[a] < dist[b] || (dist[a] == dist[b] && a < b); }
    void offer(uint32_t u, double d, uint32_t from) {
        if (!(d < dist[u])) return;
        if (dist[u] == kInf) touched.push_back(u);
        dist[u] = d;
        via[u] = from;
        queue.push(u, [this](uint32_t a, uint32_t b) { return before(a, b); });
    }
    // The next node to settle, kNo when none is left.
    uint32_t next() {
        if (queue.empty()) return kNo;
        return queue.pop([this](uint32_t a, uint32_t b) { return before(a, b); });
    }
};

// Reorders one tree node's hubs (sorted by node id) into a chain along their separator:
// from the first, always on to the nearest hub not taken yet (ties: the lower node id), so
// that a block of consecutive hubs is a short piece of separator with small bounds.
void chainOrder(const View& v, std::vector<std::pair<uint32_t, uint32_t>>::iterator begin,
                std::vector<std::pair<uint32_t, uint32_t>>::iterator end) {
    const size_t n = size_t(end - begin);
    if (n < 3) return;
    std::vector<double> xyz(3 * n);
    for (size_t i = 0; i < n; ++i) {
        const uint32_t vertex = v.g->node_vertex()->Get(begin[ptrdiff_t(i)].second);
        for (uint32_t c = 0; c < 3; ++c) xyz[3 * i + c] = v.g->positions()->Get(3 * vertex + c);
    }
    std::vector<uint8_t> taken(n, 0);
    std::vector<size_t> order{0};
    order.reserve(n);
    taken[0] = 1;
    for (size_t at = 0; order.size() < n;) {
        size_t next = n;
        double nearest = kInf;
        for (size_t j = 0; j < n; ++j) {
            if (taken[j]) continue;
            const double dx = xyz[3 * j] - xyz[3 * at], dy = xyz[3 * j + 1] - xyz[3 * at + 1],
                         dz = xyz[3 * j + 2] - xyz[3 * at + 2];
            const double d = dx * dx + dy * dy + dz * dz;
            if (d < nearest) {  // strict: among equals the lower node id, which comes first
                nearest = d;
                next = j;
            }
        }
        taken[next] = 1;
        order.push_back(next);
        at = next;
    }
    std::vector<std::pair<uint32_t, uint32_t>> chained(n);
    for (size_t i = 0; i < n; ++i) chained[i] = begin[ptrdiff_t(order[i])];
    std::copy(chained.begin(), chained.end(), begin);
}

// HubLabels::blockBounds. The sphere's radius is widened past float rounding so that every
// hub of the block is inside it. The landmark intervals hold the hubs' values exactly as
// the runtime reads them (steps times the scale, in float), so they need no widening.
std::vector<float> blockBounds(const View& v, const std::vector<HubTreeNode>& tree, const std::vector<uint32_t>& hubNode,
                               const std::vector<uint16_t>& hubLandmarks) {
    const auto* landmarkScale = v.g->landmark_scale();
    const uint32_t K = landmarkScale ? landmarkScale->size() : 0;
    std::vector<float> bounds;
    auto position = [&](uint32_t h, uint32_t c) {
        return double(v.g->positions()->Get(3 * v.g->node_vertex()->Get(hubNode[h]) + c));
    };
    for (const HubTreeNode& t : tree)
        for (uint32_t b = 0; b < t.hubCount; b += kHubBlock) {
            const uint32_t first = t.hubBegin + b, end = t.hubBegin + std::min(t.hubCount, b + kHubBlock);
            double centre[3] = {0, 0, 0};
            for (uint32_t h = first; h < end; ++h)
                for (uint32_t c = 0; c < 3; ++c) centre[c] += position(h, c) / double(end - first);
            float fc[3];
            for (uint32_t c = 0; c < 3; ++c) fc[c] = float(centre[c]);
            double radius = 0;
            for (uint32_t h = first; h < end; ++h) {
                double r2 = 0;
                for (uint32_t c = 0; c < 3; ++c) r2 += (position(h, c) - double(fc[c])) * (position(h, c) - double(fc[c]));
                radius = std::max(radius, std::sqrt(r2));
            }
            bounds.insert(bounds.end(), {fc[0], fc[1], fc[2], float(radius * (1.0 + 1e-5) + 1e-30)});
            for (uint32_t k = 0; k < K; ++k) {
                float lo = std::numeric_limits<float>::infinity(), hi = -lo;
                for (uint32_t h = first; h < end; ++h) {
                    const uint16_t q = hubLandmarks[uint64_t(h) * K + k];
                    const float d = q == kHubUnreachable ? std::numeric_limits<float>::infinity()
                                                         : float(q) * landmarkScale->Get(k);
                    lo = std::min(lo, d);
                    hi = std::max(hi, d);
                }
                const bool bounded = std::isfinite(hi);
                bounds.push_back(bounded ? lo : -std::numeric_limits<float>::infinity());
                bounds.push_back(bounded ? hi : std::numeric_limits<float>::infinity());
            }
        }
    return bounds;
}

double centroidDistance(const std::vector<double>& c, uint32_t a, uint32_t b) {
    const double dx = c[3 * a] - c[3 * b], dy = c[3 * a + 1] - c[3 * b + 1], dz = c[3 * a + 2] - c[3 * b + 2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// The tree of patch sets: every set split in two by the smallest separator found (or
// into its connected parts, which need no hubs between them).
class TreeBuilder {
public:
    TreeBuilder(const View& v, HubLabels& out) : v_(v), out_(out) {
        const uint32_t F = v.firstCount;
        centroid_.assign(size_t(F) * 3, 0.0);
        patchNodes_.assign(F, {});
        for (uint32_t p = 0; p < F; ++p) {
            const fb::PatchRecord& r = v.first(p);
            for (uint32_t k = 0; k < r.slot_count(); ++k) patchNodes_[p].push_back(v.slot(r.slot_begin() + k));
            for (uint32_t n : patchNodes_[p]) {
                const uint32_t vertex = v.g->node_vertex()->Get(n);
                for (int c = 0; c < 3; ++c) centroid_[3 * p + c] += v.g->positions()->Get(3 * vertex + c);
            }
            for (int c = 0; c < 3; ++c) centroid_[3 * p + c] /= double(std::max<size_t>(1, patchNodes_[p].size()));
        }
        adjacency_.assign(F, {});
        const auto* begin = v.g->node_first_begin();
        for (uint32_t n = 0; n < v.nodes; ++n)
            for (uint32_t a = begin->Get(n); a < begin->Get(n + 1); ++a)
                for (uint32_t b = begin->Get(n); b < begin->Get(n + 1); ++b) {
                    const uint32_t p = v.g->node_first()->Get(a)->patch(), q = v.g->node_first()->Get(b)->patch();
                    if (p != q) adjacency_[p].push_back(q);
                }
        for (auto& list : adjacency_) {
            std::sort(list.begin(), list.end());
            list.erase(std::unique(list.begin(), list.end()), list.end());
        }
        inSet_.assign(F, 0);
        count_.assign(v.nodes, {0, 0});
        out_.firstLeaf.assign(F, kNo);
    }

    uint32_t build(std::vector<uint32_t> set, uint32_t parent) {
        const uint32_t id = uint32_t(out_.tree.size());
        out_.tree.push_back(HubTreeNode{parent, 0, 0, 0});
        depth_.push_back(parent == kNo ? 0 : depth_[parent] + 1);
        if (set.size() == 1) {
            out_.firstLeaf[set[0]] = id;
            return id;
        }
        std::vector<uint32_t> a, b;
        split(set, a, b);
        build(std::move(a), id);
        build(std::move(b), id);
        return id;
    }

    uint32_t lca(uint32_t a, uint32_t b) const {
        while (depth_[a] > depth_[b]) a = out_.tree[a].parent;
        while (depth_[b] > depth_[a]) b = out_.tree[b].parent;
        while (a != b) {
            a = out_.tree[a].parent;
            b = out_.tree[b].parent;
        }
        return a;
    }

private:
    // Distances from `source` over the patch adjacency inside the marked set.
    std::vector<double> distancesFrom(uint32_t source) {
        Dijkstra dj;
        dj.begin(v_.firstCount);
        dj.offer(source, 0.0, kNo);
        for (uint32_t u = dj.next(); u != kNo; u = dj.next())
            for (uint32_t w : adjacency_[u])
                if (inSet_[w]) dj.offer(w, dj.dist[u] + centroidDistance(centroid_, u, w), kNo);
        std::vector<double> d(v_.firstCount);
        for (uint32_t p = 0; p < v_.firstCount; ++p) d[p] = dj.dist[p];
        return d;
    }

    static uint32_t farthest(const std::vector<uint32_t>& set, const std::vector<double>& d) {
        uint32_t best = set[0];
        for (uint32_t p : set)
            if (d[p] > d[best]) best = p;
        return best;
    }

    // Nodes shared by the two sides if the first `cut` patches of `order` go to one side:
    // for every cut position in [lo, hi], by moving patches over one at a time.
    uint32_t bestCut(const std::vector<uint32_t>& order, size_t lo, size_t hi, size_t& at) {
        for (uint32_t p : order)
            for (uint32_t n : patchNodes_[p]) count_[n] = {0, 0};
        for (uint32_t p : order)
            for (uint32_t n : patchNodes_[p]) ++count_[n].second;
        uint32_t shared = 0, best = UINT32_MAX;
        for (size_t k = 0; k < hi; ++k) {
            for (uint32_t n : patchNodes_[order[k]]) {
                auto& c = count_[n];
                const bool before = c.first > 0 && c.second > 0;
                ++c.first;
                --c.second;
                const bool after = c.first > 0 && c.second > 0;
                shared += uint32_t(after) - uint32_t(before);
            }
            const size_t position = k + 1;
            // The smallest separator, and among equal ones the most even split.
            const size_t mid = order.size() / 2;
            auto offMid = [&](size_t x) { return x > mid ? x - mid : mid - x; };
            if (position >= lo && (shared < best || (shared == best && offMid(position) < offMid(at)))) {
                best = shared;
                at = position;
            }
        }
        return best;
    }

    // Two halves: the smallest separator (nodes shared across) over a few sweeps through
    // the set, each cut between 30% and 70% of its patches: along the two patches farthest
    // apart, and along the coordinate axes and diagonals.
    void split(const std::vector<uint32_t>& set, std::vector<uint32_t>& a, std::vector<uint32_t>& b) {
        for (uint32_t p : set) inSet_[p] = 1;
        const std::vector<double> d0 = distancesFrom(set[0]);
        bool connected = true;
        for (uint32_t p : set) connected &= std::isfinite(d0[p]);
        if (!connected) {  // its connected parts: the one of set[0], and the rest
            for (uint32_t p : set) (std::isfinite(d0[p]) ? a : b).push_back(p);
        } else {
            const uint32_t ea = farthest(set, d0);
            const std::vector<double> da = distancesFrom(ea);
            const std::vector<double> db = distancesFrom(farthest(set, da));
            std::vector<std::vector<double>> keys;
            std::vector<double> key(v_.firstCount, 0.0);
            for (uint32_t p : set) key[p] = da[p] - db[p];
            keys.push_back(key);
            const double directions[7][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
            for (const auto& dir : directions) {
                for (uint32_t p : set)
                    key[p] = dir[0] * centroid_[3 * p] + dir[1] * centroid_[3 * p + 1] + dir[2] * centroid_[3 * p + 2];
                keys.push_back(key);
            }
            const size_t n = set.size();
            const size_t lo = std::max<size_t>(1, (3 * n) / 10), hi = std::max(lo, std::min(n - 1, (7 * n + 9) / 10));
            uint32_t best = UINT32_MAX;
            std::vector<uint32_t> bestOrder;
            size_t bestAt = 0;
            for (const auto& k : keys) {
                std::vector<uint32_t> order(set);
                std::sort(order.begin(), order.end(), [&](uint32_t p, uint32_t q) { return k[p] != k[q] ? k[p] < k[q] : p < q; });
                size_t at = lo;
                const uint32_t cut = bestCut(order, lo, hi, at);
                if (cut < best) {
                    best = cut;
                    bestOrder = order;
                    bestAt = at;
                }
            }
            a.assign(bestOrder.begin(), bestOrder.begin() + bestAt);
            b.assign(bestOrder.begin() + bestAt, bestOrder.end());
            std::sort(a.begin(), a.end());
            std::sort(b.begin(), b.end());
        }
        for (uint32_t p : set) inSet_[p] = 0;
    }

    const View& v_;
    HubLabels& out_;
    std::vector<double> centroid_;
    std::vector<std::vector<uint32_t>> patchNodes_;  // per patch: its nodes (its slots)
    std::vector<std::vector<uint32_t>> adjacency_;
    std::vector<uint8_t> inSet_;
    std::vector<uint32_t> depth_;
    std::vector<std::pair<uint32_t, uint32_t>> count_;  // per node: its patches on each side
};

// The readers round inner rows they compute with the same function (vorogeo_inner_rows.h).
uint16_t steps(double d, float scale) { return vg_label_steps(d, scale); }

// The rows of first-layer patch f's inner matrix: the active nodes of its second-layer
// patches (`children`), sorted.
void innerNodesOf(const View& v, const std::vector<uint32_t>& children, std::vector<uint32_t>& nodes) {
    nodes.clear();
    for (uint32_t c : children) {
        const fb::PatchRecord& q = v.second(c);
        for (uint32_t j = 0; j < q.node_count(); ++j) {
            const uint32_t n = v.slot(q.slot_begin() + j);
            if (v.active(n)) nodes.push_back(n);
        }
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
}

// Inner rows of first-layer patch f (`nodes`: innerNodesOf its children): shortest
// distances inside f's second-layer node graph from each of f's first-layer nodes, as the
// runtime's search relaxes rows (active nodes only); with blockRuns a search per
// kHubBlock of them (hub_label_runs.h), else a Dijkstra each (the tests' reference, the
// same numbers). The runs go over local ids (f's active nodes in
// increasing id, so ties settle as with global ids) and f's second-layer node blocks
// unpacked once, in the order the graph lists each node's patches.
void innerRows(const View& v, uint32_t f, const std::vector<uint32_t>& children, const std::vector<uint32_t>& nodes,
               bool blockRuns, std::vector<float>& values) {
    const fb::PatchRecord& fr = v.first(f);
    const uint32_t K = fr.slot_count();
    values.assign(nodes.size() * K, std::numeric_limits<float>::infinity());
    auto localOf = [&](uint32_t n) {
        const auto it = std::lower_bound(nodes.begin(), nodes.end(), n);
        return it != nodes.end() && *it == n ? uint32_t(it - nodes.begin()) : kNo;
    };

    // Per child: its node slots' local ids (kNo: merged away) and its node x node quanta.
    struct Child {
        uint32_t slotBegin, nodeCount;
        uint64_t quantaBegin;
        double scale;
    };
    std::vector<Child> local(children.size());
    std::vector<uint32_t> slotLocal;
    std::vector<uint16_t> quanta;
    for (size_t c = 0; c < children.size(); ++c) {
        const fb::PatchRecord& q = v.second(children[c]);
        const uint32_t nq = q.node_count();
        local[c] = Child{uint32_t(slotLocal.size()), nq, quanta.size(), double(q.scale())};
        for (uint32_t j = 0; j < nq; ++j) slotLocal.push_back(localOf(v.slot(q.slot_begin() + j)));
        for (uint64_t k = 0; k < uint64_t(nq) * nq; ++k) quanta.push_back(uint16_t(v.secondQuantum(q.matrix_begin() + k)));
    }
    // Per node (local id, or a merged-away first-layer node): its (child, slot) rows.
    auto membershipsOf = [&](uint32_t n, std::vector<std::pair<uint32_t, uint32_t>>& out) {
        const auto* begin = v.g->node_second_begin();
        for (uint32_t m = begin->Get(n); m < begin->Get(n + 1); ++m) {
            const fb::Membership* ms = v.g->node_second()->Get(m);
            if (v.second(ms->patch()).parent() != f) continue;
            const size_t c = size_t(std::lower_bound(children.begin(), children.end(), ms->patch()) - children.begin());
            out.push_back({uint32_t(c), ms->slot()});
        }
    };
    std::vector<uint32_t> rowsBegin(nodes.size() + 1, 0);
    std::vector<std::pair<uint32_t, uint32_t>> rows;
    for (size_t r = 0; r < nodes.size(); ++r) {
        membershipsOf(nodes[r], rows);
        rowsBegin[r + 1] = uint32_t(rows.size());
    }

    if (blockRuns) {
        // A block of kHubBlock slots per search. A merged-away first-layer node is a node of
        // its own here, after the inner nodes: it has its rows but is no row's column, so it
        // only starts its lane.
        LabelOverlay o;
        o.noPath = kNoPath;
        o.quanta = std::move(quanta);
        for (const Child& q : local) {
            o.quantaBegin.push_back(q.quantaBegin);
            o.slotBegin.push_back(q.slotBegin);
            o.scale.push_back(q.scale);
        }
        o.quantaBegin.push_back(o.quanta.size());
        o.slotBegin.push_back(uint32_t(slotLocal.size()));
        o.slotNode = slotLocal;
        o.patchLeaf.assign(local.size(), 0);
        o.members = rows;
        o.memberBegin = rowsBegin;
        std::vector<uint32_t> sourceOf(K);
        for (uint32_t k = 0; k < K; ++k) {
            const uint32_t b = v.slot(fr.slot_begin() + k);
            if (v.active(b)) {
                sourceOf[k] = localOf(b);
                continue;
            }
            sourceOf[k] = uint32_t(o.memberBegin.size() - 1);
            membershipsOf(b, o.members);
            o.memberBegin.push_back(uint32_t(o.members.size()));
        }
        BlockRuns runs;
        for (uint32_t k = 0; k < K; k += kHubBlock) {
            const uint32_t count = std::min(kHubBlock, K - k);
            runs.run(o, sourceOf.data() + k, count, 0, 1);
            for (size_t r = 0; r < nodes.size(); ++r) {
                const double* d = runs.distances(uint32_t(r));
                for (uint32_t i = 0; i < count; ++i) values[r * K + k + i] = float(d[i]);
            }
        }
        return;
    }
    Dijkstra dj;
    auto relaxRow = [&](const std::pair<uint32_t, uint32_t>& row, double du) {
        const Child& q = local[row.first];
        const uint32_t i = row.second;
        const uint16_t* entries = quanta.data() + q.quantaBegin + uint64_t(i) * q.nodeCount;
        const uint32_t* to = slotLocal.data() + q.slotBegin;
        for (uint32_t j = 0; j < q.nodeCount; ++j) {
            if (j == i || entries[j] == kNoPath || to[j] == kNo) continue;
            dj.offer(to[j], du + double(entries[j]) * q.scale, kNo);
        }
    };
    std::vector<std::pair<uint32_t, uint32_t>> sourceRows;
    for (uint32_t k = 0; k < K; ++k) {
        const uint32_t b = v.slot(fr.slot_begin() + k);
        dj.begin(nodes.size());
        if (v.active(b)) {
            dj.offer(localOf(b), 0.0, kNo);
        } else {  // merged away: it enters through its rows, as an endpoint does
            sourceRows.clear();
            membershipsOf(b, sourceRows);
            for (const auto& row : sourceRows) relaxRow(row, 0.0);
        }
        for (uint32_t u = dj.next(); u != kNo; u = dj.next())
            for (uint32_t m = rowsBegin[u]; m < rowsBegin[u + 1]; ++m) relaxRow(rows[m], dj.dist[u]);
        for (size_t r = 0; r < nodes.size(); ++r) values[r * K + k] = float(dj.dist[r]);
    }
}

// The overlay for the block runs: the unpacked matrices, and the nodes of first-layer
// slots renumbered in slot order (overlayOf: graph node -> overlay node, kNo if none) with
// their memberships in the graph's order.
void buildLabelOverlay(const View& v, std::vector<uint64_t> quantaBegin, std::vector<uint16_t> quanta,
                       std::vector<double> patchScale, const std::vector<uint32_t>& slotNode,
                       const std::vector<uint32_t>& firstLeaf, LabelOverlay& o, std::vector<uint32_t>& overlayOf) {
    o.noPath = kNoPath;
    o.quantaBegin = std::move(quantaBegin);
    o.quanta = std::move(quanta);
    o.scale = std::move(patchScale);
    o.patchLeaf = firstLeaf;
    o.slotBegin.assign(size_t(v.firstCount) + 1, 0);
    for (uint32_t p = 0; p < v.firstCount; ++p) o.slotBegin[p + 1] = o.slotBegin[p] + v.first(p).slot_count();
    o.slotNode.assign(o.slotBegin.back(), kNo);
    std::vector<uint32_t> nodeOf;  // overlay node -> graph node
    for (uint32_t p = 0; p < v.firstCount; ++p) {
        const uint32_t begin = v.first(p).slot_begin();
        for (uint32_t j = 0; j < v.first(p).slot_count(); ++j) {
            const uint32_t n = slotNode[begin + j];
            if (overlayOf[n] == kNo) {
                overlayOf[n] = uint32_t(nodeOf.size());
                nodeOf.push_back(n);
            }
            o.slotNode[o.slotBegin[p] + j] = overlayOf[n];
        }
    }
    const auto* firstBegin = v.g->node_first_begin();
    o.memberBegin.assign(nodeOf.size() + 1, 0);
    o.members.clear();
    for (size_t k = 0; k < nodeOf.size(); ++k) {
        for (uint32_t m = firstBegin->Get(nodeOf[k]); m < firstBegin->Get(nodeOf[k] + 1); ++m) {
            const fb::Membership* ms = v.g->node_first()->Get(m);
            o.members.push_back({ms->patch(), ms->slot()});
        }
        o.memberBegin[k + 1] = uint32_t(o.members.size());
    }
}

}  // namespace

HubLabels computeHubLabels(const std::vector<uint8_t>& flatbuffer, const HubProgress& progress,
                           const HubPlanCheck& checkPlan, HubLabelRuns runs) {
    const auto start = std::chrono::steady_clock::now();
    HubLabels out;
    View v;
    v.g = fb::GetGraph(flatbuffer.data());
    v.nodes = v.g->node_vertex()->size();
    v.firstCount = v.g->first_patches()->size();
    v.secondCount = v.g->second_patches()->size();
    if (v.firstCount == 0) return out;

    // The tree, and every first-layer node's tree node: where its patches part ways.
    TreeBuilder builder(v, out);
    std::vector<uint32_t> all(v.firstCount);
    for (uint32_t p = 0; p < v.firstCount; ++p) all[p] = p;
    builder.build(all, kNo);
    const uint32_t T = uint32_t(out.tree.size());
    std::vector<std::pair<uint32_t, uint32_t>> hubs;  // (tree node, graph node)
    const auto* firstBegin = v.g->node_first_begin();
    for (uint32_t n = 0; n < v.nodes; ++n) {
        uint32_t t = kNo;
        for (uint32_t m = firstBegin->Get(n); m < firstBegin->Get(n + 1); ++m) {
            const uint32_t leaf = out.firstLeaf[v.g->node_first()->Get(m)->patch()];
            t = t == kNo ? leaf : builder.lca(t, leaf);
        }
        if (t != kNo) hubs.push_back({t, n});
    }
    std::sort(hubs.begin(), hubs.end());
    for (size_t b = 0, e = 0; b < hubs.size(); b = e) {
        for (e = b; e < hubs.size() && hubs[e].first == hubs[b].first; ++e) {}
        chainOrder(v, hubs.begin() + ptrdiff_t(b), hubs.begin() + ptrdiff_t(e));
    }
    const uint32_t H = uint32_t(hubs.size());
    out.nodeHub.assign(v.nodes, kNo);
    std::vector<uint32_t> hubTree(H), hubNode(H);
    for (uint32_t h = 0; h < H; ++h) {
        hubTree[h] = hubs[h].first;
        hubNode[h] = hubs[h].second;
        out.nodeHub[hubs[h].second] = h;
        ++out.tree[hubs[h].first].hubCount;
    }
    for (uint32_t t = 0, next = 0; t < T; ++t) {
        out.tree[t].hubBegin = next;
        next += out.tree[t].hubCount;
        const uint32_t p = out.tree[t].parent;
        out.tree[t].pathBegin = p == kNo ? 0 : out.tree[p].pathBegin + out.tree[p].hubCount;
    }
    // Preorder: a subtree is a range of tree nodes, and so of hubs.
    std::vector<uint32_t> subtreeEnd(T);
    for (uint32_t t = 0; t < T; ++t) subtreeEnd[t] = t + 1;
    for (uint32_t t = T; t-- > 1;) subtreeEnd[out.tree[t].parent] = std::max(subtreeEnd[out.tree[t].parent], subtreeEnd[t]);
    auto hubEnd = [&](uint32_t t) { return subtreeEnd[t] < T ? out.tree[subtreeEnd[t]].hubBegin : H; };
    out.hubCount = H;
    out.columnBegin.assign(T + 1, 0);
    for (uint32_t t = 0; t < T; ++t) {
        const uint64_t blocks = (out.tree[t].hubCount + kHubBlock - 1) / kHubBlock;
        out.columnBegin[t + 1] = out.columnBegin[t] + blocks * kHubBlock * (hubEnd(t) - out.tree[t].hubBegin);
    }

    // Inner rows, a first-layer patch per job.
    std::vector<std::vector<uint32_t>> children(v.firstCount), innerNodes(v.firstCount);
    for (uint32_t q = 0; q < v.secondCount; ++q) children[v.second(q).parent()].push_back(q);
    // Distances are kept as floats until their steps are known (a double each would take
    // igea x16's 1.4 billion entries to 11 GB); a float's rounding moves an entry by at
    // most 0.004 of a step before the step's own rounding.
    std::vector<std::vector<float>> innerValues(v.firstCount);
    std::atomic<size_t> done{0};
    std::mutex progressMutex;
    const size_t jobs = size_t(v.firstCount) + H;
    const size_t step = std::max<size_t>(1, jobs / 100);
    auto tick = [&](size_t count) {
        const size_t n = done += count;
        if (progress && (n / step != (n - count) / step || n == jobs)) {
            std::lock_guard<std::mutex> lock(progressMutex);
            progress(double(n) / double(jobs));
        }
    };
    parallelFor(v.firstCount, [&](size_t f) { innerNodesOf(v, children[f], innerNodes[f]); });
    // The tables' sizes are known now, before the long runs: the caller may refuse them.
    if (checkPlan) {
        HubLabelSizes sizes;
        sizes.labelEntries = out.columnBegin[T];
        for (uint32_t f = 0; f < v.firstCount; ++f) {
            sizes.innerNodes += innerNodes[f].size();
            sizes.innerEntries += uint64_t(innerNodes[f].size()) * v.first(f).slot_count();
        }
        checkPlan(sizes);
    }
    parallelFor(v.firstCount, [&](size_t f) {
        innerRows(v, uint32_t(f), children[f], innerNodes[f], runs == HubLabelRuns::blocks, innerValues[f]);
        tick(1);
    });

    // The overlay graph once: every first-layer matrix unpacked (quanta, kNoPath kept), its
    // slots' node ids, and every node's memberships, for the label runs below.
    std::vector<uint64_t> quantaBegin(size_t(v.firstCount) + 1, 0);
    for (uint32_t p = 0; p < v.firstCount; ++p)
        quantaBegin[p + 1] = quantaBegin[p] + uint64_t(v.first(p).slot_count()) * v.first(p).slot_count();
    std::vector<uint16_t> quanta(quantaBegin.back());
    std::vector<uint32_t> slotNode(v.g->slots()->size());
    std::vector<double> patchScale(v.firstCount);
    parallelFor(v.firstCount, [&](size_t p) {
        const fb::PatchRecord& r = v.first(uint32_t(p));
        const uint64_t S = r.slot_count();
        for (uint64_t k = 0; k < S * S; ++k) quanta[quantaBegin[p] + k] = uint16_t(v.firstQuantum(r.matrix_begin() + k));
        for (uint64_t j = 0; j < S; ++j) slotNode[r.slot_begin() + j] = v.slot(r.slot_begin() + j);
        patchScale[p] = double(r.scale());
    });
    out.landmarks = hubLandmarkSteps(*v.g, FirstLayerOverlay{quantaBegin, quanta, patchScale, slotNode, kNoPath}, hubNode);
    out.blockBounds = blockBounds(v, out.tree, hubNode, out.landmarks);

    // Labels over the first-layer patches of each tree node's subtree (hub_labels.h: why no
    // path outside is needed; a subtree is a range of tree nodes, so a patch is inside when
    // its leaf is in that range): a block of hubs per search (hub_label_runs.h).
    // Per tree node, so that each is freed once it is in steps.
    std::vector<std::vector<float>> labelValue(T);
    for (uint32_t t = 0; t < T; ++t)
        labelValue[t].assign(out.columnBegin[t + 1] - out.columnBegin[t], std::numeric_limits<float>::infinity());
    if (runs == HubLabelRuns::blocks) {
        LabelOverlay overlay;
        std::vector<uint32_t> overlayOf(v.nodes, kNo);
        // (the unpacked matrices move into it: only the per-hub references read them too)
        buildLabelOverlay(v, std::move(quantaBegin), std::move(quanta), std::move(patchScale), slotNode, out.firstLeaf,
                          overlay, overlayOf);
        // Closed matrices let the runs skip half of their rows (hub_label_runs.h).
        overlay.closed.assign(v.firstCount, 0);
        parallelFor(v.firstCount, [&](size_t p) { closePatchMatrix(overlay, uint32_t(p)); });
        std::vector<std::pair<uint32_t, uint32_t>> blocks;  // (tree node, block)
        for (uint32_t t = 0; t < T; ++t)
            for (uint32_t b = 0; b * kHubBlock < out.tree[t].hubCount; ++b) blocks.push_back({t, b});
        PerThread<BlockRuns> blockScratch;
        parallelFor(blocks.size(), [&](size_t k) {
            BlockRuns& runs = blockScratch.local();
            const uint32_t t = blocks[k].first, first = out.tree[t].hubBegin + blocks[k].second * kHubBlock;
            const uint32_t count = std::min(kHubBlock, out.tree[t].hubBegin + out.tree[t].hubCount - first);
            uint32_t sources[kHubBlock];
            for (uint32_t i = 0; i < count; ++i) sources[i] = overlayOf[hubNode[first + i]];
            runs.run(overlay, sources, count, t, subtreeEnd[t]);
            // The block's matrix: a row of kHubBlock lanes per hub of the subtree.
            const uint32_t targetsBegin = out.tree[t].hubBegin, targetsEnd = hubEnd(t);
            float* matrix = labelValue[t].data() + uint64_t(blocks[k].second) * kHubBlock * (targetsEnd - targetsBegin);
            for (uint32_t r = targetsBegin; r < targetsEnd; ++r) {
                const double* d = runs.distances(overlayOf[hubNode[r]]);
                for (uint32_t i = 0; i < count; ++i) matrix[uint64_t(r - targetsBegin) * kHubBlock + i] = float(d[i]);
            }
            tick(count);
        });
    } else {
        // The references: one Dijkstra per hub x, over its subtree or the whole overlay,
        // stopped once every hub whose label holds x (the hubs of x's subtree) is settled.
        const bool wholeOverlay = runs == HubLabelRuns::perHubWholeOverlay;
        PerThread<Dijkstra> scratch;
        parallelFor(H, [&](size_t x) {
            Dijkstra& dj = scratch.local();
            const uint32_t t = hubTree[x];
            const uint32_t targetsBegin = out.tree[t].hubBegin, targetsEnd = hubEnd(t);
            // x's column: lane x % 16 of its block's matrix, one row per hub of the subtree.
            const uint32_t local = uint32_t(x) - targetsBegin;
            const uint64_t column =
                uint64_t(local / kHubBlock) * kHubBlock * (targetsEnd - targetsBegin) + local % kHubBlock;
            uint32_t remaining = targetsEnd - targetsBegin;
            dj.begin(v.nodes);
            dj.offer(hubNode[x], 0.0, kNo);
            for (uint32_t u = dj.next(); u != kNo; u = dj.next()) {
                const uint32_t hu = out.nodeHub[u];
                if (hu != kNo && hu >= targetsBegin && hu < targetsEnd && --remaining == 0) break;
                for (uint32_t m = firstBegin->Get(u); m < firstBegin->Get(u + 1); ++m) {
                    const fb::Membership* ms = v.g->node_first()->Get(m);
                    const uint32_t p = ms->patch();
                    if (!wholeOverlay && (out.firstLeaf[p] < t || out.firstLeaf[p] >= subtreeEnd[t])) continue;
                    const fb::PatchRecord& r = v.first(p);
                    const uint32_t S = r.slot_count();
                    const uint16_t* row = quanta.data() + quantaBegin[p] + uint64_t(ms->slot()) * S;
                    const uint32_t* to = slotNode.data() + r.slot_begin();
                    for (uint32_t j = 0; j < S; ++j)
                        if (row[j] != kNoPath) dj.offer(to[j], dj.dist[u] + double(row[j]) * patchScale[p], p);
                }
            }
            for (uint32_t b = targetsBegin; b < targetsEnd; ++b)
                labelValue[t][column + uint64_t(b - targetsBegin) * kHubBlock] = float(dj.dist[hubNode[b]]);
            tick(1);
        });
    }

    // 16-bit steps of one scale for labels and inner rows, so that the runtime adds them
    // as they are; the largest value takes kLargestLabelStep steps.
    // The steps fill reserved (untouched) memory while the floats are freed a table at a
    // time, so the stage's peak stays at its floats.
    double largest = 0;
    for (const auto& values : labelValue)
        for (float d : values)
            if (std::isfinite(d)) largest = std::max(largest, double(d));
    for (const auto& values : innerValues)
        for (float d : values)
            if (std::isfinite(d)) largest = std::max(largest, double(d));
    out.labelScale = largest > 0 ? float(largest / kLargestLabelStep) : 1.0f;
    out.columns.reserve(out.columnBegin[T]);
    for (auto& values : labelValue) {
        for (float d : values) out.columns.push_back(steps(d, out.labelScale));
        std::vector<float>().swap(values);
    }
    uint64_t innerEntries = 0;
    for (const auto& values : innerValues) innerEntries += values.size();
    out.inner.reserve(innerEntries);
    out.innerBegin.assign(1, 0);
    out.innerMatrixBegin.assign(1, 0);
    for (uint32_t f = 0; f < v.firstCount; ++f) {
        out.innerNode.insert(out.innerNode.end(), innerNodes[f].begin(), innerNodes[f].end());
        out.innerBegin.push_back(uint32_t(out.innerNode.size()));
        for (float d : innerValues[f]) out.inner.push_back(steps(d, out.labelScale));
        std::vector<float>().swap(innerValues[f]);
        out.innerMatrixBegin.push_back(out.inner.size());
    }
    computeHubExitLists(flatbuffer, out);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::string innerRowsAtOpenExcess(const std::vector<uint8_t>& flatbuffer, const InnerRowsAtOpenLimits& limits) {
    static_assert(VG_INNER_AT_OPEN_MAX_NODES == 16384 && VG_INNER_AT_OPEN_MAX_CHILDREN == 4096 &&
                      VG_INNER_AT_OPEN_MAX_CHILD_NODES == 65536,
                  "hub_labels.h states the format's limits as the default");
    const fb::Graph* g = fb::GetGraph(flatbuffer.data());
    const View v{g, uint32_t(g->node_flags()->size()), g->first_patches()->size(), g->second_patches()->size()};
    std::vector<std::vector<uint32_t>> children(v.firstCount);
    for (uint32_t q = 0; q < v.secondCount; ++q) children[v.second(q).parent()].push_back(q);
    auto tooMany = [](uint32_t f, uint64_t count, const char* what, uint64_t limit) {
        return "first-layer patch " + std::to_string(f) + " has " + std::to_string(count) + " " + what +
               ", more than the " + std::to_string(limit) +
               " a reader's search holds (bake with more first-layer patches, --n1, or store the rows)";
    };
    // A patch's inner rows are innerNodesOf its second-layer patches, known before the
    // labels: the bake stops before its longest stage.
    std::vector<uint32_t> rows;
    for (uint32_t f = 0; f < v.firstCount; ++f) {
        innerNodesOf(v, children[f], rows);
        uint64_t nodes = rows.size(), childNodes = 0;
        const fb::PatchRecord& r = v.first(f);
        for (uint32_t k = 0; k < r.slot_count(); ++k) nodes += v.active(v.slot(r.slot_begin() + k)) ? 0 : 1;
        for (uint32_t q : children[f]) childNodes += v.second(q).node_count();
        if (nodes > limits.nodes) return tooMany(f, nodes, "inner rows and merged-away slots", limits.nodes);
        if (children[f].size() > limits.children)
            return tooMany(f, children[f].size(), "second-layer patches", limits.children);
        if (childNodes > limits.childNodes)
            return tooMany(f, childNodes, "node slots in its second-layer patches", limits.childNodes);
    }
    return std::string();
}

}  // namespace vorogeo
