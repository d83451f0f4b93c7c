// Layer 6 of the implicit module: Kalra–Barr LG octrees with Gascuel's improvements
// (Kalra & Barr, SIGGRAPH '89; Gascuel 1995 §3.1–3.4), and the guaranteed first-root
// search along a ray.
//
// Notation: g(p) = F(p) − T for the octree's field F and threshold T (inside: g > 0). For a
// cell with centre C and half diagonal b, Bound(cell) gives L >= |∇F| and G >= |second
// directional derivative of F| (field.h). Along a ray p(t) = o + t·d the parametric bounds
// are Lt = L|d| and Gt = G|d|², since d/dt = d·∇ and d²/dt² = dᵀ∇²F d.
//
// Build heuristics (in the order applied; each but 2 switchable in OctreeHeuristics):
//   range  (ours)  Bound's value interval excludes T  → Full/Empty. Sound: it contains F.
//   1      |g(C)| > bL → Full/Empty by the sign of g(C). Sound: |F(p) − F(C)| <= L|p − C|.
//   1bis   |g(C)| > b‖∇F(C)‖ + ½b²G → Full/Empty. Sound: Taylor along C→p with integral
//          remainder, F being C¹ and piecewise C² (the paper omits the ½: conservative).
//   2      depth == maxDepth → leaf (always on: it guarantees termination).
//   3      depth >= minDepth, G finite, and the signs of g at the 8 corners and the centre
//          differ → leaf.
//   3bis   depth >= minDepth, G finite, and b/min < dRatio → leaf, min being the smallest
//          distance to an active skeleton (subdividing a cell small compared with its
//          distance to the skeletons barely tightens L and G). dRatio = −1 never fires
//          (≈ KB89).
//   budget when the node memory would exceed memoryBudget, or the lattice values computed
//          by the build (including those of cells later merged by heuristic 4) would take
//          more than memoryBudget → leaf, and one warning per tree.
//   patch  (Gascuel §3.4, patch octrees only) some neighbour's smallest contribution over
//          the cell exceeds the own term's largest → Empty: no root in the cell can be
//          accepted, so the tree only covers the part of the patch box where the own
//          skeleton may predominate. Tested right after the value-range test.
//   4      after subdivision: all eight children Full (or all Empty) → parent likewise.
//   5      after subdivision: all children leaves and max child G >= h5GRatio·G → one
//          leaf with the parent's L and G (still valid on every child).
// Empty/Full cells take no memory (two bits in their parent's record); leaves store L and G (rounded
// up to floats) and their active terms (the terms not identically 0 in the cell), which the search sums alone.
//
// Per-cell mode (LazyCellStore; README.md, "Per-cell trees"): the same heuristics but 4 and
// 5, applied to a cell's eight children when a ray first reaches it, and kept under the
// object's budget. Under automatic accuracy a ray searches an inner cell no longer than
// descentFootprints of its footprint widths as one leaf (the cell's L and G are bounds on
// it), so cells far smaller than a pixel are never built.
//
// Per-leaf search over [tA, tB] (λ = tB − tA, gA, gB the end values, tm the midpoint), in
// their sound forms (research note §4.2); each but 2 switchable:
//   0bis   gA == 0 → candidate root tA.
//   1      same sign and |gA| + |gB| > Lt·λ → no root (g would have to fall to 0 and
//          climb back within slope Lt).
//   2      λ <= minimum width → the floor policy below (always on: termination).
//   2bis   same sign: chord bound min(|gA|, |gB|) > Gt·λ²/8 → no root (g stays within
//          Gtλ²/8 of its chord); then, with the directional derivative g'(tm),
//          |g'(tm)| > Gt·λ/2 → g monotone → no root.
//   3      |g'(tm)| > Gt·λ/2 → g' ≠ 0 on [tA, tB] (|g'(t) − g'(tm)| <= Gt|t − tm|), at most
//          one root, present iff the ends' signs differ: solve with Ridders, or report no
//          root when the signs agree (the same conclusion as 2bis's second part).
//          Otherwise split at tm and search the near half first.
// Where G is too weak for test 3 ever to fire (Gt·λ > 2Lt; e.g. infinite because the leaf
// touches a linear kernel's skeleton, a circle's axis or a polyline's kinks), each segment
// is bounded by Field::Bound over its own box (a per-segment bound in the spirit of segment
// tracing), finite once the segment avoids those points; tests needing G are skipped while
// it stays infinite.
// Floor (minimum width / tangency) policy, identical for every ray: a segment no longer
// than minWidth whose ends differ in sign yields its root (Ridders to the tolerance);
// otherwise g is evaluated at its midpoint and a sign opposite to the ends' reports the
// midpoint as a root (the ray enters and leaves within the segment); otherwise no root is
// reported and the segment is counted as unresolved. So a ray is reported as hitting only
// where a sign change was observed, and tangential contacts shorter than minWidth that rise
// above the threshold by less than Gt·minWidth²/32 (the chord bound on each half) are
// misses.
//
// Guarantee: with sound bounds, every root returned lies within `tolerance` of a sign
// change of g along the ray, and no sign change earlier along the ray (in leaves wider
// than the floor) is skipped.
#pragma once

