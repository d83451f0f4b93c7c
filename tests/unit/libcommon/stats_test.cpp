// Statistics counters: every registered counter keeps its own slot however many there are
// (a scene with many implicit objects registers dozens per object), in every thread.
#include "libcommon/stats.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <thread>
#include <vector>

namespace rs {
namespace {

std::map<std::string, uint64_t> Totals() {
    std::map<std::string, uint64_t> totals;
    for (const CounterValue& c : StatsSnapshot()) totals[c.name] = c.value;
    return totals;
}

TEST(Stats, ThousandsOfCountersKeepTheirOwnCounts) {
    constexpr int kCounters = 5000;
    std::vector<CounterId> ids;
    for (int i = 0; i < kCounters; ++i) {
        ids.push_back(RegisterCounter("stats test counter " + std::to_string(i)));
    }
    for (int i = 0; i < kCounters; ++i) Count(ids[i], static_cast<uint64_t>(i) + 1);
    // Another thread counts every counter once more, registering its array late and
    // growing it from the first count of the highest id.
    std::thread other([&] {
        Count(ids.back(), 1);
        for (int i = 0; i + 1 < kCounters; ++i) Count(ids[i], 1);
        EXPECT_EQ(ThreadCount(ids.front()), 1u);
        EXPECT_EQ(ThreadCount(ids.back()), 1u);
    });
    other.join();
    EXPECT_EQ(ThreadCount(ids[41]), 42u);
    const std::map<std::string, uint64_t> totals = Totals();
    for (int i = 0; i < kCounters; ++i) {
        const auto it = totals.find("stats test counter " + std::to_string(i));
        ASSERT_NE(it, totals.end()) << i;
        ASSERT_EQ(it->second, static_cast<uint64_t>(i) + 2) << i;
    }
}

TEST(Stats, ACounterRegisteredAfterTheFirstCountStartsAtZero) {
    const CounterId early = RegisterCounter("stats test early");
    Count(early, 3);
    const CounterId late = RegisterCounter("stats test late");
    EXPECT_EQ(ThreadCount(late), 0u);
    Count(late, 5);
    EXPECT_EQ(ThreadCount(early), 3u);
    EXPECT_EQ(ThreadCount(late), 5u);
    EXPECT_EQ(RegisterCounter("stats test late"), late);
    ResetStats();
    EXPECT_EQ(ThreadCount(early), 0u);
    EXPECT_EQ(CounterTotal("stats test late"), 0u);
}

}  // namespace
}  // namespace rs
