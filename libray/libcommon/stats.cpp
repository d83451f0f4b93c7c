#include "libcommon/stats.h"

#include <array>
#include <memory>
#include <mutex>

namespace rs {

namespace {

struct Registry {
    std::mutex mutex;
    std::vector<std::string> names;
    std::vector<std::shared_ptr<std::array<uint64_t, detail::kMaxCounters>>> threadArrays;
};

Registry& TheRegistry() {
    static Registry r;
    return r;
}

}  // namespace

CounterId RegisterCounter(const std::string& name) {
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    for (size_t i = 0; i < r.names.size(); ++i)
        if (r.names[i] == name) return static_cast<CounterId>(i);
    if (r.names.size() >= static_cast<size_t>(detail::kMaxCounters))
        return detail::kMaxCounters - 1;  // overflow bucket; never reached in practice
    r.names.push_back(name);
    return static_cast<CounterId>(r.names.size() - 1);
}

uint64_t* detail::RegisterThreadCounters() {
    // The registry keeps the array alive after the thread ends, so its counts still appear
    // in StatsSnapshot().
    auto a = std::make_shared<std::array<uint64_t, kMaxCounters>>();
    a->fill(0);
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.threadArrays.push_back(a);
    threadCounters = a->data();
    return threadCounters;
}

std::vector<CounterValue> StatsSnapshot() {
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    std::vector<CounterValue> out;
    for (size_t i = 0; i < r.names.size(); ++i) {
        uint64_t sum = 0;
        for (const auto& a : r.threadArrays) sum += (*a)[i];
        out.push_back({r.names[i], sum});
    }
    return out;
}

uint64_t CounterTotal(const std::string& name) {
    for (const CounterValue& c : StatsSnapshot())
        if (c.name == name) return c.value;
    return 0;
}

void ResetStats() {
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    for (const auto& a : r.threadArrays) a->fill(0);
}

}  // namespace rs
