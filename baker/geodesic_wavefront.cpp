#include "geodesic_wavefront.h"
#include "parallel.h"
#include "window_math.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace vorogeo {

namespace {

constexpr uint32_t kNil = 0xFFFFFFFFu;

inline double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }
inline double len2(double x, double y) { return std::sqrt(x * x + y * y); }  // no hypot: the scaling is not needed

// Parameter t along the line O + t u (u a unit vector) where the line through the source
// S and the edge point (x, 0) meets it.
inline double meetLine(double ox, double oy, double ux, double uy, double sx, double sy, double x) {
    const double dx = x - sx, dy = -sy;
    return cross2(sx - ox, sy - oy, dx, dy) / cross2(ux, uy, dx, dy);
}

// Whether the segments from S1 to (x1, 0) and from S2 to (x2, 0) cross before the edge:
// then the two paths have swapped sides by the time they enter the face.
inline bool crossBeforeEdge(double s1x, double s1y, double x1, double s2x, double s2y, double x2) {
    const double d1x = s1x - x1, d2x = s2x - x2;
    const double den = cross2(d1x, s1y, d2x, s2y);
    if (den == 0.0) return false;
    const double y = cross2(x2 - x1, 0.0, d2x, s2y) / den * s1y;
    return y <= 0.0 && y >= s1y && y >= s2y;
}

// Whether a corner's straight way, `room` longer than the window's sigma, is shorter than
// the window's own distance there: room < sqrt(dx^2 + dy^2), without the square root.
inline bool cornerWins(double room, double dx, double dy) { return room < 0.0 || room * room < dx * dx + dy * dy; }

// Where the straight line from S to the apex C meets the edge (y = 0).
inline double splitAtApex(double sx, double sy, double cx, double cy) {
    const double den = cy - sy;
    if (den <= 0.0) return cx >= sx ? kInfinity : -kInfinity;  // degenerate face
    return sx - sy * (cx - sx) / den;
}

}  // namespace

// A list is a chain of blocks of windows, so its windows lie side by side in memory: the
// walk follows one link per block and the hardware prefetches within it.
uint32_t WavefrontWorkspace::allocBlock() {
    if (!freeBlocks_.empty()) {
        const uint32_t id = freeBlocks_.back();
        freeBlocks_.pop_back();
        return id;
    }
    blocks_.emplace_back();
    return uint32_t(blocks_.size() - 1);
}

// The window is written field by field from registers: built whole on the stack and
// copied, its 16-byte loads waited on the 8-byte stores that had just built it (a failed
// store-to-load forward; igea's patch runs 1.02-1.11x, BENCHMARKS.md).
inline void WavefrontWorkspace::append(int32_t h, double b0, double b1, double sx, double sy, double sigma) {
    ++alive_;
    ++stats_.windowsCreated;
    stats_.peakWindows = std::max(stats_.peakWindows, alive_);
    uint32_t t = listTail_[h];
    if (t == kNil || blocks_[t].count == kBlockWindows) {
        const uint32_t fresh = allocBlock();
        blocks_[fresh].count = 0;
        blocks_[fresh].next = kNil;
        if (t == kNil) listHead_[h] = fresh;
        else blocks_[t].next = fresh;
        listTail_[h] = t = fresh;
    }
    Block& block = blocks_[t];
    Window& w = block.windows[block.count++];
    w.b0 = b0;
    w.b1 = b1;
    w.sx = sx;
    w.sy = sy;
    w.sigma = sigma;
}

void WavefrontWorkspace::pushList(int32_t h) {
    if (h >= 0 && listHead_[h] != kNil) fifo_.push_back(h);
}

void WavefrontWorkspace::heapUpdate(uint32_t v) {
    const std::vector<double>& d = *dist_;
    uint32_t i = heapPos_[v];
    if (i == kNil) {
        i = uint32_t(heap_.size());
        heap_.push_back(v);
    }
    while (i > 0) {  // distances only decrease: sift up
        const uint32_t parent = (i - 1) / 2;
        if (!(d[v] < d[heap_[parent]])) break;
        heap_[i] = heap_[parent];
        heapPos_[heap_[i]] = i;
        i = parent;
    }
    heap_[i] = v;
    heapPos_[v] = i;
}

