// The LG octree's search along a ray (lg_octree.h, "Per-leaf search"): the traversal of
// the tree front to back and the per-leaf tests, and the patch search with its seam rule.
#include "libobj/implicit/lg_octree.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "libobj/implicit/lg_octree_detail.h"
#include "libobj/implicit/root_finding.h"

namespace rs {

using lg_octree_detail::ChildBox;
using lg_octree_detail::ChildIndexOf;
using lg_octree_detail::Counters;
using lg_octree_detail::Inside;

namespace {

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
            // those points (research note §5's local bounds), at the ray's time for a moving
            // field. Both bounds hold on [a, b]; keep the smaller L and the segment's G.
            Count(Counters().segmentBounds);
            const Bounds3 box(ray_.At(a), ray_.At(b));
            const FieldBound local = tree_.GetField().BoundAtRayTime(box);
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

// Splits the ray's span [t0, t1] in `box` where it crosses the three mid-planes and calls
// visit(child, childBox, a, b) for each piece, in ray order, whose child's bit is set in
// `live` (the child found from the piece's midpoint); stops early when visit returns true.
template <class Visit>
bool ForEachLivePiece(const Bounds3& box, uint32_t live, const Ray& ray, double t0, double t1,
                      Visit&& visit) {
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
        if (!((live >> child) & 1)) continue;  // Empty or Full
        Bounds3 sub;  // ChildBox(box, child), from the centre already at hand
        sub.lo = {(child & 1) ? c.x : box.lo.x, (child & 2) ? c.y : box.lo.y,
                  (child & 4) ? c.z : box.lo.z};
        sub.hi = {(child & 1) ? box.hi.x : c.x, (child & 2) ? box.hi.y : c.y,
                  (child & 4) ? box.hi.z : c.z};
        if (visit(child, sub, a, b)) return true;
    }
    return false;
}

}  // namespace

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
    return ForEachLivePiece(box, classes, ray, t0, t1,
                            [&](int child, const Bounds3& sub, double a, double b) {
                                const uint32_t before = classes & ((1u << child) - 1);
                                const Ref next = nodes_[ref + 1 + std::popcount(before)];
                                return Visit(next, sub, ray, a, b, visit);
                            });
}

template <class Visitor>
bool LGOctree::VisitLazy(const LazyBlock& owner, int child, const Bounds3& box, int depth,
                         LatticePoint low, bool keep, bool byFootprint, const Ray& ray,
                         double t0, double t1, Visitor& visit) const {
    const LazyCell& cell = owner.Cell(child);
    const bool inner = (owner.classes >> (16 + child)) & 1;
    if (!inner || (byFootprint && !DescendInto(box, ray, t0, t1))) {
        return visit(LeafSpan{t0, t1, cell.L, cell.G, owner.Terms(cell)});
    }
    std::unique_ptr<LazyBlock> scratch;
    const LazyBlock& block = Children(owner, cell, box, depth, low, keep, scratch);
    const uint32_t half = 1u << (settings_.maxDepth - depth);
    return ForEachLivePiece(box, block.classes, ray, t0, t1,
                            [&](int i, const Bounds3& sub, double a, double b) {
                                const LatticePoint q{low.x + ((i & 1) ? half : 0),
                                                     low.y + ((i & 2) ? half : 0),
                                                     low.z + ((i & 4) ? half : 0)};
                                return VisitLazy(block, i, sub, depth + 1, q, keep, byFootprint,
                                                 ray, a, b, visit);
                            });
}

bool LGOctree::DescendInto(const Bounds3& box, const Ray& ray, double t0, double t1) const {
    // The footprint is affine in t: its smaller end value is its minimum on the span.
    const double width =
        std::min(ray.footprintWidth + ray.footprintSpread * t0,
                 ray.footprintWidth + ray.footprintSpread * t1) * Length(ray.dir);
    const Vec3 e = box.Extent();
    return std::max({e.x, e.y, e.z}) > settings_.descentFootprints * width;
}

template <class Visitor>
bool LGOctree::VisitRoot(const Ray& ray, double t0, double t1, bool byFootprint,
                         Visitor& visit) const {
    if (!lazy_) return Visit(root_, box_, ray, t0, t1, visit);
    if (!(lazy_->root.classes & 1)) return false;
    return VisitLazy(lazy_->root, 0, box_, 0, {0, 0, 0}, true, byFootprint, ray, t0, t1, visit);
}

void LGOctree::Traverse(const Ray& ray, double tMin, double tMax,
                        const std::function<bool(const LeafSpan&)>& visit) const {
    if (box_.IsEmpty()) return;
    double t0 = tMin, t1 = tMax;
    if (!box_.ClipRay(ray, t0, t1)) return;
    VisitRoot(ray, t0, t1, false, visit);
}

CellClass LGOctree::Classify(const Vec3& p) const {
    if (box_.IsEmpty() || !box_.Contains(p)) return CellClass::Empty;
    if (lazy_) {
        const LazyBlock* owner = &lazy_->root;
        std::unique_ptr<LazyBlock> held;  // owner, when not kept
        int child = 0, depth = 0;
        Bounds3 box = box_;
        LatticePoint low{0, 0, 0};
        bool keep = true;
        while ((owner->classes >> (16 + child)) & 1) {
            std::unique_ptr<LazyBlock> scratch;
            const LazyBlock& block =
                Children(*owner, owner->Cell(child), box, depth, low, keep, scratch);
            const uint32_t half = 1u << (settings_.maxDepth - depth);
            child = ChildIndexOf(box, p);
            box = ChildBox(box, child);
            low = {low.x + ((child & 1) ? half : 0), low.y + ((child & 2) ? half : 0),
                   low.z + ((child & 4) ? half : 0)};
            ++depth;
            owner = &block;
            if (scratch) held = std::move(scratch);
        }
        if ((owner->classes >> child) & 1) return CellClass::Leaf;
        return (owner->classes >> (8 + child)) & 1 ? CellClass::Full : CellClass::Empty;
    }
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
    const bool byFootprint = settings_.autoTolerance && settings_.descentFootprints > 0 &&
                             (ray.footprintWidth != 0 || ray.footprintSpread != 0);
    VisitRoot(ray, t0, t1, byFootprint, leaf);
    return search.result;
}

std::optional<double> PatchFirstRoot(const Patch& patch, const LGOctree& octree,
                                     const Ray& ray, double tMin, double tMax) {
    return octree.FirstRoot(ray, tMin, tMax, [&](double t, double uncertaintyT) {
        using Verdict = LGOctree::RootVerdict;
        // The computed point lies within uncertaintyT·|d| of the true root's point, plus
        // the rounding of o + t·d (a few ulps of |o| + |t|·|d|).
        const double dirLength = Length(ray.dir);
        const double uncertainty =
            uncertaintyT * dirLength +
            Patch::kPositionRounding * (Length(ray.origin) + std::abs(t) * dirLength);
        switch (patch.PredominanceAt(ray.At(t), uncertainty)) {
            case Patch::Predominance::Strict:
                return Verdict::Accept;
            case Patch::Predominance::Near:
                return Verdict::Undecided;
            default:
                return Verdict::Reject;
        }
    });
}

}  // namespace rs
