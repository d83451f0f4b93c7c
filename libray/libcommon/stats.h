// Statistics counters. Counting is cheap and lock-free: every thread increments its own
// array; StatsSnapshot() sums all threads' arrays (call it when rendering has stopped).
// Counters are registered by name once (typically in a function-local static) and
// addressed by the returned id. The library only counts; libshade formats the report.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rs {

using CounterId = int;

// Returns the id of the counter called `name`, creating it on first use. Thread-safe.
CounterId RegisterCounter(const std::string& name);

namespace detail {
// This thread's counter array and its length: null and 0 before the thread's first count.
// Constant-initialised thread_locals cost one TLS load per count, with no initialisation
// guard. The array grows (GrowThreadCounters) when a counter registered after it was sized
// is first counted, so any number of counters keeps its own slot.
inline thread_local uint64_t* threadCounters = nullptr;
inline thread_local CounterId threadCapacity = 0;
// Makes this thread's array hold counter `id` (registering the array on first use).
void GrowThreadCounters(CounterId id);
}  // namespace detail

inline void Count(CounterId id, uint64_t n = 1) {
    if (id >= detail::threadCapacity) [[unlikely]] detail::GrowThreadCounters(id);
    detail::threadCounters[id] += n;
}

// This thread's count of a counter so far (0 before the thread first counts it). Callers
// take differences around a piece of work to attribute it (per ray, per object).
inline uint64_t ThreadCount(CounterId id) {
    return id < detail::threadCapacity ? detail::threadCounters[id] : 0;
}

struct CounterValue {
    std::string name;
    uint64_t value;
};

// All registered counters in registration order, summed over every thread so far.
std::vector<CounterValue> StatsSnapshot();
uint64_t CounterTotal(const std::string& name);
// Zeroes every thread's counters (between frames, or between tests).
void ResetStats();

// The pair of counters of a primitive type: "<Type> tests" and "<Type> hits". The report
// prints one line per type that was tested, in the spec's order (§5).
struct IntersectionCounters {
    explicit IntersectionCounters(const std::string& type)
        : typeName(type), tests(RegisterCounter(type + " tests")), hits(RegisterCounter(type + " hits")) {}
    std::string typeName;  // "Sphere", "Box", ... (also used by the verbose report)
    CounterId tests, hits;
};

}  // namespace rs
