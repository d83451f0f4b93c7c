#include "libobj/implicit/object_stats.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "libobj/implicit/field.h"

namespace rs {

namespace {

constexpr const char kCounterPrefix[] = "Implicit ";
constexpr const char kOctreeCounterPrefix[] = "Implicit octree ";

bool StartsWith(const std::string& s, const char* prefix) {
    return s.compare(0, std::char_traits<char>::length(prefix), prefix) == 0;
}

// The module's counters a build advances, declared by the files that count them (the
// octree's, OctreeCounterIds, and the field's, FieldCounterIds), in registration order,
// with the name of the per-object counter each is attributed to: "octree ..." for the
// octree build counters, "preprocessing ..." for the others (search tests and evaluations
// made while building).
const std::vector<std::pair<CounterId, std::string>>& BuildCounterSources() {
    static const std::vector<std::pair<CounterId, std::string>> sources = [] {
        std::vector<CounterId> ids = OctreeCounterIds();
        const FieldCounters& field = FieldCounterIds();
        ids.insert(ids.end(), {field.values, field.gradients, field.bounds});
        std::sort(ids.begin(), ids.end());
        const std::vector<CounterValue> all = StatsSnapshot();
        std::vector<std::pair<CounterId, std::string>> out;
        for (CounterId id : ids) {
            const std::string& name = all[static_cast<size_t>(id)].name;
            std::string what = name.substr(std::char_traits<char>::length(kCounterPrefix));
            if (!StartsWith(name, kOctreeCounterPrefix)) what = "preprocessing " + what;
            out.emplace_back(id, what);
        }
        return out;
    }();
    return sources;
}

// The evaluations this thread made inside lazy builds, so a ray's counts can leave them out.
struct BuildTally {
    uint64_t values = 0, gradients = 0, bounds = 0, riddersIterations = 0;
};
thread_local BuildTally buildTally;

}  // namespace

uint64_t ImplicitBuildEvaluations() {
    return buildTally.values + buildTally.gradients + buildTally.bounds;
}

ImplicitObjectStats::ImplicitObjectStats() {
    static std::atomic<int> created{0};
    label_ = "Implicit object " + std::to_string(++created);
    auto reg = [this](const char* what) { return RegisterCounter(label_ + ": " + what); };
    tests_ = reg("intersection calls");
    hits_ = reg("hits");
    values_ = reg("field evaluations");
    gradients_ = reg("gradient evaluations");
    bounds_ = reg("bound evaluations");
    riddersIterations_ = reg("Ridders iterations");
    buildMicroseconds_ = reg("preprocessing time (microseconds)");
    cells_ = reg("octree cells");
    memoryBytes_ = reg("octree memory (bytes)");
    automaticContacts_ = reg("automatic contacts");
    const size_t count = BuildCounterSources().size();
    buildCounterIds_ = std::make_unique<std::atomic<CounterId>[]>(count);
    for (size_t k = 0; k < count; ++k) buildCounterIds_[k].store(-1);
}

void ImplicitObjectStats::CountPreprocessing(uint64_t microseconds) const {
    Count(buildMicroseconds_, microseconds);
}

void ImplicitObjectStats::CountAutomaticContact() const { Count(automaticContacts_); }

void ImplicitObjectStats::CountTree(const LGOctree& tree) const {
    Count(cells_, static_cast<uint64_t>(tree.InternalCount() + tree.LeafCount()));
    Count(memoryBytes_, tree.MemoryBytes());
}

ImplicitObjectStats::BuildSnapshot ImplicitObjectStats::TakeBuildSnapshot() const {
    const std::vector<std::pair<CounterId, std::string>>& sources = BuildCounterSources();
    BuildSnapshot s;
    s.counts.resize(sources.size());
    for (size_t k = 0; k < sources.size(); ++k) s.counts[k] = ThreadCount(sources[k].first);
    s.cpuStart = ThreadCpuMicroseconds();
    return s;
}

// Attributes a build to this object by differences of the building thread's own counters
// (other threads may be counting at the same time).
void ImplicitObjectStats::Expand(const std::function<void()>& expand) const {
    const BuildSnapshot before = TakeBuildSnapshot();
    expand();
    AttributeBuild(before);
}

void ImplicitObjectStats::Kept(uint64_t cells, uint64_t bytes) const {
    Count(cells_, cells);
    Count(memoryBytes_, bytes);
}

void ImplicitObjectStats::AttributeBuild(const BuildSnapshot& before) const {
    Count(buildMicroseconds_, ThreadCpuMicroseconds() - before.cpuStart);
    const std::vector<std::pair<CounterId, std::string>>& sources = BuildCounterSources();
    const FieldCounters& field = FieldCounterIds();
    for (size_t k = 0; k < sources.size(); ++k) {
        const CounterId source = sources[k].first;
        const uint64_t delta = ThreadCount(source) - before.counts[k];
        if (delta == 0) continue;
        if (source == field.values) buildTally.values += delta;
        if (source == field.gradients) buildTally.gradients += delta;
        if (source == field.bounds) buildTally.bounds += delta;
        if (source == RiddersIterationCounter()) buildTally.riddersIterations += delta;
        CounterId target = buildCounterIds_[k].load(std::memory_order_relaxed);
        if (target < 0) {
            // RegisterCounter is idempotent, so racing threads store the same id.
            target = RegisterCounter(label_ + ": " + sources[k].second);
            buildCounterIds_[k].store(target, std::memory_order_relaxed);
        }
        Count(target, delta);
    }
}

ImplicitObjectStats::RaySnapshot ImplicitObjectStats::TakeRaySnapshot() const {
    const FieldCounters& field = FieldCounterIds();
    return {ThreadCount(field.values),   ThreadCount(field.gradients),
            ThreadCount(field.bounds),   ThreadCount(RiddersIterationCounter()),
            buildTally.values,           buildTally.gradients,
            buildTally.bounds,           buildTally.riddersIterations};
}

void ImplicitObjectStats::CountRay(const RaySnapshot& before, bool found) const {
    const FieldCounters& field = FieldCounterIds();
    Count(tests_);
    if (found) Count(hits_);
    // Less whatever lazy tree builds counted during this call.
    Count(values_, ThreadCount(field.values) - before.values -
                       (buildTally.values - before.builtValues));
    Count(gradients_, ThreadCount(field.gradients) - before.gradients -
                          (buildTally.gradients - before.builtGradients));
    Count(bounds_, ThreadCount(field.bounds) - before.bounds -
                       (buildTally.bounds - before.builtBounds));
    Count(riddersIterations_, ThreadCount(RiddersIterationCounter()) - before.iterations -
                                  (buildTally.riddersIterations - before.builtIterations));
}

}  // namespace rs
