#include "libcommon/parallel_build.h"

#include <algorithm>

namespace rs {

namespace {

// The loop installed on this thread; threads a loop runs on start with none.
thread_local const ParallelLoop* tInstalled = nullptr;

}  // namespace

ParallelBuildScope::ParallelBuildScope(const ParallelLoop* loop) : previous_(tInstalled) {
    tInstalled = loop;
}

ParallelBuildScope::~ParallelBuildScope() { tInstalled = previous_; }

void RunBuildLoop(long count, const std::function<void(long)>& body) {
    if (tInstalled == nullptr || count <= 1) {
        const ParallelBuildScope none(nullptr);
        for (long i = 0; i < count; ++i) body(i);
        return;
    }
    const ParallelLoop& loop = *tInstalled;
    const ParallelBuildScope none(nullptr);  // this thread runs body too
    loop(count, body);
}

void RunBuildLoopInChunks(std::size_t count, std::size_t chunk,
                          const std::function<void(std::size_t begin, std::size_t end)>& body) {
    const std::size_t chunks = (count + chunk - 1) / chunk;
    RunBuildLoop(static_cast<long>(chunks), [&](long k) {
        const std::size_t begin = static_cast<std::size_t>(k) * chunk;
        body(begin, std::min(count, begin + chunk));
    });
}

bool BuildLoopInstalled() { return tInstalled != nullptr; }

}  // namespace rs