uint32_t WavefrontWorkspace::heapPop() {
    const std::vector<double>& d = *dist_;
    const uint32_t top = heap_[0];
    heapPos_[top] = kNil;
    const uint32_t last = heap_.back();
    heap_.pop_back();
    if (heap_.empty()) return top;
    const uint32_t n = uint32_t(heap_.size());
    uint32_t i = 0;
    for (;;) {
        uint32_t c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n && d[heap_[c + 1]] < d[heap_[c]]) ++c;
        if (!(d[heap_[c]] < d[last])) break;
        heap_[i] = heap_[c];
        heapPos_[heap_[i]] = i;
        i = c;
    }
    heap_[i] = last;
    heapPos_[last] = i;
    return top;
}

// A shorter path to v: a vertex not yet passed joins the queue; one the wavefront has
// passed re-emits its windows if paths can bend there (its old windows are beaten).
void WavefrontWorkspace::improve(uint32_t v, double d) {
    double& cur = (*dist_)[v];
    if (!(d < cur)) return;
    cur = d;
    if (!geo_->alias_.empty())  // the same point in another fan of a patch
        for (uint32_t a = geo_->alias_[v]; a != v; a = geo_->alias_[a]) improve(a, d);
    if (state_[v] != kInside) {
        state_[v] = kFront;
        heapUpdate(v);
    } else if (geo_->pseudo_[v]) {
        emitFromVertex(v, true);
    }
}

// Windows from v across the edge opposite v in each of its faces, and its neighbours'
// distances along its edges.
void WavefrontWorkspace::emitFromVertex(uint32_t v, bool insideArea) {
    const Mesh& m = *geo_->mesh_;
    const double dv = (*dist_)[v];
    if (dv > maxDistance_) return;  // everything it could give lies beyond the bound
    if (targeted_ && dv > budget(v)) return;  // ... or can reach no target within its bound
    ++stats_.pseudoSources;
    const int32_t start = m.vertexOut[v];
    if (start < 0) return;
    int32_t h = start;
    do {
        const int32_t k = Mesh::next(h);  // the edge opposite v in face(h)
        improve(m.head(h), dv + geo_->edgeLength_[geo_->edgeOf_[h]]);
        const int32_t g = m.twin[k];
        if (g >= 0) {
            const double lk = geo_->edgeLength_[geo_->edgeOf_[k]];
            const auto& fr = geo_->frame_[k];  // v is k's apex; g is k reversed
            append(g, 0.0, lk, lk - fr.apexX, -fr.apexY, dv);
            if (insideArea && (state_[m.tail(g)] == kInside || state_[m.head(g)] == kInside)) pushList(g);
        }
        h = m.nextAroundVertex(h);
    } while (h >= 0 && h != start);
    if (h < 0) {  // a boundary fan: its last neighbour lies on the other boundary edge
        int32_t last = start;
        for (int32_t t = start; t >= 0; t = m.nextAroundVertex(t)) last = t;
        const int32_t p = Mesh::prev(last);
        improve(m.tail(p), dv + geo_->edgeLength_[geo_->edgeOf_[p]]);
    }
}

