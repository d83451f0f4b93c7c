#include "libobj/implicit/lg_octree.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "libcommon/error.h"
#include "libcommon/float_rounding.h"
#include "libcommon/stats.h"
#include "libobj/implicit/lg_octree_detail.h"

namespace rs {

using lg_octree_detail::ChildBox;
using lg_octree_detail::Counters;
using lg_octree_detail::OctreeCounters;

namespace lg_octree_detail {

const OctreeCounters& Counters() {
    static const OctreeCounters counters;
    return counters;
}

}  // namespace lg_octree_detail

CounterId RiddersIterationCounter() { return Counters().riddersIterations; }

std::vector<CounterId> OctreeCounterIds() {
    const OctreeCounters& c = Counters();
    return {c.cellsBuilt,
                               c.rangeFired,
                               c.patchFired,
                               c.h1Fired,
                               c.h1bisFired,
                               c.h2Fired,
                               c.h3Fired,
                               c.h3bisFired,
                               c.budgetFired,
                               c.h4Fired,
                               c.h5Fired,
                               c.cellsVisited,
                               c.test0bis,
                               c.test1,
                               c.test2bisChord,
                               c.monotoneNoRoot,
                               c.test3,
                               c.splits,
                               c.segmentBounds,
                               c.ridders,
                               c.riddersIterations,
                               c.floorRoots,
                               c.unresolved,
                               c.rejectedRoots,
                               c.excludedSegments};
}


namespace {

// The lattice values of the tree being built (LGOctree::LatticeValue): an open-addressing
// table per thread, reused by every build on that thread (a tree is built on one thread,
// start to end) and emptied in O(1) by advancing a generation stamp.
class LatticeValueTable {
  public:
    void Clear() {
        if (++stamp_ == 0) {  // wrapped: forget every stamp
            std::fill(stamps_.begin(), stamps_.end(), 0u);
            stamp_ = 1;
        }
        size_ = 0;
    }
    double* Find(uint64_t key) {
        if (stamps_.empty()) return nullptr;
        for (size_t i = Hash(key) & mask_;; i = (i + 1) & mask_) {
            if (stamps_[i] != stamp_) return nullptr;
            if (keys_[i] == key) return &values_[i];
        }
    }
    // The memory the values of the current build need: a slot each (key, value, stamp) at
    // the table's highest load, one half.
    size_t LiveBytes() const {
        return 2 * size_ * (sizeof(uint64_t) + sizeof(double) + sizeof(uint32_t));
    }
    // key must be absent.
    double* Insert(uint64_t key, double value) {
        if (2 * (size_ + 1) > stamps_.size()) Grow();
        size_t i = Hash(key) & mask_;
        while (stamps_[i] == stamp_) i = (i + 1) & mask_;
        stamps_[i] = stamp_;
        keys_[i] = key;
        values_[i] = value;
        ++size_;
        return &values_[i];
    }

  private:
    static size_t Hash(uint64_t key) {  // a 64-bit mix (splitmix64's finaliser)
        key ^= key >> 30;
        key *= 0xbf58476d1ce4e5b9ULL;
        key ^= key >> 27;
        key *= 0x94d049bb133111ebULL;
        key ^= key >> 31;
        return static_cast<size_t>(key);
    }
    void Grow() {
        std::vector<uint64_t> keys = std::move(keys_);
        std::vector<double> values = std::move(values_);
        std::vector<uint32_t> stamps = std::move(stamps_);
        const size_t capacity = std::max<size_t>(1024, 2 * stamps.size());
        keys_.assign(capacity, 0);
        values_.assign(capacity, 0);
        stamps_.assign(capacity, 0);
        mask_ = capacity - 1;
        const uint32_t live = stamp_;
        stamp_ = 1;
        size_ = 0;
        for (size_t i = 0; i < stamps.size(); ++i) {
            if (stamps[i] == live) Insert(keys[i], values[i]);
        }
    }