#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "libcommon/constants.h"
#include "libcommon/limits.h"
#include "libcommon/ray.h"
#include "libobj/implicit/patch.h"
#include "libobj/implicit/root_finding.h"

namespace rs {

// How an LG octree is built and searched beyond the root accuracy: depth limits, Gascuel's
// and Kalra & Barr's build heuristics, the memory budget, and the search tests. These are
// the octree methods' own settings (patches, kb89); RootSearchSettings are every method's.
struct OctreeHeuristics {
    // Octree depth limits (Gascuel's tables: max depth 4–10, min depth 3). minDepth is the
    // "deep enough" of heuristics 3 and 3bis. Measured on 60 blended point skeletons (the
    // research note's §12 parameters, 20 000 rays): min depth 2 / 3 / 4 / 5 gave 131 / 62 /
    // 31 / 20 field plus gradient evaluations per ray for 1 / 4 / 10 / 29 KB of tree per
    // patch and 1 / 1.5 / 4 / 13 ms of build per patch. Whole renders decide, though: on the
    // benchmark's point chains (bench/implicit.sh, 512×512, one thread) min depth 3 against
    // 4 took 0.52 / 1.04 / 2.59 s against 0.84 / 1.15 / 4.78 s for N = 10 / 100 / 1000,
    // because every patch pays the build and most pixels see few patches; 3 is also the
    // paper's setting.
    int maxDepth = 6;
    int minDepth = 3;
    bool useValueRange = true;
    bool useHeuristic1 = true;
    bool useHeuristic1bis = true;
    bool useHeuristic3 = true;
    bool useHeuristic3bis = true;
    double dRatio = 2;  // Gascuel's value; −1 disables 3bis
    bool useHeuristic4 = true;
    bool useHeuristic5 = true;
    bool usePredominancePruning = true;  // the "patch" rule; needs an own term
    double h5GRatio = 0.9;  // "not too different": children keep >= 90 % of the parent's G
    // Node memory per tree (internal nodes 4 bytes plus 4 per child that is neither Empty
    // nor Full, leaves 16 bytes plus 4 bytes per entry of their active-term lists). A cell
    // subdivides only while one more internal node (at most 36 bytes) and eight leaves fit,
    // lists not counted, so the tree may overshoot the budget by that much (164 bytes) plus
    // eight lists per level of the path being built. The build's table of lattice values
    // (LatticeValueBytes per value) is held to the same budget: cells that heuristic 4
    // merges cost it nothing in nodes, so without this bound a tree whose cells mostly
    // merge (a long thin skeleton) could take unbounded time and memory to build.
    std::size_t memoryBudget = static_cast<std::size_t>(Limits().octreeBytes);

    // Per-cell trees under automatic accuracy: a ray with a footprint descends into an
    // inner cell only while the cell's longest edge exceeds this many footprint widths;
    // below, it searches the cell as one leaf. 0: always descend.
    double descentFootprints = 8;
    // The LG search tests (lg_search.cpp).
    bool useTest0bis = true;
    bool useTest1 = true;
    bool useTest2bis = true;
    bool useTest3 = true;