// Takes every window waiting on half-edge h across its face at once: drops those that a
// corner of the edge beats at an end, gives the apex its distance from the best of them,
// and hands each survivor's rays to the face's other two edges, one side only unless it
// is the window through which the apex is reached (one angle, two sides).
void WavefrontWorkspace::propagateList(int32_t h) {
    uint32_t block = listHead_[h];
    if (block == kNil) return;
    listHead_[h] = listTail_[h] = kNil;
    const Mesh& m = *geo_->mesh_;
    const std::vector<double>& dist = *dist_;
    const uint32_t a = m.tail(h), b = m.head(h), c = m.apex(h);
    const double L = geo_->edgeLength_[geo_->edgeOf_[h]];
    const double cx = geo_->frame_[h].apexX, cy = geo_->frame_[h].apexY;
    const double da = dist[a], db = dist[b];
    // Windows whose minimum lies beyond keep give nothing within the bound(s).
    double keep = maxDistance_;
    if (targeted_) keep = std::min(keep, 0.5 * (budget(a) + budget(b) + L));

    size_t pendingCount = 0;
    double best = kInfinity, bestSplit = 0.0, bestSx = 0.0, bestSy = 0.0;
    const double tiny = 1e-20 * L;
    // Each block is copied out and freed at once, so the children reuse warm blocks.
    while (block != kNil) {
        const Block& blk = blocks_[block];
        const uint32_t count = blk.count, nextBlock = blk.next;
        if (nextBlock != kNil) __builtin_prefetch(&blocks_[nextBlock]);
        for (uint32_t k = 0; k < count; ++k) {
            const Window& w = blk.windows[k];
            ++stats_.windowsPropagated;
            --alive_;
            // A window's distance minus a corner's straight way is monotone along the edge,
            // so a corner that wins at the far end wins on the whole window. Compared
            // squared: no square root for the ~97% of windows that survive.
            if (cornerWins(da + w.b1 - w.sigma, w.b1 - w.sx, w.sy) ||
                cornerWins(db + (L - w.b0) - w.sigma, w.b0 - w.sx, w.sy))
                continue;
            // Distances only grow along a window's rays: one that starts beyond the bound
            // gives nothing within it.
            if (keep < kInfinity && windowMin(w.b0, w.b1, w.sx, w.sy, w.sigma) > keep) continue;
            // The window's way to the apex: straight through it, or round one of its ends.
            const double at = splitAtApex(w.sx, w.sy, cx, cy);
            double split = at, toApex;
            if (at - w.b0 > tiny && at - w.b1 < -tiny) {
                toApex = w.sigma + len2(cx - w.sx, cy - w.sy);
            } else if (at - w.b0 <= tiny) {
                toApex = windowDistance(w.sx, w.sy, w.sigma, w.b0) + len2(cx - w.b0, cy);
                split = w.b0;
            } else {
                toApex = windowDistance(w.sx, w.sy, w.sigma, w.b1) + len2(cx - w.b1, cy);
                split = w.b1;
            }
            if (toApex < best) {
                best = toApex;
                bestSplit = split;
                bestSx = w.sx;
                bestSy = w.sy;
            }
            // (In place, for the reason append gives.)
            if (pendingCount == batch_.size()) batch_.resize(std::max<size_t>(64, 2 * pendingCount));
            Pending& pending = batch_[pendingCount++];
            pending.window = w;
            pending.split = split;
            pending.at = at;
        }
        freeBlocks_.push_back(block);
        block = nextBlock;
    }
    if (pendingCount == 0) return;
    improve(c, best);

    const int32_t gl = m.twin[Mesh::prev(h)];  // a -> c, beyond the face
    const int32_t gr = m.twin[Mesh::next(h)];  // c -> b, beyond the face
    const double ll = len2(cx, cy), lr = len2(L - cx, cy);
    const double ulx = cx / ll, uly = cy / ll;
    const double urx = (L - cx) / lr, ury = -cy / lr;
    const double side = 1e-8 * L;
    for (size_t i = 0; i < pendingCount; ++i) {
        const Pending& pending = batch_[i];
        const Window& w = pending.window;
        bool toLeft = true, toRight = true;
        const double split = pending.split, at = pending.at;
        // Rays of w that pass the apex on the far side of the best window's path to it
        // cross that path, which is shorter up to the crossing: they are not shortest.
        if (split < bestSplit - side) {
            if (w.b1 < bestSplit || crossBeforeEdge(bestSx, bestSy, bestSplit, w.sx, w.sy, w.b1)) toRight = false;
        } else if (split > bestSplit + side) {
            if (w.b0 > bestSplit || crossBeforeEdge(bestSx, bestSy, bestSplit, w.sx, w.sy, w.b0)) toLeft = false;
        }
        if (toLeft && gl >= 0) {
            const double lo = w.b0, hi = std::min(w.b1, at);
            if (hi > lo) {
                const double t0 = std::max(0.0, meetLine(0.0, 0.0, ulx, uly, w.sx, w.sy, lo));
                // The ray through the apex meets the edge at its end: no division for it.
                const double t1 = hi == at ? ll : std::min(ll, meetLine(0.0, 0.0, ulx, uly, w.sx, w.sy, hi));
                if (t0 < t1) {
                    append(gl, t0, t1, ulx * w.sx + uly * w.sy, cross2(ulx, uly, w.sx, w.sy), w.sigma);
                }
            }
        }
        if (toRight && gr >= 0) {
            const double lo = std::max(w.b0, at), hi = w.b1;
            if (hi > lo) {
                const double t0 = lo == at ? 0.0 : std::max(0.0, meetLine(cx, cy, urx, ury, w.sx, w.sy, lo));
                const double t1 = std::min(lr, meetLine(cx, cy, urx, ury, w.sx, w.sy, hi));
                if (t0 < t1) {
                    const double rx = w.sx - cx, ry = w.sy - cy;
                    append(gr, t0, t1, urx * rx + ury * ry, cross2(urx, ury, rx, ry), w.sigma);
                }
            }
        }
    }
    // Lists next to the passed area cross their faces now; the others wait for a corner.
    if (gl >= 0 && (state_[a] == kInside || state_[c] == kInside)) pushList(gl);
    if (gr >= 0 && (state_[c] == kInside || state_[b] == kInside)) pushList(gr);
}

