// A few persistent threads that run the tasks of vg_distance_field_parallel, as an
// engine's job system would: `vorogeo bench` times the query on them without paying for
// thread creation per call. Like such systems (and TBB), an idle helper polls for the next
// round for a while before it sleeps: waking a sleeping thread takes the kernel tens of
// microseconds or more (a hypercall on this project's host), which a one-to-all query of a
// few milliseconds would otherwise pay at its start and at its end.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "vorogeo.h"

namespace vorogeo::tools {

class TaskThreads {
public:
    // `helpers` threads besides the caller's (0: the caller runs every task). A helper and
    // a caller waiting for one poll for up to `spinMicroseconds` before they sleep.
    explicit TaskThreads(unsigned helpers, unsigned spinMicroseconds = 2000);
    ~TaskThreads();
    TaskThreads(const TaskThreads&) = delete;
    TaskThreads& operator=(const TaskThreads&) = delete;

    // A vg_parallel_for: user is the TaskThreads. Task i runs on thread i % (helpers + 1),
    // the caller being thread 0; returns when all have returned.
    static void parallelFor(void* user, uint32_t count, vg_task task, void* context);

private:
    void work(unsigned index);
    // Polls until done() holds or the spin time has passed; true if it holds.
    template <class Done>
    bool spinUntil(Done done) const;

    const unsigned helpers_;
    const unsigned spinMicroseconds_;
    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable wake_, finished_;
    std::atomic<uint64_t> round_{0};   // bumped per parallelFor: the helpers' signal to start
    std::atomic<unsigned> running_{0};  // helpers still working on the current round
    std::atomic<bool> quit_{false};
    // The current round's work, written before round_ is bumped (release) and read after
    // it is seen (acquire).
    vg_task task_ = nullptr;
    void* context_ = nullptr;
    uint32_t count_ = 0;
};

}  // namespace vorogeo::tools
