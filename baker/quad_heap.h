// An indexed 4-ary min-heap of node ids for the hub-label stage's searches (hub_labels.cpp,
// hub_label_runs.cpp): one entry per node, moved up in place when its key drops. The
// order is the caller's `before(a, b)` (a comes first), read at every step, so a queued
// node's key may only drop, and only right before push.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vorogeo {

class QuadHeap {
public:
    static constexpr uint32_t kNotQueued = UINT32_MAX;

    // Room for node ids below `nodes`, none queued.
    void reset(size_t nodes) {
        heap_.clear();
        position_.assign(nodes, kNotQueued);
    }
    // Empties the queue (the nodes still in it become unqueued).
    void clear() {
        for (uint32_t u : heap_) position_[u] = kNotQueued;
        heap_.clear();
    }
    bool empty() const { return heap_.empty(); }
    bool queued(uint32_t u) const { return position_[u] != kNotQueued; }

    // Queues u, or moves it up after its key dropped.
    template <class Before>
    void push(uint32_t u, const Before& before) {
        uint32_t i = position_[u];
        if (i == kNotQueued) {
            i = uint32_t(heap_.size());
            heap_.push_back(u);
        }
        while (i > 0) {
            const uint32_t parent = (i - 1) / 4;
            if (!before(u, heap_[parent])) break;
            place(i, heap_[parent]);
            i = parent;
        }
        place(i, u);
    }
    // Takes the first node off the queue (the queue must not be empty).
    template <class Before>
    uint32_t pop(const Before& before) {
        const uint32_t top = heap_[0], last = heap_.back();
        heap_.pop_back();
        position_[top] = kNotQueued;
        const uint32_t n = uint32_t(heap_.size());
        if (n == 0) return top;
        uint32_t i = 0;
        for (;;) {
            const uint32_t first = 4 * i + 1;
            if (first >= n) break;
            uint32_t best = first;
            const uint32_t end = first + 4 < n ? first + 4 : n;
            for (uint32_t c = first + 1; c < end; ++c)
                if (before(heap_[c], heap_[best])) best = c;
            if (!before(heap_[best], last)) break;
            place(i, heap_[best]);
            i = best;
        }
        place(i, last);
        return top;
    }

private:
    void place(uint32_t i, uint32_t u) {
        heap_[i] = u;
        position_[u] = i;
    }
    std::vector<uint32_t> heap_;
    std::vector<uint32_t> position_;  // per node: its index in heap_, or kNotQueued
};

}  // namespace vorogeo
