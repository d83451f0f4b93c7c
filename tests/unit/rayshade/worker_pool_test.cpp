#include "rayshade/worker_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace rs {
namespace {

TEST(WorkerPool, RunsEveryIndexOnceForAnyThreadCount) {
    for (int threads : {1, 2, 4}) {
        WorkerPool pool(threads);
        for (long count : {0L, 1L, 3L, 1000L}) {
            std::vector<std::atomic<int>> runs(static_cast<size_t>(count));
            pool.Run(count, [&](long i) { runs[static_cast<size_t>(i)].fetch_add(1); }, false);
            for (long i = 0; i < count; ++i)
                EXPECT_EQ(runs[static_cast<size_t>(i)].load(), 1) << threads << " threads, index " << i;
        }
    }
}

TEST(WorkerPool, UsesItsHelperThreads) {
    WorkerPool pool(2);
    std::atomic<int> waiting{0};
    std::atomic<bool> other{false};
    const std::thread::id caller = std::this_thread::get_id();
    // Two items that each wait (bounded) for the other to start: only two threads can
    // finish both promptly.
    pool.Run(2, [&](long) {
        if (std::this_thread::get_id() != caller) other = true;
        waiting.fetch_add(1);
        for (int spin = 0; spin < 2000000 && waiting.load() < 2; ++spin) std::this_thread::yield();
    }, false);
    EXPECT_TRUE(other.load());
    EXPECT_EQ(waiting.load(), 2);
}

TEST(WorkerPool, AnExceptionOnTheCallerIsRethrownAndThePoolStaysUsable) {
    WorkerPool pool(2);
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<long> done{0};
    // The helper's items are slow, so the caller is sure to take one of the 100.
    EXPECT_THROW(pool.Run(100, [&](long) {
        if (std::this_thread::get_id() == caller) throw std::runtime_error("stop");
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        done.fetch_add(1);
    }, false), std::runtime_error);
    EXPECT_LT(done.load(), 100);
    std::atomic<long> sum{0};
    pool.Run(10, [&](long i) { sum.fetch_add(i); }, false);
    EXPECT_EQ(sum.load(), 45);
}

}  // namespace
}  // namespace rs
