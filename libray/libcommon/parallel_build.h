// Parallel loops for the scene's preparation (acceleration builds) on threads the program
// owns: rayshade installs its render worker pool around PrepareFrame, so the hierarchies
// and grids are built on the render's threads. Library code calls RunBuildLoop, which runs
// serially when nothing is installed (tests, rayquery), so results must never depend on
// whether or how the calls overlap: each index's work writes only its own outputs.
#pragma once

#include <cstddef>
#include <functional>

namespace rs {

// Runs body(i) for every i in [0, count), in any order and possibly concurrently, and
// returns when every call has returned. Build bodies throw nothing but std::bad_alloc, which
// on a thread other than the caller's ends the process (as in any std::thread).
using ParallelLoop = std::function<void(long count, const std::function<void(long)>& body)>;

// Installs `loop` for RunBuildLoop calls made on the constructing thread while the scope
// lives (scopes nest; the innermost wins; null installs none).
class ParallelBuildScope {
  public:
    explicit ParallelBuildScope(const ParallelLoop* loop);
    ~ParallelBuildScope();
    ParallelBuildScope(const ParallelBuildScope&) = delete;
    ParallelBuildScope& operator=(const ParallelBuildScope&) = delete;

  private:
    const ParallelLoop* previous_;
};

// Runs body(i) for i in [0, count) through the loop installed on the calling thread, or in
// increasing order on this thread when none is. While body runs no loop is installed on any
// thread that runs it, so RunBuildLoop calls nested in body run serially (the loop need not
// be re-entrant).
void RunBuildLoop(long count, const std::function<void(long)>& body);

// RunBuildLoop over the ranges [begin, end) that cut [0, count) into runs of `chunk` items
// (the last one shorter; range k begins at k * chunk): for passes over many items, each too
// cheap to hand out alone.
void RunBuildLoopInChunks(std::size_t count, std::size_t chunk,
                          const std::function<void(std::size_t begin, std::size_t end)>& body);

// Whether RunBuildLoop calls made on this thread now may run concurrently (a loop is
// installed): for work that pays only when they do.
bool BuildLoopInstalled();

}  // namespace rs