    // Kalra & Barr 1989 as summarised by Gascuel: heuristics 1, 2, 3 and tests 1, 2, 3 only.
    // The per-segment bounds stay on: KB89's G lacked the |f'|/r term, so it was never
    // infinite, while ours is near linear-kernel skeletons and without them the search
    // would split such spans down to the floor.
    static OctreeHeuristics Kb89();
};

// What one tree is built with: the object's root search settings and the method's
// heuristics.
struct OctreeSettings : RootSearchSettings, OctreeHeuristics {
    OctreeSettings() = default;
    OctreeSettings(const RootSearchSettings& search, const OctreeHeuristics& heuristics)
        : RootSearchSettings(search), OctreeHeuristics(heuristics) {}
};

// A leaf met by a ray: the parametric span [tEnter, tExit], the leaf's bounds and its
// active terms (Field::ActiveTerms of the leaf cell padded by the tree's leaf padding: every
// other term is exactly 0 on the ray piece, so sums over these give the full field's bits).
struct LeafSpan {
    double tEnter = 0, tExit = 0;
    double L = 0, G = 0;
    std::span<const int32_t> terms;
};

enum class CellClass { Empty, Full, Leaf };

// Told of the cells the per-cell lazy trees of an object expand (LazyCellStore).
class CellExpansionObserver {
  public:
    virtual ~CellExpansionObserver() = default;
    // Runs `expand` (one cell's expansion into its children) and attributes its work.
    virtual void Expand(const std::function<void()>& expand) const = 0;
    // `cells` cells taking `bytes` bytes were kept (published in a tree).
    virtual void Kept(uint64_t cells, uint64_t bytes) const = 0;
};

// Shared by the per-cell lazy trees of one object (LGOctree's lazy mode): the memory budget
// of the cells they keep, and an optional observer of their expansions. Must outlive the
// trees. Thread-safe.
class LazyCellStore {
  public:
    explicit LazyCellStore(std::size_t budget, const CellExpansionObserver* observer = nullptr)
        : budget_(budget), observer_(observer) {}
    // Takes `bytes` from the budget; false (taking nothing) when they do not fit.
    bool Reserve(std::size_t bytes);
    void Release(std::size_t bytes) { used_.fetch_sub(bytes, std::memory_order_relaxed); }
    std::size_t UsedBytes() const { return used_.load(std::memory_order_relaxed); }
    // True once some expansion did not fit the budget.
    bool Degraded() const { return degraded_.load(std::memory_order_relaxed); }
    const CellExpansionObserver* Observer() const { return observer_; }

  private:
    std::size_t budget_;
    std::atomic<std::size_t> used_{0};
    std::atomic<bool> degraded_{false};
    const CellExpansionObserver* observer_;
};

class LGOctree {
  public:
    // Builds the tree of g = F − T over `box` (the copy shares the field's term table).
    // With ownTerm >= 0 the tree serves a patch whose own term is the field's term (row)
    // `ownTerm`: cells where that term cannot predominate are marked Empty (the "patch"
    // rule), so FirstRoot then only finds roots an `accept` predominance test could keep.
    //
    // With `lazy` (per-cell mode), only the root cell is classified here: an inner cell's
    // eight children are classified and kept the first time a search or Classify reaches it,
    // by whichever thread, lock-free (racing threads compute the same children and one
    // publishes them). A cell's content is a function of the cell alone (its box, depth and
    // the rows meeting it), so every result is the same whatever the order and threads of
    // the rays: the heuristics are those of the whole build but the merges (4 and 5), which
    // need the children, and the budget is `lazy`'s, shared by the object's trees; children
    // that do not fit it are computed for the ray at hand and dropped after (slower, the
    // same results).
    LGOctree(Field field, double threshold, const Bounds3& box, const OctreeSettings& settings,
             int ownTerm = -1, LazyCellStore* lazy = nullptr);
    LGOctree(LGOctree&&) noexcept;
    LGOctree& operator=(LGOctree&&) noexcept;
    ~LGOctree();

    const Field& GetField() const { return field_; }
    double Threshold() const { return threshold_; }
    const Bounds3& Box() const { return box_; }
    // A box containing every leaf cell (empty when the tree has no leaf): FirstRoot returns
    // nothing at once for rays that miss it.
    const Bounds3& LeafBox() const { return leafBox_; }
    const OctreeSettings& Settings() const { return settings_; }

    // Calls `visit` for every leaf the ray meets within [tMin, tMax], in ray order, with
    // the span clipped to [tMin, tMax]; stops early when `visit` returns true.
    void Traverse(const Ray& ray, double tMin, double tMax,
                  const std::function<bool(const LeafSpan&)>& visit) const;

    // The class of the cell containing p (Empty outside the root box). Full: g > 0 in the
    // cell; Empty: g < 0 in the cell, or (patch rule) no predominant point in it.
    CellClass Classify(const Vec3& p) const;

