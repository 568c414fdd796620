#include "task_threads.h"

#include <chrono>

namespace vorogeo::tools {

namespace {

inline void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

}  // namespace

TaskThreads::TaskThreads(unsigned helpers, unsigned spinMicroseconds)
    : helpers_(helpers), spinMicroseconds_(spinMicroseconds) {
    for (unsigned i = 0; i < helpers; ++i) threads_.emplace_back([this, i] { work(i + 1); });
}

TaskThreads::~TaskThreads() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_.store(true, std::memory_order_release);
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
}

template <class Done>
bool TaskThreads::spinUntil(Done done) const {
    const auto end = std::chrono::steady_clock::now() + std::chrono::microseconds(spinMicroseconds_);
    for (uint32_t i = 0;; ++i) {
        if (done()) return true;
        cpuRelax();
        // (The clock only every so often: it costs more than a poll.)
        if ((i & 255) == 255 && std::chrono::steady_clock::now() >= end) return done();
    }
}

void TaskThreads::work(unsigned index) {
    const uint32_t stride = helpers_ + 1;
    uint64_t seen = 0;
    for (;;) {
        auto ready = [&] {
            return quit_.load(std::memory_order_acquire) || round_.load(std::memory_order_acquire) != seen;
        };
        if (!spinUntil(ready)) {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, ready);
        }
        if (quit_.load(std::memory_order_acquire)) return;
        seen = round_.load(std::memory_order_acquire);
        const vg_task task = task_;
        void* const context = context_;
        const uint32_t count = count_;
        for (uint32_t i = index; i < count; i += stride) task(context, i);
        if (running_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            // Through the mutex, so that a caller between its test and its wait hears this.
            { std::lock_guard<std::mutex> lock(mutex_); }
            finished_.notify_one();
        }
    }
}

void TaskThreads::parallelFor(void* user, uint32_t count, vg_task task, void* context) {
    TaskThreads& self = *static_cast<TaskThreads*>(user);
    const uint32_t stride = self.helpers_ + 1;
    {
        std::lock_guard<std::mutex> lock(self.mutex_);
        self.task_ = task, self.context_ = context, self.count_ = count;
        self.running_.store(self.helpers_, std::memory_order_relaxed);
        self.round_.fetch_add(1, std::memory_order_release);
    }
    self.wake_.notify_all();
    for (uint32_t i = 0; i < count; i += stride) task(context, i);
    auto finished = [&] { return self.running_.load(std::memory_order_acquire) == 0; };
    if (self.spinUntil(finished)) return;
    std::unique_lock<std::mutex> lock(self.mutex_);
    self.finished_.wait(lock, finished);
}

}  // namespace vorogeo::tools
