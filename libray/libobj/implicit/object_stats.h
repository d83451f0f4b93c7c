// Layer 7 of the implicit module: the statistics of one implicit object, labelled "Implicit
// object N" (N = 1, 2, ... in order of creation), under "<label>: ...": its preprocessing
// time (microseconds), octree cells and memory (bytes), each octree heuristic's firings and
// the evaluations made while building (all summed over rebuilds), and per Intersect call
// the rays tested, hits, field, gradient and bound evaluations and Ridders iterations.
//
// Everything is attributed by differences of the counting thread's own counters
// (libcommon/stats.h ThreadCount): no locks. Octrees are built lazily, by the first ray
// reaching each one, on whichever render thread: a build's figures are attributed the same
// way by the building thread and left out of that ray's evaluation counts, so the
// preprocessing time is build CPU time summed over threads, part of the rendering time.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "libcommon/cpu_clock.h"
#include "libcommon/stats.h"
#include "libobj/implicit/field_motion.h"
#include "libobj/implicit/lg_octree.h"

namespace rs {

// The field, gradient and bound evaluations this thread has made inside lazy octree builds
// so far; callers counting a ray's evaluations by ThreadCount differences subtract it.
uint64_t ImplicitBuildEvaluations();

class ImplicitObjectStats final : public CellExpansionObserver {
  public:
    // Registers the object's counters under the next label.
    ImplicitObjectStats();

    // "Implicit object N", the prefix of this object's counters.
    const std::string& Label() const { return label_; }
    // Counts `microseconds` of preprocessing done outside tree builds (patches, BVH).
    void CountPreprocessing(uint64_t microseconds) const;
    // Counts the cells and memory of a tree built outside BuildTree (contacts build every
    // tree at once; their build figures are counted by the global counters only).
    void CountTree(const LGOctree& tree) const;
    // Counts one pair put in contact by `contact auto` in this build ("automatic contacts":
    // the pairs of the frame, since the statistics are reset between frames).
    void CountAutomaticContact() const;
    // Returns build()'s tree (an LGOctree) and attributes its time, cells, memory and the
    // module counters it advanced ("octree ...", "preprocessing ...") to this object,
    // leaving its evaluations out of the current ray's counts. Thread-safe. The build sees
    // no ray time: a moving field's point values there are its reference terms' (the tree
    // then does not depend on which ray builds it; its bounds hold at every time).
    template <class Build>
    LGOctree BuildTree(Build&& build) const {
        const RayTimeScope noTime(kNoRayTime);
        const BuildSnapshot before = TakeBuildSnapshot();
        LGOctree tree = build();
        AttributeBuild(before);
        CountTree(tree);
        return tree;
    }
    // The cell expansions of per-cell trees (LazyCellStore), attributed like tree builds.
    void Expand(const std::function<void()>& expand) const override;
    void Kept(uint64_t cells, uint64_t bytes) const override;

    // Runs search() (a ray's intersection, returning whether it hit) and counts the call,
    // the hit and the evaluations it made, less those of the tree builds it triggered.
    template <class Search>
    bool CountIntersect(Search&& search) const {
        const RaySnapshot before = TakeRaySnapshot();
        const bool found = search();
        CountRay(before, found);
        return found;
    }

  private:
    struct BuildSnapshot {
        std::vector<uint64_t> counts;  // the module's build counters, this thread
        uint64_t cpuStart = 0;  // ThreadCpuMicroseconds() when taken
    };
    struct RaySnapshot {
        uint64_t values, gradients, bounds, iterations;  // this thread's counters
        uint64_t builtValues, builtGradients, builtBounds, builtIterations;  // inside builds
    };
    BuildSnapshot TakeBuildSnapshot() const;
    void AttributeBuild(const BuildSnapshot& before) const;
    RaySnapshot TakeRaySnapshot() const;
    void CountRay(const RaySnapshot& before, bool found) const;

    std::string label_;
    CounterId tests_, hits_, values_, gradients_, bounds_, riddersIterations_;
    CounterId buildMicroseconds_, cells_, memoryBytes_, automaticContacts_;
    // Per-object counters fed by lazy builds ("<label>: octree ...", "preprocessing ..."),
    // registered on first use; index as the module's build counters, -1 until registered.
    std::unique_ptr<std::atomic<CounterId>[]> buildCounterIds_;
};

}  // namespace rs