    // True when the tree serves a patch (ownTerm >= 0, patch rule on) and some other term's
    // smallest value over `box` exceeds the own term's largest by a relative margin of
    // kExclusionMargin: no point of the box can pass a predominance test. Ridders' method
    // is skipped on a ray segment whose box is excluded: every point the solver could
    // return lies in that box (the ray's coordinates are monotone in t under rounding),
    // where `accept` would reject it, so the result is the same without the solve. The
    // margin covers the rounding of TermRange against TermValue (a few ulps). Only the rows
    // in `terms` are tested as excluding terms: a list holding every row that may be
    // non-zero somewhere in the box (the field's rows, or a leaf's active list for a box in
    // the leaf) gives the same answer as all rows, since a term that is 0 over the whole box
    // has a TermRange whose lower end is at most 0 (its upper distance bound is >= R).
    bool OwnExcluded(const Bounds3& box, std::span<const int32_t> terms) const;
    static constexpr double kExclusionMargin = 1e-9;

    // What a root filter says of a candidate root at t, known to be within uncertaintyT
    // (parameter units) of a true sign change of g.
    enum class RootVerdict {
        Reject,
        Accept,
        // Acceptable only within the uncertainty: FirstRoot narrows the root's bracket to
        // the rounding of t (kFineRootTolerance) and asks again; a root still undecided
        // there is kept, and its refined t returned.
        Undecided,
    };
    using RootFilter = std::function<RootVerdict(double t, double uncertaintyT)>;
    // The bracket width FirstRoot narrows an undecided root to, relative to |t|: a few ulps.
    static constexpr double kFineRootTolerance = 4 * 0x1p-52;

    // The first t in (tMin, tMax) where g changes sign along the ray (to the tolerance) and
    // `accept` does not reject; rejected roots are skipped and the search continues past
    // them.
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax,
                                    const RootFilter& accept = {}) const;

    // The cells and memory of a whole tree; in per-cell mode, those kept at construction
    // (the root cell; the store's observer is told of the cells kept later).
    int InternalCount() const;
    int LeafCount() const;
    std::size_t MemoryBytes() const;
    // True when the memory budget stopped subdivision somewhere (per-cell mode: when the
    // store's budget refused some cells).
    bool Degraded() const;
    bool PerCell() const { return lazy_ != nullptr; }

  private:
    // Child reference: >= 0 internal node (its record's offset in nodes_); kEmptyRef,
    // kFullRef; <= kFirstLeafRef leaf.
    using Ref = int32_t;
    static constexpr Ref kEmptyRef = -1, kFullRef = -2, kFirstLeafRef = -3;
    // An internal node is a record in nodes_: a header word whose bit i (0–7) says that
    // child i is live (an internal node or a leaf) and bit 8 + i that a child that is not
    // live is Full (else Empty), then the references of the live children in child order.
    // Empty and Full children take no word: a record takes 4 bytes plus 4 per live child
    // (at most kMaxInternalBytes), against 32 bytes for eight references.
    static constexpr std::size_t kMaxInternalBytes = 9 * sizeof(Ref);
    // The reference of child `child` of internal node `node`.
    Ref ChildRef(Ref node, int child) const;
    // Appends the record of an internal node with these children; returns its reference.
    Ref PushInternal(const Ref (&children)[8]);
    // A leaf's bounds and its active terms, terms_[firstTerm, firstTerm + termCount). L and
    // G are the cell's bounds rounded up to floats (UpperFloat): still bounds, and a leaf
    // takes 16 bytes instead of 24.
    struct Leaf {
        float L, G;
        uint32_t firstTerm, termCount;
    };
    // A leaf while its tree is built, with the exact bounds (heuristic 5 compares them).
    struct BuildLeaf {
        double L, G;
        uint32_t firstTerm, termCount;
    };

