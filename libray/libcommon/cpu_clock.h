// The CPU time the calling thread has used, for statistics that must not count time the
// thread spent waiting or descheduled (on a loaded machine wall time overstates the work).
#pragma once

#include <time.h>

#include <cstdint>

namespace rs {

// Microseconds of CPU time used by the calling thread so far (POSIX
// CLOCK_THREAD_CPUTIME_ID); 0 where that clock is unavailable.
inline uint64_t ThreadCpuMicroseconds() {
    timespec now{};
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now) != 0) return 0;
    return static_cast<uint64_t>(now.tv_sec) * 1000000u + static_cast<uint64_t>(now.tv_nsec) / 1000u;
}

}  // namespace rs
