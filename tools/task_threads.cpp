#include "task_threads.h"

namespace vorogeo::tools {

TaskThreads::TaskThreads(unsigned helpers) : helpers_(helpers) {
    for (unsigned i = 0; i < helpers; ++i) threads_.emplace_back([this, i] { work(i + 1); });
}

TaskThreads::~TaskThreads() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
}

void TaskThreads::work(unsigned index) {
    const uint32_t stride = helpers_ + 1;
    uint64_t seen = 0;
    for (;;) {
        vg_task task;
        void* context;
        uint32_t count;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return quit_ || round_ != seen; });
            if (quit_) return;
            seen = round_;
            task = task_, context = context_, count = count_;
        }
        for (uint32_t i = index; i < count; i += stride) task(context, i);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            --running_;
        }
        finished_.notify_one();
    }
}

void TaskThreads::parallelFor(void* user, uint32_t count, vg_task task, void* context) {
    TaskThreads& self = *static_cast<TaskThreads*>(user);
    const uint32_t stride = self.helpers_ + 1;
    {
        std::lock_guard<std::mutex> lock(self.mutex_);
        self.task_ = task, self.context_ = context, self.count_ = count;
        self.running_ = self.helpers_;
        ++self.round_;
    }
    self.wake_.notify_all();
    for (uint32_t i = 0; i < count; i += stride) task(context, i);
    std::unique_lock<std::mutex> lock(self.mutex_);
    self.finished_.wait(lock, [&] { return self.running_ == 0; });
}

}  // namespace vorogeo::tools
