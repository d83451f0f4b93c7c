#include "libobj/implicit/lg_octree.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "libcommon/error.h"
#include "libcommon/stats.h"
#include "libobj/implicit/root_finding.h"

namespace rs {

namespace {

struct OctreeCounters {
    CounterId cellsBuilt = RegisterCounter("Implicit octree cells built");
    CounterId rangeFired = RegisterCounter("Implicit octree value-range prunes");
    CounterId patchFired = RegisterCounter("Implicit octree patch-rule prunes");
    CounterId h1Fired = RegisterCounter("Implicit octree heuristic 1 prunes");
    CounterId h1bisFired = RegisterCounter("Implicit octree heuristic 1bis prunes");
    CounterId h2Fired = RegisterCounter("Implicit octree heuristic 2 leaves");
    CounterId h3Fired = RegisterCounter("Implicit octree heuristic 3 leaves");
    CounterId h3bisFired = RegisterCounter("Implicit octree heuristic 3bis leaves");
    CounterId budgetFired = RegisterCounter("Implicit octree memory-budget leaves");
    CounterId h4Fired = RegisterCounter("Implicit octree heuristic 4 merges");
    CounterId h5Fired = RegisterCounter("Implicit octree heuristic 5 merges");
    CounterId cellsVisited = RegisterCounter("Implicit cells visited");
    CounterId test0bis = RegisterCounter("Implicit test 0bis roots");
    CounterId test1 = RegisterCounter("Implicit test 1 (L) rejections");
    CounterId test2bisChord = RegisterCounter("Implicit test 2bis chord rejections");
    CounterId monotoneNoRoot = RegisterCounter("Implicit monotone same-sign rejections");
    CounterId test3 = RegisterCounter("Implicit test 3 single-root intervals");
    CounterId splits = RegisterCounter("Implicit interval splits");
    CounterId segmentBounds = RegisterCounter("Implicit segment bounds");
    CounterId ridders = RegisterCounter("Implicit Ridders calls");
    CounterId riddersIterations = RegisterCounter("Implicit Ridders iterations");
    CounterId floorRoots = RegisterCounter("Implicit minimum-width roots");
    CounterId unresolved = RegisterCounter("Implicit unresolved intervals");
    CounterId rejectedRoots = RegisterCounter("Implicit roots rejected by predominance");
    CounterId excludedSegments =
        RegisterCounter("Implicit single-root segments excluded by predominance");
};

const OctreeCounters& Counters() {
    static const OctreeCounters counters;
    return counters;
}

}  // namespace

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

bool Inside(double g) { return g > 0; }

Bounds3 ChildBox(const Bounds3& box, int i) {
    Vec3 c = box.Center();
    Bounds3 b;
    b.lo = {(i & 1) ? c.x : box.lo.x, (i & 2) ? c.y : box.lo.y, (i & 4) ? c.z : box.lo.z};
    b.hi = {(i & 1) ? box.hi.x : c.x, (i & 2) ? box.hi.y : c.y, (i & 4) ? box.hi.z : c.z};
    return b;
}

int ChildIndexOf(const Bounds3& box, const Vec3& p) {
    Vec3 c = box.Center();
    return (p.x >= c.x ? 1 : 0) | (p.y >= c.y ? 2 : 0) | (p.z >= c.z ? 4 : 0);
}

// The recursive per-leaf search of one ray (see the header for the tests).
class RaySearch {
  public:
    RaySearch(const LGOctree& tree, const Ray& ray, double tMin, double tMax,
              const LGOctree::RootFilter& accept)
        : tree_(tree),
          s_(tree.Settings()),
          ray_(ray),
          tMin_(tMin),
          tMax_(tMax),
          accept_(accept),
          dirLength_(Length(ray.dir)),
          fixedTolT_(s_.tolerance / dirLength_),
          fixedFloorT_(std::max(s_.minWidth, s_.tolerance) / dirLength_),
          adaptive_(s_.autoTolerance && (ray.footprintWidth != 0 || ray.footprintSpread != 0)),
          tolT_(fixedTolT_),
          floorT_(fixedFloorT_) {}

    // g at ray parameter t of the current leaf span, summing its active terms only.
    double G(double t) const {
        return tree_.GetField().Value(ray_.At(t), terms_) - tree_.Threshold();
    }

