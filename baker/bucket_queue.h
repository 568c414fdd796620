// Min-priority queue for wavefront searches, whose keys mostly grow. Entries are binned
// into buckets of a fixed key width and only the bucket being drained is kept as a binary
// heap, so pops still come out in exact key order but each heap stays small.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace vorogeo {

template <class Entry>  // Entry has a `double key`
class BucketQueue {
public:
    // Keys are expected in [0, width * buckets); larger ones share the last bucket.
    void reset(double width, size_t buckets) {
        for (auto& b : buckets_) b.clear();
        if (buckets_.size() < buckets) buckets_.resize(buckets);
        used_ = std::max<size_t>(buckets, 1);
        width_ = width > 0 ? width : 1.0;
        current_ = 0;
        count_ = 0;
    }
    bool empty() const { return count_ == 0; }
    size_t size() const { return count_; }
    size_t memoryBytes() const {
        size_t bytes = buckets_.capacity() * sizeof(buckets_[0]);
        for (const auto& b : buckets_) bytes += b.capacity() * sizeof(Entry);
        return bytes;
    }

    void push(const Entry& e) {
        size_t b = bucketOf(e.key);
        if (b <= current_) {  // keys behind the front join the heap being drained
            auto& cur = buckets_[current_];
            cur.push_back(e);
            std::push_heap(cur.begin(), cur.end(), Greater());
        } else {
            buckets_[b].push_back(e);
        }
        ++count_;
    }
    // Valid only when !empty().
    const Entry& top() {
        advance();
        return buckets_[current_].front();
    }
    void pop() {
        advance();
        auto& cur = buckets_[current_];
        std::pop_heap(cur.begin(), cur.end(), Greater());
        cur.pop_back();
        --count_;
    }

private:
    struct Greater {
        bool operator()(const Entry& a, const Entry& b) const { return a.key > b.key; }
    };
    size_t bucketOf(double key) const {
        double b = key / width_;
        return b < double(used_ - 1) ? (b > 0 ? size_t(b) : 0) : used_ - 1;
    }
    void advance() {
        while (buckets_[current_].empty()) {
            ++current_;
            auto& cur = buckets_[current_];
            std::make_heap(cur.begin(), cur.end(), Greater());
        }
    }

    std::vector<std::vector<Entry>> buckets_;
    size_t used_ = 1, current_ = 0, count_ = 0;
    double width_ = 1.0;
};

}  // namespace vorogeo