    // A cell's low corner on the lattice of corners and centres of the deepest cells: the
    // root spans 2^(maxDepth + 1) steps per axis (at most 2^17, so each index fits 21 bits).
    struct LatticePoint {
        uint32_t x, y, z;
    };
    // What the heuristics range, patch, 1, 1bis, 2, 3 and 3bis (in that order) make of cell
    // `box` at `depth` (low corner `low`), whose TermsMeeting list is `terms`; fb receives
    // the cell's bound. value(p, q) gives F at lattice point q (coordinates p). Defined and
    // used in the .cpp only.
    enum class Decision { Empty, Full, Leaf, Subdivide };
    // g's range at a cell centre over the shutter, given g there now (gc): {gc, gc} unless
    // the field moves (heuristic 1 of a moving field); {0, 0}, which never fires heuristic
    // 1, when the cell's bounds `fb` (half diagonal b) show it cannot fire.
    std::pair<double, double> CentreRangeOverShutter(const Vec3& centre,
                                                     std::span<const int32_t> terms, double gc,
                                                     const FieldBound& fb, double b) const;
    template <class Value>
    Decision Decide(const Bounds3& box, int depth, LatticePoint low,
                    std::span<const int32_t> terms, FieldBound& fb, Value&& value) const;
    // Builds cell `box`. `parentTerms` holds every row of the field meeting the parent cell
    // padded by leafPadding_ (Field::TermsMeeting; the field's rows at the root): the cell
    // keeps those meeting its own padded box, and its bound, field values and leaf list sum
    // only these. Every other row's support box misses the cell, so it is skipped by the
    // full sums and bound too: the results are bit-identical, at the cost of the terms near
    // the cell instead of all the patch's terms.
    Ref Build(const Bounds3& box, int depth, LatticePoint low,
              std::span<const int32_t> parentTerms);
    // F at a lattice point (p its coordinates, a corner or the centre of a cell whose
    // TermsMeeting list is `terms`), evaluated once per build: neighbouring cells share
    // corners, and a cell's centre is its children's shared corner. Every cell derives a
    // given lattice point's coordinates by the same midpoint operations, so the cached value
    // is exactly what a fresh evaluation would return.
    double LatticeValue(const Vec3& p, LatticePoint q, std::span<const int32_t> terms);
    // `ranges[k]` is the value range of row terms[k] over the cell (Field::Bound); `terms`
    // holds every row of the field meeting the cell.
    bool OwnMayPredominate(std::span<const int32_t> terms,
                           const std::vector<TermValueRange>& ranges) const;
    // A leaf for cell `box`, with the active terms of the cell padded by leafPadding_
    // (shared with an equal list made before when the list cache finds one), taken from the
    // cell's TermsMeeting list `terms`.
    Ref MakeLeaf(const Bounds3& box, double L, double G, std::span<const int32_t> terms);
    // Extends leafBox_ by the cells of the leaves below `ref` (cell `box`).
    void ExtendLeafBox(Ref ref, const Bounds3& box);
    // The leaves below `ref` (cell `box`) met by the ray within [t0, t1], in ray order.
    // Visitor: bool(const LeafSpan&), true to stop. Defined and used in the .cpp only.
    template <class Visitor>
    bool Visit(Ref ref, const Bounds3& box, const Ray& ray, double t0, double t1,
               Visitor& visit) const;

    // Per-cell mode. A block holds the eight children of an expanded inner cell: the
    // classes, then the live ones (leaves and inner cells) in child order, each with its
    // bounds (rounded up to floats) and its list in the block's terms: a leaf's active
    // terms, an inner cell's TermsMeeting list (its children's parent list).
    struct LazyBlock;
    struct LazyCell {
        float L = 0, G = 0;
        uint32_t firstTerm = 0, termCount = 0;
        // An inner cell's children once expanded and kept; owned by the block.
        mutable std::atomic<LazyBlock*> children{nullptr};
    };
    struct LazyBlock {
        // Bit i: child i live; 8 + i: child i, not live, is Full (else Empty); 16 + i: child
        // i, live, is an inner cell (else a leaf).
        uint32_t classes = 0;
        std::unique_ptr<LazyCell[]> cells;
        std::vector<int32_t> terms;
        ~LazyBlock();
        std::size_t Bytes() const;
        const LazyCell& Cell(int child) const {
            return cells[std::popcount(classes & ((1u << child) - 1))];
        }
        std::span<const int32_t> Terms(const LazyCell& cell) const {
            return {terms.data() + cell.firstTerm, cell.termCount};
        }
    };
    // The tree of per-cell mode: the root cell as child 0 of a block of its own.
    struct LazyTree {
        LazyCellStore* store;
        LazyBlock root;
        std::atomic<std::size_t> bytes{0};  // of the blocks kept, released to the store
        std::atomic<bool> degraded{false};
        ~LazyTree() { store->Release(bytes.load()); }
    };
    // A child of a block being made: its index, box, class and bound, and its TermsMeeting
    // list.
    struct ChildPlan {
        int child;
        Bounds3 box;
        Decision decision;
        double L, G;
        const std::vector<int32_t>* terms;
    };
    // Fills an empty block with these children (in increasing child order).
    void FillLazyBlock(LazyBlock& block, std::span<const ChildPlan> plans) const;
    // Classifies the eight children of cell (box, depth, low) whose TermsMeeting list is
    // `terms` into `block`.
    void ExpandLazy(LazyBlock& block, const Bounds3& box, int depth, LatticePoint low,
                    std::span<const int32_t> terms) const;
    // The children of inner cell `cell` of `owner` (cell box, depth, low): the kept ones, else
    // computed now, kept when `keep` and the budget allows, else held in `scratch` (and
    // `keep` turns false: their own children are not kept either).
    const LazyBlock& Children(const LazyBlock& owner, const LazyCell& cell, const Bounds3& box,
                              int depth, LatticePoint low, bool& keep,
                              std::unique_ptr<LazyBlock>& scratch) const;
    // The leaves below child `child` of `owner` (cell box, depth, low) met by the ray within
    // [t0, t1], in ray order, expanding inner cells on the way (kept while `keep`); with
    // `byFootprint`, an inner cell DescendInto refuses is visited as a leaf (its bounds and
    // its TermsMeeting list, a superset of its active terms).
    template <class Visitor>
    bool VisitLazy(const LazyBlock& owner, int child, const Bounds3& box, int depth,
                   LatticePoint low, bool keep, bool byFootprint, const Ray& ray, double t0,
                   double t1, Visitor& visit) const;
    // True when the ray's span [t0, t1] in cell `box` should descend into the cell's
    // children: the cell's longest edge exceeds descentFootprints ray footprints (their
    // smaller width on the span).
    bool DescendInto(const Bounds3& box, const Ray& ray, double t0, double t1) const;
    // Visits the tree, whichever its mode.
    template <class Visitor>
    bool VisitRoot(const Ray& ray, double t0, double t1, bool byFootprint,
                   Visitor& visit) const;

