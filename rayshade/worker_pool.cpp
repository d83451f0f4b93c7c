#include "rayshade/worker_pool.h"

#include <cstdlib>
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

// glibc gives each helper a heap of its own (an arena, at most 64 MiB) and grows it a page
// at a time, one mprotect call per page, each taking the process's memory-map lock that
// every page fault of the other threads waits for: tetra's parallel parse made 6,400 such
// calls on its helper. Two allocations below the mmap threshold (rayshade's main sets it to
// 32 MiB) grow the heap to 60 MiB at once; freed, they stay in the heap (the trim threshold
// is above them), so later allocations reuse the span without system calls (tetra: 17
// calls; its whole render at -t 2, 0.187 s against 0.197 s, median of 12 interleaved
// runs). The span is only reserved: its pages take memory when first written, as before.
void WorkerPool::ReserveThreadHeap() {
#if defined(__GLIBC__)
    constexpr size_t kBlock = size_t{30} << 20;
    void* volatile first = std::malloc(kBlock);  // (volatile: kept, not elided)
    void* volatile second = std::malloc(kBlock);
    std::free(second);
    std::free(first);
#endif
}

void WorkerPool::Work() {
    for (long i; !(stoppable_ && StopRequested()) && (i = next_.fetch_add(1)) < count_;) (*body_)(i);
}

void WorkerPool::HelperLoop() {
    ReserveThreadHeap();
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
