// A fixed set of threads that run the renderer's parallel loops. A frame runs a few dozen
// loops (blocks of rows, refinement passes, encoding); starting threads for each one made
// every loop wait for a cold thread, whose first touch of its stack and heap costs page
// faults (expensive on virtual machines). The pool starts its threads once.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rs {

class WorkerPool {
  public:
    // `threads` ≥ 1 workers in all, the calling thread included.
    explicit WorkerPool(int threads);
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    // Runs body(i) for i in [0, count) on all workers, handing out indices in increasing
    // order, and returns when every started call has returned. When `stoppable`, no new
    // index is handed out once StopRequested() (renderer.h) is true. An exception thrown
    // by body on the calling thread is rethrown once the helpers have finished. Not
    // re-entrant: one loop at a time, from one thread.
    void Run(long count, const std::function<void(long)>& body, bool stoppable);

  private:
    void Work();          // takes indices of the current loop until none is left
    void HelperLoop();    // a helper thread: waits for loops and works on them
    static void ReserveThreadHeap();  // grows a helper's malloc heap in one step

    std::vector<std::thread> helpers_;
    std::mutex mutex_;
    std::condition_variable loopStarted_, loopFinished_;
    // The current loop (written under mutex_ before a loop starts, read by workers after).
    const std::function<void(long)>* body_ = nullptr;
    long count_ = 0;
    bool stoppable_ = true;
    std::atomic<long> next_{0};
    unsigned long loop_ = 0;  // number of loops started; helpers wait for it to change
    int busyHelpers_ = 0;     // helpers still working on the current loop
    bool quit_ = false;
};

}  // namespace rs
