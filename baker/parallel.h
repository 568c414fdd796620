// The baker's parallel loops and per-thread scratch. TBB in every build except the
// ThreadSanitizer one (VOROGEO_PLAIN_THREADS): Debian's libtbb is not instrumented, so
// TSan cannot see the ordering its scheduler provides and reports its internals; there
// the same loops run on std::threads (as many as TBB would use), so that TSan checks the
// loop bodies, which are vorogeo's code, under real concurrency.
#pragma once

#include <algorithm>
#include <cstddef>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#if VOROGEO_PLAIN_THREADS
#include <atomic>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>
#else
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#endif

namespace vorogeo {

// Threads a loop started here may use: the current arena's size within TBB's global limit.
inline size_t parallelism() {
    const size_t arena = size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
    return std::min(arena, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

#if !VOROGEO_PLAIN_THREADS

// body(i) for every i in [0, n), in parallel; the first exception is rethrown here.
template <class Body>
void parallelFor(size_t n, const Body& body) {
    tbb::parallel_for(size_t(0), n, body);
}

// One T per worker thread, created on first use by local().
template <class T>
using PerThread = tbb::enumerable_thread_specific<T>;

#else

template <class Body>
void parallelFor(size_t n, const Body& body) {
    const size_t threads = std::min(parallelism(), n);
    if (threads <= 1) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    std::atomic<size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex errorMutex;
    auto work = [&] {
        try {
            for (size_t i; !failed.load() && (i = next++) < n;) body(i);
        } catch (...) {
            std::lock_guard<std::mutex> lock(errorMutex);
            if (!error) error = std::current_exception();
            failed = true;
        }
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

template <class T>
class PerThread {
public:
    T& local() {
        std::lock_guard<std::mutex> lock(mutex_);
        std::unique_ptr<T>& slot = byThread_[std::this_thread::get_id()];
        if (!slot) slot = std::make_unique<T>();
        return *slot;
    }

private:
    std::mutex mutex_;
    std::map<std::thread::id, std::unique_ptr<T>> byThread_;
};

#endif

}  // namespace vorogeo