    // Searches one leaf span; true when an accepted root was found (in result).
    bool Leaf(const LeafSpan& span) {
        Count(Counters().cellsVisited);
        double a = span.tEnter, b = span.tExit;
        if (!(b >= a)) return false;
        terms_ = span.terms;
        if (adaptive_) {
            // The footprint is affine in t, so its smaller end value is its minimum here.
            const double width = std::min(ray_.footprintWidth + ray_.footprintSpread * a,
                                          ray_.footprintWidth + ray_.footprintSpread * b);
            const double tol = std::min(s_.footprintFraction * width, s_.autoToleranceCap);
            tolT_ = std::max(tol, fixedTolT_);
            floorT_ = std::max(tol, fixedFloorT_);
        }
        double ga = a == cachedT_ ? cachedG_ : G(a);
        double gb = G(b);
        cachedT_ = b;
        cachedG_ = gb;
        return Search(a, ga, b, gb, span.L * dirLength_, span.G * dirLength_ * dirLength_);
    }

    std::optional<double> result;

  private:
    // A sign change of g in [a, b], with its end values.
    struct Bracket {
        double a, ga, b, gb;
    };

    // A candidate root at t, within uncertaintyT of a sign change of g in `bracket`, or with
    // no bracket to narrow (an exact zero of g).
    bool Candidate(double t, double uncertaintyT, const Bracket* bracket) {
        if (!(t > tMin_ && t < tMax_)) return false;
        using Verdict = LGOctree::RootVerdict;
        Verdict verdict = accept_ ? accept_(t, uncertaintyT) : Verdict::Accept;
        if (verdict == Verdict::Undecided && bracket) {
            const double fineT = LGOctree::kFineRootTolerance *
                                 std::max(std::abs(bracket->a), std::abs(bracket->b));
            auto f = [this](double s) { return G(s); };
            std::optional<RootResult> fine = RiddersRoot(f, bracket->a, bracket->ga, bracket->b,
                                                         bracket->gb, fineT, kFineIterations);
            if (fine && fine->root > tMin_ && fine->root < tMax_) {
                t = fine->root;
                verdict = accept_(t, fineT);
            }
        }
        if (verdict == Verdict::Reject) {
            Count(Counters().rejectedRoots);
            return false;
        }
        result = t;
        return true;
    }
    // Ridders' iterations allowed to narrow a tolerance-wide bracket to a few ulps: it at
    // least halves the bracket each iteration, and 2^-60 covers any tolerance down to the
    // ulps of t (it converges in a handful on simple roots).
    static constexpr int kFineIterations = 60;

    bool Ridders(double a, double ga, double b, double gb) {
        if (tree_.OwnExcluded(Bounds3(ray_.At(a), ray_.At(b)), terms_)) {
            Count(Counters().excludedSegments);
            return false;
        }
        Count(Counters().ridders);
        auto f = [this](double t) { return G(t); };
        std::optional<RootResult> r = RiddersRoot(f, a, ga, b, gb, tolT_, s_.maxRiddersIterations);
        if (!r) {
            // Only when maxRiddersIterations is set too low for the bracket: finish by
            // bisection rather than lose the root.
            r = BisectRoot(f, a, ga, b, gb, tolT_, 2000);
            if (!r) return false;
        }
        Count(Counters().riddersIterations, r->iterations);
        // Both solvers stop on a bracket of width <= tolT_ around a sign change
        // (root_finding.h), or on an exact zero.
        const Bracket bracket{a, ga, b, gb};
        return Candidate(r->root, tolT_, &bracket);
    }

    bool Floor(double a, double ga, double b, double gb) {
        if (Inside(ga) != Inside(gb) || ga == 0 || gb == 0) {
            Count(Counters().floorRoots);
            return Ridders(a, ga, b, gb);
        }
        double m = 0.5 * (a + b);
        double gm = G(m);
        if (Inside(gm) != Inside(ga) || gm == 0) {
            Count(Counters().floorRoots);
            // g changes class in [a, m], so m is within m − a of a sign change.
            const Bracket bracket{a, ga, m, gm};
            return Candidate(m, m - a, &bracket);
        }
        Count(Counters().unresolved);
        return false;
    }