    Field field_;
    double threshold_;
    int ownTerm_;
    Bounds3 box_;
    // The union of the leaf cells, padded by kLeafBoxPadding of the root box's longest edge
    // (empty without leaves). Only leaves hold roots, and the search visits a leaf only for
    // a ray piece whose midpoint lies in that cell up to the rounding of the ray's
    // parameters (relative 1e-16, far below the padding), so a ray missing this box meets
    // no leaf: FirstRoot stops there, with the result a full walk would give.
    Bounds3 leafBox_;
    static constexpr double kLeafBoxPadding = 1e-6;
    double leafPadding_ = 0;  // kLeafBoxPadding × the root box's longest edge
    OctreeSettings settings_;
    std::vector<Ref> nodes_;  // the internal nodes' records
    int internalCount_ = 0;
    std::vector<Leaf> leaves_;
    std::vector<BuildLeaf> buildLeaves_;  // the leaves during the build (then empty)
    std::vector<int32_t> terms_;  // the leaves' active-term lists
    Ref root_ = kEmptyRef;
    bool degraded_ = false;
    std::unique_ptr<LazyTree> lazy_;  // per-cell mode only
    // Build scratch: the TermsMeeting list of the cell being built at each depth (a
    // thread's reused arrays, held only during the build).
    std::vector<std::vector<int32_t>> cellTerms_;
};

// The smallest float not below x, for x >= 0 (+infinity above the float range, and for
// x = +infinity): a bound stored as float stays a bound.
float UpperFloat(double x);

// The statistics counter of Ridders iterations (every octree search counts into it), so
// callers can attribute iterations to an object by differences of ThreadCount. The build
// counters are all named "Implicit octree ...".
CounterId RiddersIterationCounter();
// Every counter of this file (the build heuristics' firings and the search tests), in
// registration order, so callers can attribute them (object_stats.h).
std::vector<CounterId> OctreeCounterIds();

// The octree of a patch: its field over its box, with the patch rule for its own term;
// per cell with `lazy`.
LGOctree BuildPatchOctree(const Patch& patch, double threshold, const OctreeSettings& settings,
                          LazyCellStore* lazy = nullptr);

// The first root of a patch along the ray in (tMin, tMax): a root of the patch field where
// the patch's own term predominates (patch.h), continuing past rejected roots. The seam
// rule (README.md, "Patches"): a root where the own term predominates only within the
// root's positional uncertainty (Patch::PredominatesNear) is narrowed to the rounding of t
// and tested again there, and kept if it still passes within that rounding, so a root on
// the seam between two patches is never rejected by both. `octree` must come from
// BuildPatchOctree(patch, ...).
std::optional<double> PatchFirstRoot(const Patch& patch, const LGOctree& octree,
                                     const Ray& ray, double tMin, double tMax);

}  // namespace rs
