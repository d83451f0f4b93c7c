#include "rayshade/worker_pool.h"

#include <exception>

#include "rayshade/renderer.h"

namespace rs {

WorkerPool::WorkerPool(int threads) {
    for (int t = 1; t < threads; ++t) helpers_.emplace_back([this] { HelperLoop(); });
}

WorkerPool::~WorkerPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
    }
    loopStarted_.notify_all();
    for (std::thread& t : helpers_) t.join();
}

void WorkerPool::Work() {
    for (long i; !(stoppable_ && StopRequested()) && (i = next_.fetch_add(1)) < count_;) (*body_)(i);
}

void WorkerPool::HelperLoop() {
    unsigned long seen = 0;
    while (true) {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            loopStarted_.wait(lock, [&] { return quit_ || loop_ != seen; });
            if (quit_) return;
            seen = loop_;
        }
        Work();
        std::lock_guard<std::mutex> lock(mutex_);
        if (--busyHelpers_ == 0) loopFinished_.notify_one();
    }
}

void WorkerPool::Run(long count, const std::function<void(long)>& body, bool stoppable) {
    if (count <= 0) return;
    const bool helped = !helpers_.empty() && count > 1;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        body_ = &body;
        count_ = count;
        stoppable_ = stoppable;
        next_.store(0);
        if (helped) {
            busyHelpers_ = static_cast<int>(helpers_.size());
            ++loop_;
        }
    }
    if (helped) loopStarted_.notify_all();
    // An exception from body on this thread ends the loop, but only after the helpers have
    // left it (they use `body`). On a helper thread it terminates, as in any std::thread.
    std::exception_ptr failure;
    try {
        Work();
    } catch (...) {
        failure = std::current_exception();
        next_.store(count);  // hand out no more indices
    }
    if (helped) {
        std::unique_lock<std::mutex> lock(mutex_);
        loopFinished_.wait(lock, [&] { return busyHelpers_ == 0; });
    }
    if (failure) std::rethrow_exception(failure);
}

}  // namespace rs