    // lt, gt: the parametric bounds Lt, Gt valid on [a, b].
    bool Search(double a, double ga, double b, double gb, double lt, double gt) {
        double lambda = b - a;
        if (s_.useTest0bis && ga == 0) {
            Count(Counters().test0bis);
            if (Candidate(a, 0, nullptr)) return true;
        }
        if (lambda <= floorT_) return Floor(a, ga, b, gb);
        if (!(gt * lambda <= 2 * lt)) {
            // G is too weak for test 3 ever to fire here (|g'| <= Lt < Gt·λ/2), typically
            // because the leaf touches a point where F is not C² (a linear kernel's
            // skeleton, a circle's axis, a polyline's kink) or comes very close to one:
            // bound the segment's own box instead, which is finite once the segment avoids
            // those points (research note §5's local bounds). Both bounds hold on [a, b];
            // keep the smaller L and the segment's G.
            Count(Counters().segmentBounds);
            FieldBound local = tree_.GetField().Bound(Bounds3(ray_.At(a), ray_.At(b)));
            lt = std::min(lt, local.L * dirLength_);
            gt = std::min(gt, local.G * dirLength_ * dirLength_);
        }
        bool signChange = Inside(ga) != Inside(gb) || gb == 0;
        if (!signChange) {
            if (s_.useTest1 && std::abs(ga) + std::abs(gb) > lt * lambda) {
                Count(Counters().test1);
                return false;
            }
            if (s_.useTest2bis && std::min(std::abs(ga), std::abs(gb)) > gt * lambda * lambda / 8) {
                Count(Counters().test2bisChord);
                return false;
            }
        }
        double m = 0.5 * (a + b);
        // g(m) comes with the gradient where that is evaluated (one pass over the terms; the
        // split below needs it whenever the tests do not conclude).
        double gm = 0;
        bool haveGm = false;
        if ((s_.useTest3 || (s_.useTest2bis && !signChange)) && std::isfinite(gt)) {
            Vec3 gradient;
            gm = tree_.GetField().ValueAndGradient(ray_.At(m), terms_, gradient) -
                 tree_.Threshold();
            haveGm = true;
            double slope = Dot(gradient, ray_.dir);
            if (std::abs(slope) > gt * lambda / 2) {
                if (!signChange) {
                    Count(Counters().monotoneNoRoot);
                    return false;
                }
                if (s_.useTest3) {
                    Count(Counters().test3);
                    return Ridders(a, ga, b, gb);
                }
            }
        }
        Count(Counters().splits);
        if (!haveGm) gm = G(m);
        return Search(a, ga, m, gm, lt, gt) || Search(m, gm, b, gb, lt, gt);
    }

    const LGOctree& tree_;
    const OctreeSettings& s_;
    Ray ray_;
    double tMin_, tMax_;
    const LGOctree::RootFilter& accept_;
    double dirLength_;
    double fixedTolT_, fixedFloorT_;  // the fixed tolerance and floor, in units of t
    bool adaptive_;                   // automatic accuracy on a ray with a footprint
    double tolT_, floorT_;            // those of the current leaf span
    double cachedT_ = std::nan(""), cachedG_ = 0;
    // The current leaf's active terms. A cached end value computed with the previous
    // leaf's list is still exact: both lists hold every term non-zero at the shared end.
    std::span<const int32_t> terms_;
};

}  // namespace

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