// The wavefront passes v: its neighbours join the front, a source or pseudo-source emits,
// and the lists around it cross their faces.
void WavefrontWorkspace::popVertex(uint32_t v) {
    const Mesh& m = *geo_->mesh_;
    state_[v] = kInside;
    const int32_t start = m.vertexOut[v];
    if (start < 0) return;
    int32_t h = start;
    do {
        for (uint32_t u : {m.head(h), m.apex(h)})
            if (state_[u] == kOutside) state_[u] = kFront;
        h = m.nextAroundVertex(h);
    } while (h >= 0 && h != start);
    if ((*dist_)[v] == 0.0 || geo_->pseudo_[v]) emitFromVertex(v, false);
    h = start;
    do {
        const int32_t p = Mesh::prev(h), k = Mesh::next(h);
        pushList(h);
        pushList(m.twin[h]);
        pushList(p);
        pushList(m.twin[p]);
        const int32_t beyond = m.twin[k];
        if (beyond < 0 || state_[m.apex(beyond)] != kOutside) {
            pushList(k);
            pushList(beyond);
        }
        h = m.nextAroundVertex(h);
    } while (h >= 0 && h != start);
    while (fifoHead_ < fifo_.size()) propagateList(fifo_[fifoHead_++]);
    fifo_.clear();
    fifoHead_ = 0;
}

void WavefrontWorkspace::reset(const ExactGeodesic& geo) {
    geo_ = &geo;
    const Mesh& m = *geo.mesh_;
    blocks_.clear();
    freeBlocks_.clear();
    listHead_.assign(m.halfedgeCount(), kNil);
    listTail_.assign(m.halfedgeCount(), kNil);
    fifo_.clear();
    fifoHead_ = 0;
    state_.assign(m.vertexCount(), kOutside);
    heap_.clear();
    heapPos_.assign(m.vertexCount(), kNil);
    alive_ = 0;
    stats_ = ExactStats{};
}

void WavefrontWorkspace::run(const ExactGeodesic& geo, const std::vector<uint32_t>& sources,
                             std::vector<double>& distances, ExactStats* stats, double maxDistance) {
    const uint32_t nv = geo.vertexCount();
    for (uint32_t s : sources)
        if (s >= nv) throw std::invalid_argument("source vertex " + std::to_string(s) + " out of range");
    if (!(maxDistance >= 0)) throw std::invalid_argument("maximum distance must be >= 0");
    targeted_ = false;
    propagate(geo, sources, distances, stats, maxDistance);
}

void WavefrontWorkspace::propagate(const ExactGeodesic& geo, const std::vector<uint32_t>& sources,
                                   std::vector<double>& distances, ExactStats* stats, double maxDistance) {
    reset(geo);
    maxDistance_ = maxDistance;
    distances.assign(geo.vertexCount(), kInfinity);
    dist_ = &distances;
    for (uint32_t s : sources) improve(s, 0.0);
    while (!heap_.empty()) popVertex(heapPop());
    if (maxDistance < kInfinity)
        for (double& d : distances)
            if (d > maxDistance) d = kInfinity;
    if (stats) *stats = stats_;
    dist_ = nullptr;
}

double WavefrontWorkspace::budget(uint32_t v) {
    if (budgetStamp_[v] == runStamp_) return budget_[v];
    const Vec3 p = geo_->mesh_->positions[v];
    const TargetLanes& t = targetLanes_;
    // Targets by decreasing bound, two at a time (padded with -inf bounds): none after one
    // whose bound is below the best can win. The maximum is the same whichever targets
    // past that point are also looked at.
    double best = -kInfinity;
#if defined(__SSE2__)
    const __m128d px = _mm_set1_pd(p.x), py = _mm_set1_pd(p.y), pz = _mm_set1_pd(p.z);
    __m128d lanes = _mm_set1_pd(-kInfinity);
    for (size_t i = 0; i < t.bound.size(); i += 2) {
        if (t.bound[i] <= best) break;
        const __m128d dx = _mm_sub_pd(px, _mm_loadu_pd(&t.x[i])), dy = _mm_sub_pd(py, _mm_loadu_pd(&t.y[i])),
                      dz = _mm_sub_pd(pz, _mm_loadu_pd(&t.z[i]));
        const __m128d d2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz));
        lanes = _mm_max_pd(lanes, _mm_sub_pd(_mm_loadu_pd(&t.bound[i]), _mm_sqrt_pd(d2)));
        best = std::max(_mm_cvtsd_f64(lanes), _mm_cvtsd_f64(_mm_unpackhi_pd(lanes, lanes)));
    }