    std::vector<uint64_t> keys_;
    std::vector<double> values_;
    std::vector<uint32_t> stamps_;  // slot i is in use when stamps_[i] == stamp_
    uint32_t stamp_ = 1;
    size_t mask_ = 0;
    size_t size_ = 0;
};

LatticeValueTable& LatticeTable() {
    thread_local LatticeValueTable table;
    return table;
}

// Recent leaf term lists of the tree being built (LGOctree::MakeLeaf), by hash: a
// direct-mapped cache per thread, like the lattice table.
class LeafListCache {
  public:
    struct Entry {
        uint32_t first, count;  // a range of the tree's term array; count kNone: unused
    };
    static constexpr uint32_t kNone = 0xffffffffu;
    void Clear() { entries_.fill({0, kNone}); }
    Entry& Slot(uint64_t hash) { return entries_[(hash ^ (hash >> 29)) % entries_.size()]; }

  private:
    std::array<Entry, 64> entries_;
};

LeafListCache& LeafLists() {
    thread_local LeafListCache cache;
    return cache;
}

}  // namespace

OctreeHeuristics OctreeHeuristics::Kb89() {
    OctreeHeuristics s;
    s.useValueRange = false;
    s.useHeuristic1bis = false;
    s.useHeuristic3bis = false;
    s.dRatio = -1;
    s.useHeuristic4 = false;
    s.useHeuristic5 = false;
    s.usePredominancePruning = false;
    s.useTest0bis = false;
    s.useTest2bis = false;
    return s;
}

LGOctree::LGOctree(LGOctree&&) noexcept = default;
LGOctree& LGOctree::operator=(LGOctree&&) noexcept = default;
LGOctree::~LGOctree() = default;

LGOctree::LGOctree(Field field, double threshold, const Bounds3& box,
                   const OctreeSettings& settings, int ownTerm, LazyCellStore* lazy)
    : field_(std::move(field)),
      threshold_(threshold),
      ownTerm_(ownTerm),
      box_(box),
      settings_(settings) {
    if (box_.IsEmpty()) return;
    const Vec3 extent = box_.Extent();
    leafPadding_ = kLeafBoxPadding * std::max({extent.x, extent.y, extent.z});
    if (lazy) {
        lazy_ = std::make_unique<LazyTree>();
        lazy_->store = lazy;
        std::vector<int32_t> terms;
        field_.TermsMeeting(box_.Padded(leafPadding_), field_.Rows(), terms);
        FieldBound fb;
        const Decision decision =
            Decide(box_, 0, {0, 0, 0}, terms, fb, [&](const Vec3& p, LatticePoint) {
                return field_.Value(p, terms);
            });
        const ChildPlan root{0, box_, decision, fb.L, fb.G, &terms};
        FillLazyBlock(lazy_->root, {&root, 1});
        if (lazy_->root.classes & 1) leafBox_ = box_.Padded(leafPadding_);
        return;
    }
    LatticeTable().Clear();
    // Build into this thread's reusable arrays (no regrowth per tree), then keep copies of
    // exactly the nodes built (no spare capacity).
    thread_local std::vector<Ref> nodeScratch;
    thread_local std::vector<BuildLeaf> leafScratch;
    thread_local std::vector<int32_t> termScratch;
    nodeScratch.clear();
    leafScratch.clear();
    LeafLists().Clear();
    termScratch.clear();
    thread_local std::vector<std::vector<int32_t>> cellTermScratch;
    if (cellTermScratch.size() < static_cast<size_t>(settings_.maxDepth) + 1) {
        cellTermScratch.resize(static_cast<size_t>(settings_.maxDepth) + 1);
    }
    nodes_.swap(nodeScratch);
    buildLeaves_.swap(leafScratch);
    terms_.swap(termScratch);
    cellTerms_.swap(cellTermScratch);
    root_ = Build(box_, 0, {0, 0, 0}, field_.Rows());
    nodes_.swap(nodeScratch);
    buildLeaves_.swap(leafScratch);
    terms_.swap(termScratch);
    cellTerms_.swap(cellTermScratch);
    nodes_.assign(nodeScratch.begin(), nodeScratch.end());
    leaves_.reserve(leafScratch.size());
    for (const BuildLeaf& leaf : leafScratch) {
        leaves_.push_back({UpperFloat(leaf.L), UpperFloat(leaf.G), leaf.firstTerm, leaf.termCount});
    }
    terms_.assign(termScratch.begin(), termScratch.end());
    ExtendLeafBox(root_, box_);
    if (!leafBox_.IsEmpty()) leafBox_ = leafBox_.Padded(leafPadding_);
    if (degraded_) {
        Report(Severity::Warn, {},
               "implicit octree: memory budget of %zu bytes reached; some cells stop above "
               "depth %d (slower, still exact)",
               settings_.memoryBudget, settings_.maxDepth);
    }
}

// During the build the leaves are in buildLeaves_, afterwards in leaves_ (one of the two is
// empty); either way each costs a final Leaf.
std::size_t LGOctree::MemoryBytes() const {
    if (lazy_) return lazy_->root.Bytes() + lazy_->bytes.load(std::memory_order_relaxed);
    return nodes_.size() * sizeof(Ref) +
           (leaves_.size() + buildLeaves_.size()) * sizeof(Leaf) + terms_.size() * sizeof(int32_t);
}

int LGOctree::InternalCount() const {
    return lazy_ ? static_cast<int>((lazy_->root.classes >> 16) & 1) : internalCount_;
}

int LGOctree::LeafCount() const {
    if (!lazy_) return static_cast<int>(leaves_.size());
    const uint32_t classes = lazy_->root.classes;
    return static_cast<int>(classes & 1 & ~(classes >> 16));
}

bool LGOctree::Degraded() const {
    return lazy_ ? lazy_->degraded.load(std::memory_order_relaxed) : degraded_;
}

float UpperFloat(double x) {
    if (!(x <= std::numeric_limits<float>::max())) return std::numeric_limits<float>::infinity();
    return FloatAtOrAbove(x);
}

// False when some other term's smallest value over the box exceeds the own term's largest
// (strictly, so even a tie won by the lower index is impossible). Rows missing from `terms`
// are 0 over the box; so is the own term when missing (then any positive term excludes).
bool LGOctree::OwnMayPredominate(std::span<const int32_t> terms,
                                 const std::vector<TermValueRange>& ranges) const {
    double ownHi = 0;
    for (size_t k = 0; k < terms.size(); ++k) {
        if (terms[k] == ownTerm_) ownHi = ranges[k].hi;
    }
    for (size_t k = 0; k < terms.size(); ++k) {
        if (terms[k] != ownTerm_ && ranges[k].lo > ownHi) return false;
    }
    return true;
}

bool LGOctree::OwnExcluded(const Bounds3& box, std::span<const int32_t> terms) const {
    if (ownTerm_ < 0 || !settings_.usePredominancePruning) return false;
    double ownLo, ownHi;
    field_.TermRangeAtRayTime(ownTerm_, box, ownLo, ownHi);
    const double limit = ownHi + kExclusionMargin * std::abs(ownHi);
    for (const int j : terms) {
        if (j == ownTerm_) continue;
        double lo, hi;
        field_.TermRangeAtRayTime(j, box, lo, hi);
        if (lo - kExclusionMargin * std::abs(lo) > limit) return true;
    }
    return false;
}

LGOctree::Ref LGOctree::ChildRef(Ref node, int child) const {
    const uint32_t classes = static_cast<uint32_t>(nodes_[node]);
    if (!((classes >> child) & 1)) return (classes >> (8 + child)) & 1 ? kFullRef : kEmptyRef;
    return nodes_[node + 1 + std::popcount(classes & ((1u << child) - 1))];
}

LGOctree::Ref LGOctree::PushInternal(const Ref (&children)[8]) {
    const Ref self = static_cast<Ref>(nodes_.size());
    uint32_t classes = 0;
    for (int i = 0; i < 8; ++i) {
        if (children[i] >= 0 || children[i] <= kFirstLeafRef) {
            classes |= 1u << i;
        } else if (children[i] == kFullRef) {
            classes |= 1u << (8 + i);
        }
    }
    nodes_.push_back(static_cast<Ref>(classes));
    for (const Ref r : children) {
        if (r >= 0 || r <= kFirstLeafRef) nodes_.push_back(r);
    }
    ++internalCount_;
    return self;
}

LGOctree::Ref LGOctree::MakeLeaf(const Bounds3& box, double L, double G,
                                 std::span<const int32_t> terms) {
    std::size_t first = terms_.size();
    field_.ActiveTerms(box.Padded(leafPadding_), terms, terms_);
    const std::size_t count = terms_.size() - first;
    // Share an equal list made before: look it up by a hash of the list in a small
    // direct-mapped cache of recent lists. An entry may be stale (its range truncated by a
    // merge, or since overwritten), so it is used only when its range exists and its
    // entries are equal.
    uint64_t hash = count;
    for (std::size_t i = first; i < terms_.size(); ++i) {
        hash = (hash ^ static_cast<uint64_t>(terms_[i])) * 0x100000001b3ULL;  // FNV-1a step
    }
    LeafListCache::Entry& cached = LeafLists().Slot(hash);
    if (cached.count == count && cached.first + count <= first &&
        std::equal(terms_.begin() + first, terms_.end(), terms_.begin() + cached.first)) {
        terms_.resize(first);
        first = cached.first;
    } else {
        cached = {static_cast<uint32_t>(first), static_cast<uint32_t>(count)};
    }
    buildLeaves_.push_back({L, G, static_cast<uint32_t>(first), static_cast<uint32_t>(count)});
    return kFirstLeafRef - static_cast<Ref>(buildLeaves_.size() - 1);
}

void LGOctree::ExtendLeafBox(Ref ref, const Bounds3& box) {
    if (ref <= kFirstLeafRef) {
        leafBox_.Extend(box);
    } else if (ref >= 0) {
        for (int i = 0; i < 8; ++i) ExtendLeafBox(ChildRef(ref, i), ChildBox(box, i));
    }
}

double LGOctree::LatticeValue(const Vec3& p, LatticePoint q, std::span<const int32_t> terms) {
    const uint64_t key = (uint64_t{q.x} << 42) | (uint64_t{q.y} << 21) | uint64_t{q.z};
    double* slot = LatticeTable().Find(key);
    if (!slot) slot = LatticeTable().Insert(key, field_.Value(p, terms));
    return *slot;
}

// g's range at `centre` over the shutter for a moving field (g = F − T there being `gc` at
// the current time); {gc, gc} for a static one. The range lies within the cell's, so when
// that is within ±b·L of T heuristic 1 cannot fire: {0, 0}, without the evaluation.
std::pair<double, double> LGOctree::CentreRangeOverShutter(const Vec3& centre,
                                                          std::span<const int32_t> terms,
                                                          double gc, const FieldBound& fb,
                                                          double b) const {
    if (!field_.Motion()) return {gc, gc};
    if (!(std::max(fb.valueMax - threshold_, threshold_ - fb.valueMin) > b * fb.L)) {
        return {0, 0};
    }
    double lo = gc, hi = gc;
    field_.ValueRangeAt(centre, terms, lo, hi);
    return {lo - threshold_, hi - threshold_};
}

template <class Value>
LGOctree::Decision LGOctree::Decide(const Bounds3& box, int depth, LatticePoint low,
                                    std::span<const int32_t> terms, FieldBound& fb,
                                    Value&& value) const {
    const OctreeCounters& c = Counters();
    Count(c.cellsBuilt);
    const OctreeSettings& s = settings_;
    const bool predominance = s.usePredominancePruning && ownTerm_ >= 0;
    thread_local std::vector<TermValueRange> termRanges;  // the predominance test's
    fb = field_.Bound(box, terms, predominance ? &termRanges : nullptr);
    if (s.useValueRange) {
        if (fb.valueMin > threshold_) {
            Count(c.rangeFired);
            return Decision::Full;
        }
        if (fb.valueMax < threshold_) {
            Count(c.rangeFired);
            return Decision::Empty;
        }
    }
    if (predominance && !OwnMayPredominate(terms, termRanges)) {
        Count(c.patchFired);
        return Decision::Empty;
    }
    Vec3 centre = box.Center();
    double b = HalfDiagonal(box);
    // The cell's edge in lattice steps (>= 2 down to maxDepth), and its centre's point.
    const uint32_t edge = 1u << (s.maxDepth + 1 - depth), half = edge / 2;
    // A moving field's centre value varies within the shutter: heuristic 1 then needs its
    // range there beyond b·L (so the cell's range must be; {0, 0} never fires), and no test
    // uses it at one time (1bis off, 3 leaves anyway).
    const bool moving = field_.Motion() != nullptr;
    const double gc = moving ? 0 : value(centre, {low.x + half, low.y + half, low.z + half}) -
                                       threshold_;
    const auto [gcLo, gcHi] = CentreRangeOverShutter(centre, terms, gc, fb, b);
    const Decision mark = (moving ? gcLo : gc) > 0 ? Decision::Full : Decision::Empty;
    if (s.useHeuristic1 && (gcLo > b * fb.L || gcHi < -b * fb.L)) {
        Count(c.h1Fired);
        return mark;
    }
    // 1bis needs |g(C)| > b‖∇F(C)‖ + ½b²G >= ½b²G: test that first, so the gradient is
    // evaluated only where the heuristic can fire.
    if (s.useHeuristic1bis && !moving && std::isfinite(fb.G) &&
        std::abs(gc) > 0.5 * b * b * fb.G) {
        double grad = Length(field_.Gradient(centre, terms));
        if (std::abs(gc) > b * grad + 0.5 * b * b * fb.G) {
            Count(c.h1bisFired);
            return mark;
        }
    }
    if (depth >= s.maxDepth) {
        Count(c.h2Fired);
        return Decision::Leaf;
    }
    // Heuristics 3 and 3bis stop early only where G is finite: a leaf with infinite G would
    // leave the search no curvature bound at all.
    if (depth >= s.minDepth && std::isfinite(fb.G)) {
        if (s.useHeuristic3) {
            // A moving field's surface may cross the cell at some time of the shutter
            // whenever its range straddles T, as it does here: a leaf, as if it crossed.
            bool anyIn = gc > 0 || moving, anyOut = gc <= 0 || moving;
            for (int i = 0; i < 8 && !(anyIn && anyOut); ++i) {
                LatticePoint q{low.x + ((i & 1) ? edge : 0), low.y + ((i & 2) ? edge : 0),
                               low.z + ((i & 4) ? edge : 0)};
                bool in = value(box.Corner(i), q) > threshold_;
                anyIn |= in;
                anyOut |= !in;
            }
            if (anyIn && anyOut) {
                Count(c.h3Fired);
                return Decision::Leaf;
            }
        }
        if (s.useHeuristic3bis && fb.minDistance > 0 && b / fb.minDistance < s.dRatio) {
            Count(c.h3bisFired);
            return Decision::Leaf;
        }
    }
    return Decision::Subdivide;
}

LGOctree::Ref LGOctree::Build(const Bounds3& box, int depth, LatticePoint low,
                              std::span<const int32_t> parentTerms) {
    const OctreeCounters& c = Counters();
    const OctreeSettings& s = settings_;
    // This cell's rows, in a per-depth slot of cellTerms_ (children fill deeper slots, so
    // the list stays valid until this call returns; the slots exist before the build).
    std::vector<int32_t>& terms = cellTerms_[depth];
    terms.clear();
    field_.TermsMeeting(box.Padded(leafPadding_), parentTerms, terms);
    FieldBound fb;
    switch (Decide(box, depth, low, terms, fb, [&](const Vec3& p, LatticePoint q) {
        return LatticeValue(p, q, terms);
    })) {
        case Decision::Empty:
            return kEmptyRef;
        case Decision::Full:
            return kFullRef;
        case Decision::Leaf:
            return MakeLeaf(box, fb.L, fb.G, terms);
        case Decision::Subdivide:
            break;
    }
    const uint32_t half = 1u << (s.maxDepth - depth);
    if (MemoryBytes() + kMaxInternalBytes + 8 * sizeof(Leaf) > s.memoryBudget ||
        LatticeTable().LiveBytes() > s.memoryBudget) {
        Count(c.budgetFired);
        degraded_ = true;
        return MakeLeaf(box, fb.L, fb.G, terms);
    }
    // Subdivide. Children's nodes are allocated after this point, so a merge below can
    // release them by truncating the three arrays (stack-like allocation; a leaf shares only
    // lists made before it, so truncated lists serve only truncated leaves).
    std::size_t nodeMark = nodes_.size(), leafMark = buildLeaves_.size(),
                termMark = terms_.size();
    const int internalMark = internalCount_;
    Ref children[8];
    for (int i = 0; i < 8; ++i) {
        LatticePoint q{low.x + ((i & 1) ? half : 0), low.y + ((i & 2) ? half : 0),
                       low.z + ((i & 4) ? half : 0)};
        children[i] = Build(ChildBox(box, i), depth + 1, q, terms);
    }
    bool allEmpty = true, allFull = true, allLeaves = true;
    double maxChildG = 0;
    for (Ref r : children) {
        allEmpty &= r == kEmptyRef;
        allFull &= r == kFullRef;
        allLeaves &= r <= kFirstLeafRef;
        if (r <= kFirstLeafRef) {
            maxChildG = std::max(maxChildG, buildLeaves_[kFirstLeafRef - r].G);
        }
    }
    if (s.useHeuristic4 && (allEmpty || allFull)) {
        Count(c.h4Fired);
        nodes_.resize(nodeMark);
        internalCount_ = internalMark;
        buildLeaves_.resize(leafMark);
        terms_.resize(termMark);
        return allEmpty ? kEmptyRef : kFullRef;
    }
    if (s.useHeuristic5 && allLeaves && maxChildG >= s.h5GRatio * fb.G) {
        Count(c.h5Fired);
        nodes_.resize(nodeMark);
        internalCount_ = internalMark;
        buildLeaves_.resize(leafMark);
        terms_.resize(termMark);
        return MakeLeaf(box, fb.L, fb.G, terms);
    }
    return PushInternal(children);
}

void LGOctree::ExpandLazy(LazyBlock& block, const Bounds3& box, int depth, LatticePoint low,
                          std::span<const int32_t> terms) const {
    const uint32_t half = 1u << (settings_.maxDepth - depth);
    // The values at the 27 points of the cell's 3×3×3 lattice (its children's corners),
    // each evaluated once; a point off it (a child's centre) is evaluated where asked.
    // Every list holding the rows meeting the point gives the same bits (Field::Value).
    double grid[27];
    bool known[27] = {};
    auto offset = [half](uint32_t from, uint32_t to) {
        const uint32_t d = to - from;
        return d == 0 ? 0 : d == half ? 1 : d == 2 * half ? 2 : -1;
    };
    thread_local std::array<std::vector<int32_t>, 8> childTerms;
    std::array<ChildPlan, 8> plans;
    for (int i = 0; i < 8; ++i) {
        const Bounds3 sub = ChildBox(box, i);
        const LatticePoint q{low.x + ((i & 1) ? half : 0), low.y + ((i & 2) ? half : 0),
                             low.z + ((i & 4) ? half : 0)};
        std::vector<int32_t>& list = childTerms[static_cast<size_t>(i)];
        list.clear();
        field_.TermsMeeting(sub.Padded(leafPadding_), terms, list);
        FieldBound fb;
        const Decision decision =
            Decide(sub, depth + 1, q, list, fb, [&](const Vec3& p, LatticePoint point) {
                const int x = offset(low.x, point.x), y = offset(low.y, point.y),
                          z = offset(low.z, point.z);
                if (x < 0 || y < 0 || z < 0) return field_.Value(p, list);
                const int k = x + 3 * y + 9 * z;
                if (!known[k]) {
                    grid[k] = field_.Value(p, list);
                    known[k] = true;
                }
                return grid[k];
            });
        plans[static_cast<size_t>(i)] = {i, sub, decision, fb.L, fb.G, &list};
    }
    FillLazyBlock(block, plans);
}

LGOctree BuildPatchOctree(const Patch& patch, double threshold, const OctreeSettings& settings,
                          LazyCellStore* lazy) {
    return LGOctree(patch.GetField(), threshold, patch.Box(), settings, patch.Own(), lazy);
}

}  // namespace rs
