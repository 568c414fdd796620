#include "geodesic_exact.h"
#include "window_math.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>
#include <string>


namespace vorogeo {

namespace {

constexpr uint32_t kNone = 0xffffffffu;
constexpr uint32_t kCandidate = 0xfffffffeu;
constexpr uint32_t kVertexEvent = 0xffffffffu;  // queue-entry ticket marking a vertex event
constexpr double kTwoPi = 6.283185307179586476925286766559;

// Relative tolerances, as fractions of the edge length (positions) or of the distance.
constexpr double kPieceEps = 1e-10;   // shorter pieces are dropped
constexpr double kGrazeEps = 1e-12;   // sources this close to the edge line do not propagate
constexpr double kWinEps = 1e-12;     // a candidate must beat a window by this much

inline double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// A window in the canonical frame of its edge, seen from the twin half-edge's frame: the
// edge reversed (x -> L - x) and the sides swapped (y -> -y).
inline void mirrorAcrossEdge(double L, double& b0, double& b1, double& sx, double& sy) {
    const double lo = L - b1, hi = L - b0;
    b0 = lo;
    b1 = hi;
    sx = L - sx;
    sy = -sy;
}

// Points in (lo, hi) where two window distance functions may be equal: roots of the
// quadratic obtained by squaring twice. Spurious roots only add harmless split points.
int crossings(double wx, double wy, double ws, double ex, double ey, double es, double lo,
              double hi, double out[2]) {
    // Shift to the interval start to keep the squared terms small.
    wx -= lo;
    ex -= lo;
    const double span = hi - lo;
    const double c = es - ws;
    const double alpha = 2.0 * (ex - wx);
    const double beta = wx * wx + wy * wy - ex * ex - ey * ey - c * c;
    const double qa = alpha * alpha - 4.0 * c * c;
    const double qb = 2.0 * alpha * beta + 8.0 * c * c * ex;
    const double qc = beta * beta - 4.0 * c * c * (ex * ex + ey * ey);
    double r[2];
    int n = 0;
    const double scale = std::fabs(qb) * span + std::fabs(qc) + 1e-300;
    if (std::fabs(qa) * span * span <= 1e-14 * scale) {
        if (qb != 0.0) r[n++] = -qc / qb;
    } else {
        // Equal sigmas give an exact double root that rounding can push to a slightly
        // negative discriminant: clamp, since an extra split point costs nothing.
        const double disc = std::max(qb * qb - 4.0 * qa * qc, 0.0);
        const double sq = std::sqrt(disc);
        const double q = -0.5 * (qb + (qb >= 0 ? sq : -sq));
        if (q != 0.0) {
            r[n++] = q / qa;
            r[n++] = qc / q;
        } else {
            r[n++] = 0.0;
        }
    }
    int m = 0;
    for (int i = 0; i < n; ++i)
        if (r[i] > 0.0 && r[i] < span && std::isfinite(r[i])) out[m++] = r[i] + lo;
    if (m == 2 && out[0] > out[1]) std::swap(out[0], out[1]);
    return m;
}

}  // namespace

// ------------------------------------------------------------------ ExactGeodesic

ExactGeodesic::ExactGeodesic(const Mesh& mesh) : mesh_(&mesh) {
    if (mesh.twin.size() != mesh.halfedgeCount())
        throw std::invalid_argument("exact geodesics need a mesh with connectivity built");
    precompute();
}

namespace {

// Interleaves the low 10 bits of x with two zero bits each (a Morton code's one axis).
uint32_t spreadBits(uint32_t x) {
    x &= 0x3FFu;
    x = (x | (x << 16)) & 0x030000FFu;
    x = (x | (x << 8)) & 0x0300F00Fu;
    x = (x | (x << 4)) & 0x030C30C3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
}

// `faces` reordered by the Morton code of their centroids (ties: the input's order), on a
// 1024^3 grid over their bounding box.
void mortonOrder(const Mesh& mesh, std::vector<uint32_t>& faces) {
    if (faces.empty()) return;
    std::vector<Vec3> centre(faces.size());
    Vec3 lo = mesh.positions[mesh.faces[faces[0]][0]], hi = lo;
    for (size_t i = 0; i < faces.size(); ++i) {
        const Tri& t = mesh.faces[faces[i]];
        centre[i] = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) * (1.0 / 3.0);
        lo = {std::min(lo.x, centre[i].x), std::min(lo.y, centre[i].y), std::min(lo.z, centre[i].z)};
        hi = {std::max(hi.x, centre[i].x), std::max(hi.y, centre[i].y), std::max(hi.z, centre[i].z)};
    }
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const double scale = extent > 0 ? 1023.0 / extent : 0.0;  // 1023: a centroid on the box's far side still fits 10 bits
    std::vector<std::pair<uint32_t, uint32_t>> keyed(faces.size());
    for (size_t i = 0; i < faces.size(); ++i) {
        const Vec3 q = (centre[i] - lo) * scale;
        keyed[i] = {spreadBits(uint32_t(q.x)) | (spreadBits(uint32_t(q.y)) << 1) | (spreadBits(uint32_t(q.z)) << 2),
                    uint32_t(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<uint32_t> ordered(faces.size());
    for (size_t i = 0; i < faces.size(); ++i) ordered[i] = faces[keyed[i].second];
    faces.swap(ordered);
}

}  // namespace

ExactGeodesic::ExactGeodesic(const Mesh& mesh, const std::vector<uint32_t>& faces, bool spatialOrder) {
    owned_ = std::make_unique<Mesh>();
    std::vector<uint32_t> sorted = faces;
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    for (uint32_t f : sorted)
        if (f >= mesh.faceCount()) throw std::invalid_argument("patch face " + std::to_string(f) + " out of range");
    for (uint32_t f : sorted)
        for (uint32_t v : mesh.faces[f]) toGlobal_.push_back(v);
    std::sort(toGlobal_.begin(), toGlobal_.end());
    toGlobal_.erase(std::unique(toGlobal_.begin(), toGlobal_.end()), toGlobal_.end());
    if (spatialOrder) {
        // Faces in Morton order, vertices in the order the faces first name them: a run's
        // front then touches faces and vertices that share cache lines, where an input's
        // scanline order puts a face's neighbours across the row far apart.
        mortonOrder(mesh, sorted);
        std::vector<uint8_t> named(toGlobal_.size(), 0);  // by position in the sorted vertices
        std::vector<uint32_t> byFaces;
        byFaces.reserve(toGlobal_.size());
        for (uint32_t f : sorted)
            for (uint32_t v : mesh.faces[f]) {
                const size_t i = size_t(std::lower_bound(toGlobal_.begin(), toGlobal_.end(), v) - toGlobal_.begin());
                if (!named[i]) {
                    named[i] = 1;
                    byFaces.push_back(v);
                }
            }
        toGlobal_.swap(byFaces);
    }
    // (In the input's order both lookups come out sorted already.)
    vertexLookup_.resize(toGlobal_.size());
    for (uint32_t i = 0; i < toGlobal_.size(); ++i) vertexLookup_[i] = {toGlobal_[i], i};
    if (spatialOrder) std::sort(vertexLookup_.begin(), vertexLookup_.end());
    owned_->positions.reserve(toGlobal_.size());
    for (uint32_t v : toGlobal_) owned_->positions.push_back(mesh.positions[v]);
    owned_->faces.reserve(sorted.size());
    for (uint32_t f : sorted) {
        Tri t;
        for (int k = 0; k < 3; ++k) t[k] = uint32_t(localVertex(mesh.faces[f][k]));
        owned_->faces.push_back(t);
    }
    faceLookup_.resize(sorted.size());
    for (uint32_t i = 0; i < sorted.size(); ++i) faceLookup_[i] = {sorted[i], i};
    if (spatialOrder) std::sort(faceLookup_.begin(), faceLookup_.end());
    faceToGlobal_ = std::move(sorted);
    splitPinchedVertices();
    ConnectivityReport rep = buildConnectivity(*owned_);
    if (!rep.ok)  // cannot happen for faces of a manifold mesh; a clear error if it does
        throw std::invalid_argument("patch is not a manifold (vertex " +
                                    std::to_string(globalVertex(uint32_t(rep.firstBadVertex))) + ")");
    mesh_ = owned_.get();
    precompute();
}

// A subset of a manifold's faces is a manifold except where two fans of faces around a
// vertex touch only at it. Such a vertex gets one copy per fan, and the copies are
// linked so that a path can still pass through the point from one fan to the other.
void ExactGeodesic::splitPinchedVertices() {
    Mesh& m = *owned_;
    const uint32_t nc = m.halfedgeCount();  // one corner per half-edge: corner c is faces[c/3][c%3]
    std::vector<uint32_t> parent(nc);
    for (uint32_t c = 0; c < nc; ++c) parent[c] = c;
    auto find = [&](uint32_t c) {
        while (parent[c] != c) c = parent[c] = parent[parent[c]];
        return c;
    };
    auto unite = [&](uint32_t a, uint32_t b) {
        a = find(a), b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    };
    // Faces sharing an edge join their corners at both ends of it.
    const std::vector<HalfedgeKey> keys = halfedgesByEdge(m);
    for (uint32_t i = 0; i + 1 < nc; ++i) {
        if (keys[i].edge != keys[i + 1].edge) continue;
        const int32_t h0 = keys[i].h, h1 = keys[i + 1].h;   // h1 runs the other way
        unite(uint32_t(h0), uint32_t(Mesh::next(h1)));      // tail(h0) == head(h1)
        unite(uint32_t(Mesh::next(h0)), uint32_t(h1));      // head(h0) == tail(h1)
    }
    // The fan holding a vertex's lowest corner keeps the vertex; other fans get copies.
    std::vector<int64_t> fanVertex(nc, -1);
    std::vector<uint8_t> taken(m.vertexCount(), 0);
    const uint32_t original = m.vertexCount();
    for (uint32_t c = 0; c < nc; ++c) {
        const uint32_t root = find(c);
        if (fanVertex[root] >= 0) continue;
        const uint32_t v = m.faces[c / 3][c % 3];
        if (!taken[v]) {
            taken[v] = 1;
            fanVertex[root] = v;
        } else {
            fanVertex[root] = m.vertexCount();
            m.positions.push_back(m.positions[v]);
            toGlobal_.push_back(toGlobal_[v]);
        }
    }
    if (m.vertexCount() == original) return;
    for (uint32_t c = 0; c < nc; ++c) m.faces[c / 3][c % 3] = uint32_t(fanVertex[find(c)]);
    // Circular lists linking the copies of each split vertex.
    alias_.resize(m.vertexCount());
    for (uint32_t v = 0; v < m.vertexCount(); ++v) alias_[v] = v;
    for (uint32_t copy = original; copy < m.vertexCount(); ++copy) {
        const uint32_t v = uint32_t(localVertex(toGlobal_[copy]));
        alias_[copy] = alias_[v];
        alias_[v] = copy;
    }
}

int64_t ExactGeodesic::localVertex(uint32_t global) const {
    if (!owned_) return global < mesh_->vertexCount() ? int64_t(global) : -1;
    // Copies of split vertices (appended later) are not in the lookup: it gives the first.
    auto it = std::lower_bound(vertexLookup_.begin(), vertexLookup_.end(), std::make_pair(global, 0u));
    return (it != vertexLookup_.end() && it->first == global) ? int64_t(it->second) : -1;
}

int64_t ExactGeodesic::localFace(uint32_t global) const {
    if (!owned_) return global < mesh_->faceCount() ? int64_t(global) : -1;
    auto it = std::lower_bound(faceLookup_.begin(), faceLookup_.end(), std::make_pair(global, 0u));
    return (it != faceLookup_.end() && it->first == global) ? int64_t(it->second) : -1;
}

void ExactGeodesic::precompute() {
    const Mesh& m = *mesh_;
    const uint32_t nh = m.halfedgeCount();
    frame_.resize(nh);
    edgeOf_.assign(nh, -1);
    canonical_.clear();
    edgeLength_.clear();
    for (uint32_t h = 0; h < nh; ++h) {
        const Vec3 p0 = m.positions[m.tail(int32_t(h))];
        const Vec3 p1 = m.positions[m.head(int32_t(h))];
        const Vec3 p2 = m.positions[m.apex(int32_t(h))];
        const Vec3 e = p1 - p0, a = p2 - p0;
        const double len = length(e);
        double x = len > 0 ? dot(a, e) / len : 0.0;
        double y = len > 0 ? length(cross(e, a)) / len : 0.0;
        frame_[h] = {x, y};
        if (edgeOf_[h] < 0) {
            int32_t id = int32_t(canonical_.size());
            canonical_.push_back(int32_t(h));
            edgeLength_.push_back(len);
            edgeOf_[h] = id;
            if (m.twin[h] >= 0) edgeOf_[m.twin[h]] = id;
        }
    }
    double sumLength = 0.0;
    for (double l : edgeLength_) sumLength += l;
    Vec3 lo{kInfinity, kInfinity, kInfinity}, hi{-kInfinity, -kInfinity, -kInfinity};
    for (const Vec3& p : m.positions) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const double meanEdge = edgeLength_.empty() ? 1.0 : sumLength / double(edgeLength_.size());
    queueBucketWidth_ = std::max(0.5 * meanEdge, 1e-300);
    // Geodesic distances rarely exceed a few bounding-box diagonals.
    const double reach = m.positions.empty() ? 1.0 : 4.0 * distance(lo, hi) + meanEdge;
    queueBuckets_ = size_t(std::min(reach / queueBucketWidth_, 1e6)) + 2;
    // Shortest paths bend only at saddle vertices (angle sum above 2*pi) and at boundary
    // vertices; flat vertices are let through by the neighbouring windows.
    std::vector<double> angle = vertexAngleSums(m);
    pseudo_.assign(m.vertexCount(), 0);
    for (uint32_t v = 0; v < m.vertexCount(); ++v)
        pseudo_[v] = m.vertexOut[v] >= 0 && (m.boundaryVertex[v] || angle[v] > kTwoPi * (1.0 + 1e-12));
}

// ------------------------------------------------------------------ ExactWorkspace

uint32_t ExactWorkspace::allocWindow() {
    ++alive_;
    stats_.peakWindows = std::max(stats_.peakWindows, alive_);
    if (!freeList_.empty()) {
        uint32_t id = freeList_.back();
        freeList_.pop_back();
        return id;
    }
    pool_.push_back(Window{});
    ticket_.push_back(0);
    return uint32_t(pool_.size() - 1);
}

void ExactWorkspace::freeWindow(uint32_t id) {
    --alive_;
    ticket_[id] = 0;
    freeList_.push_back(id);
}

void ExactWorkspace::schedule(uint32_t id) {
    const Window& w = pool_[id];
    ticket_[id] = nextTicket_++;
    queue_.push({windowMin(w.b0, w.b1, w.sx, w.sy, w.sigma), id, ticket_[id]});
}

void ExactWorkspace::relaxVertex(uint32_t v, double d) {
    double& cur = (*dist_)[v];
    if (d < cur) {
        cur = d;
        if (!isTarget_.empty() && isTarget_[v]) targetsDirty_ = true;
        if (geo_->pseudo_[v]) queue_.push({d, v, kVertexEvent});
        if (!geo_->alias_.empty())  // the same point in another fan of a patch
            for (uint32_t a = geo_->alias_[v]; a != v; a = geo_->alias_[a]) relaxVertex(a, d);
    }
}

void ExactWorkspace::reset(const ExactGeodesic& geo) {
    geo_ = &geo;
    pool_.clear();
    ticket_.clear();
    nextTicket_ = 1;
    freeList_.clear();
    // Bucket width: a fraction of the mean edge length, so a bucket holds about one
    // wavefront step; the last bucket catches whatever lies beyond the expected range.
    queue_.reset(geo.queueBucketWidth_, geo.queueBuckets_);
    edgeHead_.assign(geo.canonical_.size(), kNone);
    alive_ = 0;
    stats_ = ExactStats{};
}

// Windows from a (pseudo-)source at p, lying in `face`, onto the edges of that face.
void ExactWorkspace::emitFromPoint(const Vec3& p, uint32_t face, double sigma) {
    const Mesh& m = *geo_->mesh_;
    for (int k = 0; k < 3; ++k) {
        const int32_t h = int32_t(3 * face + k);
        const int32_t g = m.twin[h];
        if (g < 0) continue;
        // Frame of g: origin tail(g) = head(h), +x towards head(g); p lies on y < 0.
        const Vec3 o = m.positions[m.tail(g)];
        const Vec3 e = m.positions[m.head(g)] - o;
        const double len = length(e);
        if (len <= 0) continue;
        const Vec3 u = e * (1.0 / len);
        const Vec3 r = p - o;
        const double x = dot(r, u);
        const double y = -length(cross(u, r));
        insertCandidate(g, 0.0, len, x, y, sigma);
    }
}

void ExactWorkspace::emitFromVertex(uint32_t v) {
    const Mesh& m = *geo_->mesh_;
    const double dv = (*dist_)[v];
    ++stats_.pseudoSources;
    const int32_t start = m.vertexOut[v];
    if (start < 0) return;
    int32_t h = start;
    do {
        // h runs v -> w; the edge opposite v in face(h) is next(h) (w -> u).
        const int32_t k = Mesh::next(h);
        const double lk = geo_->edgeLength_[geo_->edgeOf_[k]];
        relaxVertex(m.head(h), dv + geo_->edgeLength_[geo_->edgeOf_[h]]);
        const int32_t g = m.twin[k];
        if (g >= 0) {
            // v in the frame of g (reverse of k): x' = L - x, y' = -y.
            const auto& fr = geo_->frame_[k];
            insertCandidate(g, 0.0, lk, lk - fr.apexX, -fr.apexY, dv);
        }
        h = m.nextAroundVertex(h);
    } while (h >= 0 && h != start);
    // A boundary vertex's fan starts at its boundary half-edge: relax the last neighbour too.
    if (h < 0) {
        int32_t last = start;
        for (int32_t t = start; t >= 0; t = m.nextAroundVertex(t)) last = t;
        const int32_t p = Mesh::prev(last);  // u -> v, the other boundary edge
        relaxVertex(m.tail(p), dv + geo_->edgeLength_[geo_->edgeOf_[p]]);
    }
}

void ExactWorkspace::insertCandidate(int32_t g, double b0, double b1, double sx, double sy,
                                     double sigma) {
    const ExactGeodesic& geo = *geo_;
    const Mesh& m = *geo.mesh_;
    const int32_t e = geo.edgeOf_[g];
    const double L = geo.edgeLength_[e];
    const double eps = kPieceEps * L;
    b0 = std::max(b0, 0.0);
    b1 = std::min(b1, L);
    if (!(b1 >= b0)) return;
    sy = std::min(sy, 0.0);  // the source lies behind the edge, seen from face(g)
    // To the canonical frame of the edge.
    if (geo.canonical_[e] != g) {
        double nb0 = L - b1, nb1 = L - b0;
        b0 = nb0;
        b1 = nb1;
        sx = L - sx;
        sy = -sy;
    }
    const int32_t hc = geo.canonical_[e];
    const uint32_t v0 = m.tail(hc), v1 = m.head(hc);
    std::vector<double>& dist = *dist_;

    // Vertices at the window's ends: these are real path lengths whatever happens below.
    const double d0 = windowDistance(sx, sy, sigma, b0);
    const double d1 = windowDistance(sx, sy, sigma, b1);
    if (b0 <= eps) relaxVertex(v0, windowDistance(sx, sy, sigma, 0.0));
    if (b1 >= L - eps) relaxVertex(v1, windowDistance(sx, sy, sigma, L));
    if (b1 - b0 <= eps) return;
    // Whole window beaten by the straight path from an edge end (distance differences
    // along the edge are monotone), or out of range: nothing of it can be a shortest path.
    if (d1 > dist[v0] + b1 + kWinEps * d1) return;
    if (d0 > dist[v1] + (L - b0) + kWinEps * d0) return;
    const double minDist = windowMin(b0, b1, sx, sy, sigma);
    if (minDist > maxDistance_) return;

    // Windows overlapping [b0, b1], in order.
    // `before` is the last window ending before b0 (kNone: the list head); ids, not
    // pointers, because the pool may grow below.
    uint32_t before = kNone;
    uint32_t first = edgeHead_[e];
    while (first != kNone && pool_[first].b1 <= b0) {
        before = first;
        first = pool_[first].next;
    }
    overlap_.clear();
    uint32_t after = first;
    while (after != kNone && pool_[after].b0 < b1) {
        overlap_.push_back(after);
        after = pool_[after].next;
    }

    // Pieces of the union of the candidate and the overlapped windows, each with its winner.
    pieces_.clear();
    auto addPiece = [&](double lo, double hi, uint32_t owner) {
        if (hi <= lo) return;
        if (!pieces_.empty() && pieces_.back().owner == owner && pieces_.back().hi >= lo) {
            pieces_.back().hi = hi;
            return;
        }
        pieces_.push_back({lo, hi, owner});
    };
    bool candidateWins = false;
    double cursor = b0;
    if (!overlap_.empty() && pool_[overlap_[0]].b0 < b0) addPiece(pool_[overlap_[0]].b0, b0, overlap_[0]);
    for (uint32_t id : overlap_) {
        const Window& w = pool_[id];
        if (w.b0 > cursor) {
            addPiece(cursor, std::min(w.b0, b1), kCandidate);
            candidateWins = true;
        }
        const double lo = std::max(cursor, w.b0), hi = std::min(w.b1, b1);
        if (hi > lo) {
            double split[4];
            int n = 0;
            split[n++] = lo;
            double roots[2];
            int nr = crossings(sx, sy, sigma, w.sx, w.sy, w.sigma, lo, hi, roots);
            for (int i = 0; i < nr; ++i) split[n++] = roots[i];
            split[n++] = hi;
            for (int i = 0; i + 1 < n; ++i) {
                const double mid = 0.5 * (split[i] + split[i + 1]);
                const double dc = windowDistance(sx, sy, sigma, mid);
                const double dw = windowDistance(w.sx, w.sy, w.sigma, mid);
                if (dc < dw - kWinEps * dw) {
                    addPiece(split[i], split[i + 1], kCandidate);
                    candidateWins = true;
                } else {
                    addPiece(split[i], split[i + 1], id);
                }
            }
        }
        cursor = std::max(cursor, hi);
        if (w.b1 > b1) addPiece(b1, w.b1, id);
    }
    if (cursor < b1) {
        addPiece(cursor, b1, kCandidate);
        candidateWins = true;
    }
    if (!candidateWins) return;
    bool anyLarge = false;
    for (const Piece& p : pieces_)
        if (p.owner == kCandidate && p.hi - p.lo > eps) anyLarge = true;
    if (!anyLarge) return;

    // Rebuild the list segment: the first piece of an old window reuses it, later pieces
    // of the same window are copies (queued if the original still waits in the queue).
    for (uint32_t id : overlap_) pool_[id].next = kCandidate;  // marks "not reused yet"
    uint32_t head = kNone, tail = kNone;
    auto append = [&](uint32_t id) {
        if (tail == kNone) head = id;
        else pool_[tail].next = id;
        tail = id;
    };
    for (const Piece& p : pieces_) {
        if (p.hi - p.lo <= eps) continue;
        if (p.owner == kCandidate) {
            uint32_t id = allocWindow();
            Window& w = pool_[id];
            w.b0 = p.lo;
            w.b1 = p.hi;
            w.sx = sx;
            w.sy = sy;
            w.sigma = sigma;
            w.h = g;
            w.next = kNone;
            ++stats_.windowsCreated;
            schedule(id);
            append(id);
        } else if (pool_[p.owner].next == kCandidate) {
            Window& w = pool_[p.owner];
            w.b0 = p.lo;
            w.b1 = p.hi;
            w.next = kNone;
            append(p.owner);
        } else {
            uint32_t id = allocWindow();
            Window copy = pool_[p.owner];
            copy.b0 = p.lo;
            copy.b1 = p.hi;
            copy.next = kNone;
            pool_[id] = copy;
            if (ticket_[p.owner]) schedule(id);  // the original still waits: so does its copy
            append(id);
        }
    }
    for (uint32_t id : overlap_)
        if (pool_[id].next == kCandidate) freeWindow(id);
    uint32_t& link = before == kNone ? edgeHead_[e] : pool_[before].next;
    if (tail == kNone) {
        link = after;
    } else {
        link = head;
        pool_[tail].next = after;
    }
}

void ExactWorkspace::propagate(uint32_t id) {
    const ExactGeodesic& geo = *geo_;
    const Mesh& m = *geo.mesh_;
    Window w = pool_[id];
    ticket_[id] = 0;
    ++stats_.windowsPropagated;
    const int32_t h = w.h;
    const int32_t e = geo.edgeOf_[h];
    const double L = geo.edgeLength_[e];
    // Into the frame of h: tail(h) at the origin, the face on y > 0, the source on y < 0.
    double b0 = w.b0, b1 = w.b1, sx = w.sx, sy = w.sy;
    if (geo.canonical_[e] != h) mirrorAcrossEdge(L, b0, b1, sx, sy);
    if (-sy <= kGrazeEps * L) return;  // rays along the edge enter neither face
    const double qx = geo.frame_[h].apexX, qy = geo.frame_[h].apexY;
    if (qy <= 0) return;  // degenerate face
    // Where the ray from the source through the apex crosses the edge line.
    const double xa = sx + (qx - sx) * (-sy) / (qy - sy);
    const double tol = 1e-9 * L;
    if (xa >= b0 - tol && xa <= b1 + tol) {
        const double dx = qx - sx, dy = qy - sy;
        const double da = w.sigma + std::sqrt(dx * dx + dy * dy);
        if (da <= maxDistance_) relaxVertex(m.apex(h), da);
    }
    // Left edge: tail(h) -> apex. Its outer half-edge runs the same way (origin tail(h)).
    if (xa > b0) {
        const int32_t g = m.twin[Mesh::prev(h)];
        const double lenL = std::sqrt(qx * qx + qy * qy);
        auto alphaAt = [&](double b) {
            double den = sy * qx + (b - sx) * qy;
            double a = den != 0.0 ? b * sy / den : 1.0;
            return std::min(std::max(a, 0.0), 1.0);
        };
        const double aLo = alphaAt(b0);
        const double aHi = xa <= b1 ? 1.0 : alphaAt(b1);
        const double ux = qx / lenL, uy = qy / lenL;
        const double nsx = sx * ux + sy * uy;
        const double nsy = cross2(ux, uy, sx, sy);
        if (g >= 0) {
            insertCandidate(g, aLo * lenL, aHi * lenL, nsx, nsy, w.sigma);
        } else {  // boundary: no face beyond, but its end vertices can still be reached
            if (aLo <= kPieceEps) relaxVertex(m.tail(h), windowDistance(nsx, nsy, w.sigma, 0.0));
            if (aHi >= 1.0 - kPieceEps) relaxVertex(m.apex(h), windowDistance(nsx, nsy, w.sigma, lenL));
        }
    }
    // Right edge: apex -> head(h); its outer half-edge starts at the apex.
    if (xa < b1) {
        const int32_t g = m.twin[Mesh::next(h)];
        const double ex = L - qx, ey = -qy;  // apex -> head(h)
        const double lenR = std::sqrt(ex * ex + ey * ey);
        auto betaAt = [&](double b) {  // 0 at head(h), 1 at the apex
            double den = (b - sx) * qy + sy * (qx - L);
            double t = den != 0.0 ? sy * (b - L) / den : 1.0;
            return std::min(std::max(t, 0.0), 1.0);
        };
        const double tHi = xa >= b0 ? 1.0 : betaAt(b0);
        const double tLo = betaAt(b1);
        const double ux = ex / lenR, uy = ey / lenR;
        const double rx = sx - qx, ry = sy - qy;
        const double nsx = rx * ux + ry * uy;
        const double nsy = cross2(ux, uy, rx, ry);
        const double lo = (1.0 - tHi) * lenR, hi = (1.0 - tLo) * lenR;
        if (g >= 0) {
            insertCandidate(g, lo, hi, nsx, nsy, w.sigma);
        } else {
            if (tHi >= 1.0 - kPieceEps) relaxVertex(m.apex(h), windowDistance(nsx, nsy, w.sigma, 0.0));
            if (tLo <= kPieceEps) relaxVertex(m.head(h), windowDistance(nsx, nsy, w.sigma, lenR));
        }
    }
}

double ExactWorkspace::distanceAt(const SurfacePoint& q, const std::vector<double>& distances) const {
    const ExactGeodesic& geo = *geo_;
    const Mesh& m = *geo.mesh_;
    if (q.face >= m.faceCount()) throw std::invalid_argument("face " + std::to_string(q.face) + " out of range");
    const Vec3 x = positionOf(m, q);
    double best = kInfinity;
    // Through a corner (a source vertex, a pseudo-source, or any path that reaches it).
    for (int k = 0; k < 3; ++k) {
        const uint32_t c = m.faces[q.face][k];
        best = std::min(best, distances[c] + distance(x, m.positions[c]));
    }
    // A source in the face (or on one of its edges, seen from the face across it).
    for (const SurfacePoint& sp : pointSources_) {
        bool inFace = sp.face == q.face;
        for (int k = 0; k < 3 && !inFace; ++k) {
            const int32_t t = m.twin[3 * sp.face + k];
            inFace = std::fabs(sp.bary[(k + 2) % 3]) <= 1e-12 && t >= 0 && uint32_t(Mesh::faceOf(t)) == q.face;
        }
        if (inFace) best = std::min(best, distance(x, positionOf(m, sp)));
    }
    // Windows entering the face: the straight line from the window's source when it passes
    // through the window, else through the nearer window end.
    for (int k = 0; k < 3; ++k) {
        const int32_t h = int32_t(3 * q.face + k);
        const int32_t e = geo.edgeOf_[h];
        const double L = geo.edgeLength_[e];
        const Vec3 o = m.positions[m.tail(h)];
        const Vec3 d = m.positions[m.head(h)] - o;
        if (!(L > 0)) continue;
        const Vec3 u = d * (1.0 / L);
        const Vec3 r = x - o;
        const double qx = dot(r, u), qy = length(cross(u, r));
        for (uint32_t id = edgeHead_[e]; id != kNone; id = pool_[id].next) {
            const Window& w = pool_[id];
            if (w.h != h) continue;
            double b0 = w.b0, b1 = w.b1, sx = w.sx, sy = w.sy;
            if (geo.canonical_[e] != h) mirrorAcrossEdge(L, b0, b1, sx, sy);
            const double xc = qy - sy > 0 ? sx + (qx - sx) * (-sy) / (qy - sy) : qx;
            double dw;
            if (xc >= b0 && xc <= b1) {
                dw = std::hypot(qx - sx, qy - sy);
            } else {
                const double b = xc < b0 ? b0 : b1;
                dw = std::hypot(b - sx, sy) + std::hypot(qx - b, qy);
            }
            best = std::min(best, w.sigma + dw);
        }
    }
    return best;
}

void ExactWorkspace::run(const ExactGeodesic& geo, const ExactQuery& query,
                         std::vector<double>& distances, ExactStats* stats) {
    const Mesh& m = *geo.mesh_;
    const uint32_t nv = m.vertexCount();
    for (const GeodesicSource& s : query.sources) {
        if (s.isVertex && s.vertex >= nv)
            throw std::invalid_argument("source vertex " + std::to_string(s.vertex) + " out of range");
        if (!s.isVertex) {
            const SurfacePoint& p = s.point;
            if (p.face >= m.faceCount())
                throw std::invalid_argument("source face " + std::to_string(p.face) + " out of range");
            double sum = p.bary[0] + p.bary[1] + p.bary[2];
            for (double b : p.bary)
                if (!std::isfinite(b) || b < -1e-9) throw std::invalid_argument("invalid barycentric coordinates");
            if (std::fabs(sum - 1.0) > 1e-6) throw std::invalid_argument("barycentric coordinates must sum to 1");
        }
    }
    for (uint32_t t : query.targets)
        if (t >= nv) throw std::invalid_argument("target vertex " + std::to_string(t) + " out of range");

    reset(geo);
    distances.assign(nv, kInfinity);
    dist_ = &distances;
    maxDistance_ = query.maxDistance;
    isTarget_.assign(query.targets.empty() ? 0 : nv, 0);
    for (uint32_t t : query.targets) isTarget_[t] = 1;

    pointSources_.clear();
    for (const GeodesicSource& s : query.sources) {
        if (!s.isVertex) pointSources_.push_back(s.point);
        if (s.isVertex) {
            distances[s.vertex] = 0.0;
            queue_.push({0.0, s.vertex, kVertexEvent});
            continue;
        }
        const SurfacePoint& sp = s.point;
        // Snap to a vertex when the point is one; emit into every face that contains it.
        int zero = 0, one = -1;
        for (int k = 0; k < 3; ++k) {
            if (std::fabs(sp.bary[k]) <= 1e-12) ++zero;
            if (std::fabs(sp.bary[k] - 1.0) <= 1e-12) one = k;
        }
        if (one >= 0) {
            uint32_t v = m.faces[sp.face][one];
            distances[v] = 0.0;
            queue_.push({0.0, v, kVertexEvent});
            continue;
        }
        const Vec3 p = positionOf(m, sp);
        for (int k = 0; k < 3; ++k) relaxVertex(m.faces[sp.face][k], distance(p, m.positions[m.faces[sp.face][k]]));
        emitFromPoint(p, sp.face, 0.0);
        if (zero == 1) {  // on an edge: also the face across it
            for (int k = 0; k < 3; ++k) {
                if (std::fabs(sp.bary[(k + 2) % 3]) > 1e-12) continue;  // edge k: corners k, k+1
                int32_t t = m.twin[3 * sp.face + k];
                if (t < 0) continue;
                uint32_t f2 = uint32_t(Mesh::faceOf(t));
                relaxVertex(m.apex(t), distance(p, m.positions[m.apex(t)]));
                emitFromPoint(p, f2, 0.0);
            }
        }
    }

    double targetBound = kInfinity;
    targetsDirty_ = true;
    while (!queue_.empty()) {
        const double bound = queue_.lowerBound();  // nothing left can get closer than this
        if (bound > maxDistance_) break;
        if (!query.targets.empty()) {
            if (targetsDirty_) {
                targetBound = 0.0;
                for (uint32_t t : query.targets) targetBound = std::max(targetBound, distances[t]);
                targetsDirty_ = false;
            }
            if (bound >= targetBound) break;
        }
        const QueueEntry top = queue_.top();
        queue_.pop();
        if (top.ticket == kVertexEvent) {
            if (distances[top.id] == top.key) emitFromVertex(top.id);
        } else {
            if (ticket_[top.id] == top.ticket) propagate(top.id);
        }
    }
    if (query.maxDistance < kInfinity)
        for (double& d : distances)
            if (d > query.maxDistance) d = kInfinity;
    if (stats) *stats = stats_;
    dist_ = nullptr;
}

size_t ExactWorkspace::memoryBytes() const {
    return pool_.capacity() * sizeof(Window) + (ticket_.capacity() + freeList_.capacity()) * sizeof(uint32_t) +
           edgeHead_.capacity() * sizeof(uint32_t) + queue_.memoryBytes() +
           overlap_.capacity() * sizeof(uint32_t) + pieces_.capacity() * sizeof(Piece) + isTarget_.capacity();
}

// ------------------------------------------------------------------ batch and baseline

std::vector<double> exactDistancesFrom(const Mesh& mesh, uint32_t source) {
    ExactGeodesic geo(mesh);
    ExactWorkspace ws;
    ExactQuery q;
    q.sources.push_back(GeodesicSource::atVertex(source));
    std::vector<double> d;
    ws.run(geo, q, d);
    return d;
}

void edgeDijkstra(const Mesh& mesh, uint32_t source, std::vector<double>& distances, int64_t target) {
    const uint32_t nv = mesh.vertexCount();
    if (source >= nv) throw std::invalid_argument("source vertex out of range");
    distances.assign(nv, kInfinity);
    using Item = std::pair<double, uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    distances[source] = 0.0;
    queue.push({0.0, source});
    while (!queue.empty()) {
        const double d = queue.top().first;  // not a structured binding: the lambda below captures it
        const uint32_t v = queue.top().second;
        queue.pop();
        if (d > distances[v]) continue;
        if (int64_t(v) == target) break;
        const int32_t start = mesh.vertexOut[v];
        if (start < 0) continue;
        auto relax = [&](uint32_t w) {
            double nd = d + distance(mesh.positions[v], mesh.positions[w]);
            if (nd < distances[w]) {
                distances[w] = nd;
                queue.push({nd, w});
            }
        };
        int32_t h = start, last = start;
        do {
            relax(mesh.head(h));
            last = h;
            h = mesh.nextAroundVertex(h);
        } while (h >= 0 && h != start);
        if (h < 0) relax(mesh.tail(Mesh::prev(last)));
    }
}

}  // namespace vorogeo
