// A few persistent threads that run the tasks of vg_distance_field_parallel, as an
// engine's job system would: `vorogeo bench` times the query on them without paying for
// thread creation per call.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "vorogeo.h"

namespace vorogeo::tools {

class TaskThreads {
public:
    // `helpers` threads besides the caller's (0: the caller runs every task).
    explicit TaskThreads(unsigned helpers);
    ~TaskThreads();
    TaskThreads(const TaskThreads&) = delete;
    TaskThreads& operator=(const TaskThreads&) = delete;

    // A vg_parallel_for: user is the TaskThreads. Task i runs on thread i % (helpers + 1),
    // the caller being thread 0; returns when all have returned.
    static void parallelFor(void* user, uint32_t count, vg_task task, void* context);

private:
    void work(unsigned index);

    const unsigned helpers_;
    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable wake_, finished_;
    uint64_t round_ = 0;   // bumped per parallelFor: the helpers' signal to start
    unsigned running_ = 0;  // helpers still working on the current round
    bool quit_ = false;
    vg_task task_ = nullptr;
    void* context_ = nullptr;
    uint32_t count_ = 0;
};

}  // namespace vorogeo::tools
