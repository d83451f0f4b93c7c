#include "libcommon/stats.h"

#include <algorithm>
#include <memory>
#include <mutex>

namespace rs {

namespace {

struct Registry {
    std::mutex mutex;
    std::vector<std::string> names;
    // One array per thread that has counted, kept after the thread ends so its counts still
    // appear in StatsSnapshot(). A thread resizes only its own array, under the mutex, so
    // the snapshot never reads one while it moves.
    std::vector<std::shared_ptr<std::vector<uint64_t>>> threadArrays;
};

Registry& TheRegistry() {
    static Registry r;
    return r;
}

// This thread's array in the registry (owned there; the thread_local pointer in detail is
// its data).
thread_local std::vector<uint64_t>* threadArray = nullptr;

}  // namespace

CounterId RegisterCounter(const std::string& name) {
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    for (size_t i = 0; i < r.names.size(); ++i)
        if (r.names[i] == name) return static_cast<CounterId>(i);
    r.names.push_back(name);
    return static_cast<CounterId>(r.names.size() - 1);
}

void detail::GrowThreadCounters(CounterId id) {
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    if (!threadArray) {
        auto a = std::make_shared<std::vector<uint64_t>>();
        r.threadArrays.push_back(a);
        threadArray = a.get();
    }
    // Room for every counter registered so far (at least id), and some to spare, so a
    // thread grows its array a few times in all.
    const size_t size = std::max({static_cast<size_t>(id) + 1, r.names.size(),
                                  2 * threadArray->size(), size_t{256}});
    threadArray->resize(size, 0);
    threadCounters = threadArray->data();
    threadCapacity = static_cast<CounterId>(size);
}

std::vector<CounterValue> StatsSnapshot() {
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    std::vector<CounterValue> out;
    for (size_t i = 0; i < r.names.size(); ++i) {
        uint64_t sum = 0;
        for (const auto& a : r.threadArrays) {
            if (i < a->size()) sum += (*a)[i];
        }
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
    for (const auto& a : r.threadArrays) std::fill(a->begin(), a->end(), 0);
}

}  // namespace rs