#else
    for (size_t i = 0; i < t.bound.size(); ++i) {
        if (t.bound[i] <= best) break;
        const double dx = p.x - t.x[i], dy = p.y - t.y[i], dz = p.z - t.z[i];
        best = std::max(best, t.bound[i] - std::sqrt(dx * dx + dy * dy + dz * dz));
    }
#endif
    budgetStamp_[v] = runStamp_;
    return budget_[v] = best;
}

void WavefrontWorkspace::runToTargets(const ExactGeodesic& geo, uint32_t source, const std::vector<Target>& targets,
                                      std::vector<double>& distances, ExactStats* stats) {
    const uint32_t nv = geo.vertexCount();
    if (source >= nv) throw std::invalid_argument("source vertex " + std::to_string(source) + " out of range");
    double maxBound = 0;
    for (const Target& t : targets) {
        if (t.vertex >= nv) throw std::invalid_argument("target vertex " + std::to_string(t.vertex) + " out of range");
        if (!(t.bound >= 0)) throw std::invalid_argument("target bound must be >= 0");
        maxBound = std::max(maxBound, t.bound);
    }
    byBound_.resize(targets.size());
    for (uint32_t i = 0; i < targets.size(); ++i) byBound_[i] = i;
    std::sort(byBound_.begin(), byBound_.end(), [&](uint32_t x, uint32_t y) {
        return targets[x].bound > targets[y].bound || (targets[x].bound == targets[y].bound && x < y);
    });
    const std::vector<Vec3>& pos = geo.mesh().positions;
    TargetLanes& lanes = targetLanes_;
    const size_t padded = (targets.size() + 1) / 2 * 2;
    lanes.x.assign(padded, 0.0);
    lanes.y.assign(padded, 0.0);
    lanes.z.assign(padded, 0.0);
    lanes.bound.assign(padded, -kInfinity);
    for (size_t i = 0; i < targets.size(); ++i) {
        const Target& t = targets[byBound_[i]];
        lanes.x[i] = pos[t.vertex].x;
        lanes.y[i] = pos[t.vertex].y;
        lanes.z[i] = pos[t.vertex].z;
        lanes.bound[i] = t.bound;
    }
    if (budgetStamp_.size() != nv || runStamp_ == kNil) {
        budgetStamp_.assign(nv, 0);
        budget_.assign(nv, 0.0);
        runStamp_ = 0;
    }
    ++runStamp_;
    targeted_ = true;
    propagate(geo, {source}, distances, stats, maxBound);
    for (const Target& t : targets)
        if (distances[t.vertex] > t.bound) distances[t.vertex] = kInfinity;
}

size_t WavefrontWorkspace::memoryBytes() const {
    return blocks_.capacity() * sizeof(Block) +
           (freeBlocks_.capacity() + listHead_.capacity() + listTail_.capacity() + heap_.capacity() +
            heapPos_.capacity()) * sizeof(uint32_t) +
           fifo_.capacity() * sizeof(int32_t) + state_.capacity() + batch_.capacity() * sizeof(Pending) +
           (targetLanes_.x.capacity() * 4 + budget_.capacity()) * sizeof(double) +
           (budgetStamp_.capacity() + byBound_.capacity()) * sizeof(uint32_t);
}

std::vector<double> wavefrontDistancesFrom(const ExactGeodesic& geo, uint32_t source) {
    WavefrontWorkspace ws;
    std::vector<double> d;
    ws.run(geo, {source}, d);
    return d;
}

std::vector<std::vector<double>> exactDistancesBatch(const ExactGeodesic& geo,
                                                     const std::vector<uint32_t>& sources,
                                                     double maxDistance) {
    std::vector<std::vector<double>> out(sources.size());
    PerThread<WavefrontWorkspace> workspaces;
    parallelFor(sources.size(), [&](size_t i) { workspaces.local().run(geo, {sources[i]}, out[i], nullptr, maxDistance); });
    return out;
}

}  // namespace vorogeo