OctreeSettings OctreeSettings::Kb89() {
    OctreeSettings s;
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

LGOctree::LGOctree(Field field, double threshold, const Bounds3& box,
                   const OctreeSettings& settings, int ownTerm)
    : field_(std::move(field)),
      threshold_(threshold),
      ownTerm_(ownTerm),
      box_(box),
      settings_(settings) {
    if (box_.IsEmpty()) return;
    LatticeTable().Clear();
    // Build into this thread's reusable arrays (no regrowth per tree), then keep copies of
    // exactly the nodes built (no spare capacity).
    const Vec3 extent = box_.Extent();
    leafPadding_ = kLeafBoxPadding * std::max({extent.x, extent.y, extent.z});
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
    std::vector<TermValueRange>().swap(termRanges_);
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
    return nodes_.size() * sizeof(Ref) +
           (leaves_.size() + buildLeaves_.size()) * sizeof(Leaf) + terms_.size() * sizeof(int32_t);
}

float UpperFloat(double x) {
    if (!(x <= std::numeric_limits<float>::max())) return std::numeric_limits<float>::infinity();
    const float f = static_cast<float>(x);  // the nearest float, possibly below x
    return f < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
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
    field_.TermRange(ownTerm_, box, ownLo, ownHi);
    const double limit = ownHi + kExclusionMargin * std::abs(ownHi);
    for (const int j : terms) {
        if (j == ownTerm_) continue;
        double lo, hi;
        field_.TermRange(j, box, lo, hi);
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

LGOctree::Ref LGOctree::Build(const Bounds3& box, int depth, LatticePoint low,
                              std::span<const int32_t> parentTerms) {
    const OctreeCounters& c = Counters();
    Count(c.cellsBuilt);
    const OctreeSettings& s = settings_;
    // This cell's rows, in a per-depth slot of cellTerms_ (children fill deeper slots, so
    // the list stays valid until this call returns; the slots exist before the build).
    std::vector<int32_t>& terms = cellTerms_[depth];
    terms.clear();
    field_.TermsMeeting(box.Padded(leafPadding_), parentTerms, terms);
    const bool predominance = s.usePredominancePruning && ownTerm_ >= 0;
    FieldBound fb = field_.Bound(box, terms, predominance ? &termRanges_ : nullptr);
    if (s.useValueRange) {
        if (fb.valueMin > threshold_) {
            Count(c.rangeFired);
            return kFullRef;
        }
        if (fb.valueMax < threshold_) {
            Count(c.rangeFired);
            return kEmptyRef;
        }
    }
    if (predominance && !OwnMayPredominate(terms, termRanges_)) {
        Count(c.patchFired);
        return kEmptyRef;
    }
    Vec3 centre = box.Center();
    double b = HalfDiagonal(box);
    // The cell's edge in lattice steps (>= 2 down to maxDepth), and its centre's point.
    const uint32_t edge = 1u << (s.maxDepth + 1 - depth), half = edge / 2;
    double gc =
        LatticeValue(centre, {low.x + half, low.y + half, low.z + half}, terms) - threshold_;
    Ref mark = gc > 0 ? kFullRef : kEmptyRef;
    if (s.useHeuristic1 && std::abs(gc) > b * fb.L) {
        Count(c.h1Fired);
        return mark;
    }
    // 1bis needs |g(C)| > b‖∇F(C)‖ + ½b²G >= ½b²G: test that first, so the gradient is
    // evaluated only where the heuristic can fire.
    if (s.useHeuristic1bis && std::isfinite(fb.G) && std::abs(gc) > 0.5 * b * b * fb.G) {
        double grad = Length(field_.Gradient(centre, terms));
        if (std::abs(gc) > b * grad + 0.5 * b * b * fb.G) {
            Count(c.h1bisFired);
            return mark;
        }
    }
    if (depth >= s.maxDepth) {
        Count(c.h2Fired);
        return MakeLeaf(box, fb.L, fb.G, terms);
    }
    // Heuristics 3 and 3bis stop early only where G is finite: a leaf with infinite G would
    // leave the search no curvature bound at all.
    if (depth >= s.minDepth && std::isfinite(fb.G)) {
        if (s.useHeuristic3) {
            bool anyIn = gc > 0, anyOut = gc <= 0;
            for (int i = 0; i < 8 && !(anyIn && anyOut); ++i) {
                LatticePoint q{low.x + ((i & 1) ? edge : 0), low.y + ((i & 2) ? edge : 0),
                               low.z + ((i & 4) ? edge : 0)};
                bool in = LatticeValue(box.Corner(i), q, terms) > threshold_;
                anyIn |= in;
                anyOut |= !in;
            }
            if (anyIn && anyOut) {
                Count(c.h3Fired);
                return MakeLeaf(box, fb.L, fb.G, terms);
            }
        }
        if (s.useHeuristic3bis && fb.minDistance > 0 && b / fb.minDistance < s.dRatio) {
            Count(c.h3bisFired);
            return MakeLeaf(box, fb.L, fb.G, terms);
        }
    }
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

template <class Visitor>
bool LGOctree::Visit(Ref ref, const Bounds3& box, const Ray& ray, double t0, double t1,
                     Visitor& visit) const {
    if (ref == kEmptyRef || ref == kFullRef) return false;
    if (ref <= kFirstLeafRef) {
        const Leaf& leaf = leaves_[kFirstLeafRef - ref];
        return visit(LeafSpan{t0, t1, leaf.L, leaf.G,
                              {terms_.data() + leaf.firstTerm, leaf.termCount}});
    }
    const uint32_t classes = static_cast<uint32_t>(nodes_[ref]);
    // Split [t0, t1] where the ray crosses the three mid-planes; each piece lies in one
    // child, found from the piece's midpoint. Empty and Full children are skipped before
    // their boxes are formed.
    const Vec3 c = box.Center();
    double cuts[5];
    int n = 0;
    cuts[n++] = t0;
    for (int axis = 0; axis < 3; ++axis) {
        if (ray.dir[axis] == 0) continue;
        double t = (c[axis] - ray.origin[axis]) / ray.dir[axis];
        if (t > t0 && t < t1) cuts[n++] = t;
    }
    for (int i = 2; i < n; ++i) {  // insertion sort of the (at most three) plane crossings
        for (int j = i; j > 1 && cuts[j] < cuts[j - 1]; --j) std::swap(cuts[j], cuts[j - 1]);
    }
    cuts[n++] = t1;
    for (int i = 0; i + 1 < n; ++i) {
        double a = cuts[i], b = cuts[i + 1];
        if (b <= a && n > 2) continue;
        const Vec3 p = ray.At(0.5 * (a + b));
        const int child = (p.x >= c.x ? 1 : 0) | (p.y >= c.y ? 2 : 0) | (p.z >= c.z ? 4 : 0);
        if (!((classes >> child) & 1)) continue;  // Empty or Full
        const Ref next = nodes_[ref + 1 + std::popcount(classes & ((1u << child) - 1))];
        Bounds3 sub;  // ChildBox(box, child), from the centre already at hand
        sub.lo = {(child & 1) ? c.x : box.lo.x, (child & 2) ? c.y : box.lo.y,
                  (child & 4) ? c.z : box.lo.z};
        sub.hi = {(child & 1) ? box.hi.x : c.x, (child & 2) ? box.hi.y : c.y,
                  (child & 4) ? box.hi.z : c.z};
        if (Visit(next, sub, ray, a, b, visit)) return true;
    }
    return false;
}

void LGOctree::Traverse(const Ray& ray, double tMin, double tMax,
                        const std::function<bool(const LeafSpan&)>& visit) const {
    if (box_.IsEmpty()) return;
    double t0 = tMin, t1 = tMax;
    if (!box_.ClipRay(ray, t0, t1)) return;
    Visit(root_, box_, ray, t0, t1, visit);
}

CellClass LGOctree::Classify(const Vec3& p) const {
    if (box_.IsEmpty() || !box_.Contains(p)) return CellClass::Empty;
    Ref ref = root_;
    Bounds3 box = box_;
    while (ref >= 0) {
        int child = ChildIndexOf(box, p);
        box = ChildBox(box, child);
        ref = ChildRef(ref, child);
    }
    if (ref == kEmptyRef) return CellClass::Empty;
    if (ref == kFullRef) return CellClass::Full;
    return CellClass::Leaf;
}

std::optional<double> LGOctree::FirstRoot(const Ray& ray, double tMin, double tMax,
                                          const RootFilter& accept) const {
    if (LengthSquared(ray.dir) == 0 || !(tMax > tMin)) return std::nullopt;
    // The leaf box first: most rays reaching a patch's box miss its leaves. A ray meeting
    // the leaf box only outside the root box meets no leaf either way (leaves lie in it).
    double l0 = tMin, l1 = tMax;
    if (leafBox_.IsEmpty() || !leafBox_.ClipRay(ray, l0, l1)) return std::nullopt;
    double t0 = tMin, t1 = tMax;
    if (!box_.ClipRay(ray, t0, t1)) return std::nullopt;
    RaySearch search(*this, ray, tMin, tMax, accept);
    auto leaf = [&search](const LeafSpan& span) { return search.Leaf(span); };
    Visit(root_, box_, ray, t0, t1, leaf);
    return search.result;
}

LGOctree BuildPatchOctree(const Patch& patch, double threshold, const OctreeSettings& settings) {
    return LGOctree(patch.GetField(), threshold, patch.Box(), settings, patch.Own());
}

std::optional<double> PatchFirstRoot(const Patch& patch, const LGOctree& octree,
                                     const Ray& ray, double tMin, double tMax) {
    const double dirLength = Length(ray.dir);
    const double originLength = Length(ray.origin);
    return octree.FirstRoot(ray, tMin, tMax, [&](double t, double uncertaintyT) {
        using Verdict = LGOctree::RootVerdict;
        const Vec3 p = ray.At(t);
        if (patch.Predominates(p)) return Verdict::Accept;
        // The computed point lies within uncertaintyT·|d| of the true root's point, plus
        // the rounding of o + t·d (a few ulps of |o| + |t|·|d|).
        const double uncertainty =
            uncertaintyT * dirLength +
            Patch::kPositionRounding * (originLength + std::abs(t) * dirLength);
        return patch.PredominatesNear(p, uncertainty) ? Verdict::Undecided : Verdict::Reject;
    });
}

}  // namespace rs
