// A bounding volume hierarchy over a set of boxes, used by `list` to test only the children
// a ray can reach (the original tests every child of a list; the nearest hit is the same,
// because every child whose box meets the remaining ray segment is still tested), by the
// metaball sums of `blob` and `method polynomial` (metaball_sum.h), and by the implicit
// patches (one item per patch box).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "libcommon/bounds.h"
#include "libcommon/float_rounding.h"

namespace rs {

class BoundingVolumeHierarchy {
  public:
    enum class Split {
        // At the median centroid of the widest axis, until at most kLeafSize items remain.
        Median,
        // Where the surface-area heuristic (binned centroids, all three axes) expects the
        // fewest box and item tests for rays through the node; a node stays a leaf (of at
        // most kMaxSahLeaf items) when no split is expected to pay. Below kMaxSahDepth
        // levels it falls back to median splits, so the depth stays under 64. Only the wide
        // tree is kept (Traverse), for the scene's lists and grids.
        SurfaceArea,
    };
    // Builds over `boxes` (item i has box boxes[i]).
    void Build(const std::vector<Bounds3>& boxes, Split split = Split::Median);
    bool IsEmpty() const { return wideCount_ == 0; }
    // The surface-area estimate of the wide walk's work for a ray through the root box, in
    // units of one item visit: each wide node counts one (its four-box test), each leaf lane
    // its item count, both weighted by the chance that a random ray meeting the root box
    // meets theirs (area over the root's area). No segment shortening is assumed. 0 when
    // empty or when the root box has no area.
    double ExpectedCost() const { return expectedCost_; }

    // Calls visit(i) once for every item whose box meets the ray segment (tMin, tMax), nearer
    // boxes first (items sharing a leaf with such an item may be visited too: item boxes
    // are not tested one by one). visit returns true when it found a hit, and may then have
    // shrunk tMax;
    // later boxes are clipped against the shrunken segment. Returns whether any visit hit.
    // With kStopAtFirstHit the walk returns at the first visit that hits (occlusion), and
    // the boxes met at a node are visited in lane order, not sorted by entry (any blocker
    // answers the question).
    // Each item is visited at most once. The walk runs on the 4-wide nodes (see WideNode):
    // single-precision slab tests of four boxes at once, conservative (every item whose
    // double box meets the segment is visited; a few whose boxes pass within a relative
    // 2^-21 of it may be visited too, which cannot change a nearest hit).
    template <bool kStopAtFirstHit = false, class Visit>
    bool Traverse(const Ray& ray, double tMin, double& tMax, Visit&& visit) const {
        if (wideCount_ == 0) return false;
        FloatRay fr;
        if (!fr.Set(ray, scale_)) {
            // Beyond single precision's range: every item, in order.
            bool found = false;
            for (int item : items_) {
                if (!visit(item)) continue;
                if (kStopAtFirstHit) return true;
                found = true;
            }
            return found;
        }
        const float tMinF = FloatAtOrBelow(tMin);
        float tMaxF = FloatAtOrAbove(tMax);
        // The segment's ends in every lane, for the node tests.
        const Float4 tMinLanes = Splat(tMinF);
        Float4 tMaxLanes = Splat(tMaxF);
        // The stack never holds more than 3 entries per level plus 4 (see BuildWide).
        StackEntry stack[kStackSize];
        int top = 0;
        // The lane being visited (as WideNode's child, count): the root first.
        int ref = 0, count = 0;
        bool found = false;
        for (;;) {
            if (count > 0) {
                for (int i = 0; i < count; ++i) {
                    if (!visit(items_[ref + i])) continue;
                    if (kStopAtFirstHit) return true;
                    found = true;
                    tMaxF = FloatAtOrAbove(tMax);
                    tMaxLanes = Splat(tMaxF);
                }
            } else {
                const WideNode& node = wide_[ref];
                float tNear[4];
                const int hitMask = node.Clip(fr, tMinLanes, tMaxLanes, tNear);
                if (hitMask != 0 && (hitMask & (hitMask - 1)) == 0) {
                    // One lane met (the common case deep in the tree): it would be pushed
                    // and popped next, so it is visited without the trip.
                    const int k = __builtin_ctz(hitMask);
                    if (tNear[k] <= tMaxF) {
                        ref = node.child[k];
                        count = node.count[k];
                        continue;
                    }
                } else {
                    // Push the lanes met, farthest first, so the nearest is popped next.
                    const int first = top;
                    for (int mask = hitMask; mask != 0; mask &= mask - 1) {
                        const int k = __builtin_ctz(mask);
                        StackEntry e{node.child[k], node.count[k], tNear[k]};
                        int j = top++;
                        if (!kStopAtFirstHit)
                            for (; j > first && stack[j - 1].tNear < e.tNear; --j)
                                stack[j] = stack[j - 1];
                        stack[j] = e;
                    }
                }
            }
            // The next stacked lane whose box the (possibly shrunken) segment still reaches.
            for (;;) {
                if (top == 0) return found;
                const StackEntry& entry = stack[--top];
                if (entry.tNear <= tMaxF) {
                    ref = entry.ref;
                    count = entry.count;
                    break;
                }
            }
        }
    }

    // As Traverse (children by entry parameter, a node skipped once its entry lies beyond
    // the shrunken tMax), but on the binary nodes with exact double box clips, two children
    // at a time (median builds only: an SAH build keeps only the wide tree, and this visits
    // nothing): the walk the implicit patches' evaluation counts are defined by (the wide
    // walk's float entries can order two patches differently). Each box is clipped once,
    // when its parent is visited, and stacked with its entry `near`: the clip to
    // (tMin, tMax) with a smaller tMax at its turn succeeds exactly when near <= tMax (near
    // does not depend on the far end, and the slab exits already passed near). For items
    // that are expensive to visit (an implicit patch may build its octree), so that the
    // nearest ones come first.
    template <class Visit>
    bool TraverseInEntryOrder(const Ray& ray, double tMin, double& tMax, Visit&& visit) const {
        if (nodes_.empty()) return false;
        const Vec3 invDir{1 / ray.dir.x, 1 / ray.dir.y, 1 / ray.dir.z};
        struct Entry {
            int node;
            double near;
        };
        // Visiting a node replaces it by at most two children, so the stack never holds more
        // than the tree's depth + 1 < 64 entries (see Split).
        Entry stack[64];
        int top = 0;
        double near = tMin, far = tMax;
        if (nodes_[0].box.ClipSegment(ray, invDir, near, far)) stack[top++] = {0, near};
        bool found = false;
        while (top > 0) {
            const Entry entry = stack[--top];
            if (entry.near > tMax) continue;
            const Node& node = nodes_[entry.node];
            if (node.count > 0) {
                for (int i = 0; i < node.count; ++i) found |= visit(items_[node.first + i]);
                continue;
            }
            int a = entry.node + 1, b = node.right;
            double nearA = tMin, farA = tMax, nearB = tMin, farB = tMax;
            const bool hitA = nodes_[a].box.ClipSegment(ray, invDir, nearA, farA);
            const bool hitB = nodes_[b].box.ClipSegment(ray, invDir, nearB, farB);
            if (hitA && hitB && nearB < nearA) {
                std::swap(a, b);
                std::swap(nearA, nearB);
            }
            // The child entered first is pushed last, so it is visited next.
            if (hitA && hitB) stack[top++] = {b, nearB};
            if (hitA) stack[top++] = {a, nearA};
            else if (hitB) stack[top++] = {b, nearB};
        }
        return found;
    }

    // Calls visit(i) once for every item whose box contains p (and possibly others sharing
    // its leaf). Median builds only, as TraverseInEntryOrder.
    template <class Visit>
    void VisitContaining(const Vec3& p, Visit&& visit) const {
        if (nodes_.empty()) return;
        int stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!node.box.Contains(p)) continue;
            if (node.count > 0) {
                for (int i = 0; i < node.count; ++i) visit(items_[node.first + i]);
                continue;
            }
            // The stack never holds more entries than the tree's depth + 1 < 64 (see Split).
            stack[top++] = node.right;
            stack[top++] = static_cast<int>(&node - nodes_.data()) + 1;
        }
    }

  private:
    // Four floats operated on at once (GCC/Clang vector extension: SSE on x86-64).
    typedef float Float4 __attribute__((vector_size(16)));
    // A ray in single precision for WideNode::Clip. Each axis keeps two origins, shifted
    // along the axis by delta = 2^-21 (|o| + scale) in opposite directions: the near one
    // moved forward (so near-slab parameters only decrease), the far one backward. delta
    // exceeds the rounding of the origin to float and of the slab subtraction (scale bounds
    // the boxes' coordinates), so (plane − origin) errs only outward. Every figure is
    // broadcast to the four lanes once per ray, not once per node, and nearPlane[a] and
    // farPlane[a] index the WideNode::planes the ray enters and leaves axis a's slabs
    // through (a for the lows, 3 + a for the highs), so Clip picks its planes by index
    // rather than by a branch on the sign.
    struct FloatRay {
        Float4 nearOrigin[3], farOrigin[3], invDir[3];
        std::ptrdiff_t nearPlane[3], farPlane[3];
        // False when some figure leaves single precision's normal range (the caller then
        // visits every item).
        bool Set(const Ray& ray, double scale);
    };
    // Four children's boxes, rounded outward to float, structure of arrays so one slab
    // test covers the four lanes. child/count: count > 0 for a leaf lane, items_[child,
    // child + count); 0 for an interior lane, wide_[child]; an unused lane has an empty box
    // (low = +inf, high = -inf), which Clip never admits.
    struct WideNode {
        Float4 planes[6];  // planes[a]: the lanes' lows on axis a; planes[3 + a]: their highs
        int child[4], count[4];
        // Bit k set when lane k's box meets the segment (tMin, tMax), conservatively; its
        // entry parameter, lowered by the same margin, in tNear[k].
        int Clip(const FloatRay& ray, Float4 tMin, Float4 tMax, float tNear[4]) const;
    };
    struct StackEntry {
        int ref, count;  // as WideNode's child, count
        float tNear;
    };
    static constexpr int kStackSize = 3 * 64 + 4;
    // x in every lane.
    static Float4 Splat(float x) { return Float4{x, x, x, x}; }
    // Lane by lane, x where it is below (above) `bound`, else bound: a NaN in x leaves
    // bound as it was.
    static Float4 LaneMin(Float4 x, Float4 bound) { return x < bound ? x : bound; }
    static Float4 LaneMax(Float4 x, Float4 bound) { return x > bound ? x : bound; }
    // |x| in every lane (the sign bits cleared; a NaN stays a NaN).
    static Float4 Abs(Float4 x) {
        typedef int Int4 __attribute__((vector_size(16)));
        return (Float4)((Int4)x & 0x7fffffff);
    }

    static constexpr int kLeafSize = 2;
    static constexpr int kMaxSahLeaf = 4;
    // SAH levels; median levels below them add at most log2(items) < 32 more.
    static constexpr int kMaxSahDepth = 24;
    struct Node {
        Bounds3 box;
        int first = 0, count = 0;  // leaf: items_[first, first + count)
        int right = 0;             // interior: right child index (left child follows)
        int axis = 0;
    };

    // The items' boxes and, for median builds, their centres, by item.
    struct BuildInput {
        const std::vector<Bounds3>& boxes;
        std::vector<Vec3> centres;  // empty for SAH builds
    };
    // Coordinate `axis` of item's centre.
    static double CentreOf(const BuildInput& input, int item, int axis) {
        return input.centres.empty() ? input.boxes[item].Center()[axis] : input.centres[item][axis];
    }
    // The items being built over, in their current order (every node's items are a range
    // of it): their indices and, for the SAH, each one's box in single precision rounded
    // outward, (x, y, z, 0) in two vectors, moved with it. The SAH's passes read a node's
    // boxes in sequence rather than through the indices, and unions of these boxes are
    // conservative node boxes (each holds its item's double box).
    struct SahBox {
        Float4 lo, hi;
        Float4 Centre() const { return (lo + hi) * 0.5f; }  // what the SAH bins by
    };
    struct BuildItems {
        std::vector<int>& items;
        SahBox* sahBoxes;  // null for median builds
        void Swap(int i, int j) {
            std::swap(items[i], items[j]);
            std::swap(sahBoxes[i], sahBoxes[j]);
        }
    };
    static SahBox SahBoxOf(const Bounds3& box);
    // Builds the subtree over order.items[begin, end) at `depth` into `nodes` (appended in
    // preorder: a node, its left subtree, its right one) and returns its root's index. With
    // `deferred`, a subtree of at most deferBelow items is not built but left there, its
    // root a placeholder node (a parallel task of Build).
    struct Subtree {
        int begin, end, depth, node;
    };
    static int BuildNode(std::vector<Node>& nodes, BuildItems order, int begin, int end,
                         const BuildInput& input, Split split, int depth, int deferBelow,
                         std::vector<Subtree>* deferred);
    // Below this many items the whole tree is built as one task; above it the top levels
    // are built first and the subtrees of at most items / kBuildTasks items below them as
    // separate tasks (RunBuildLoop), for any thread count, so the tree does not depend on it.
    static constexpr int kParallelBuildItems = 4096, kBuildTasks = 32;
    // The SAH split of order's [begin, end) (centroid bounds `centroids`, node box `box`):
    // when a split pays, partitions the items, sets `axis` and returns the first of the
    // right part; otherwise returns kSahLeaf, or kSahMedian when there are too many for a
    // leaf.
    static constexpr int kSahLeaf = -1, kSahMedian = -2;
    static int SahPartition(BuildItems order, int begin, int end, const Bounds3& box,
                            const Bounds3& centroids, int& axis);

    // Wide nodes built apart (a part of the wide tree, or its top): indices local to
    // `nodes`. An interior lane's child is never 0 (index 0 is the part's root, no lane's
    // child), so 0 marks an unused lane, as in the finished tree; kDeferredLane - p marks a
    // lane left to deferred part p (see BuildWide).
    struct WidePart {
        std::vector<WideNode> nodes;
        double cost = 0;  // the parts' terms of expectedCost_, unscaled
    };
    static constexpr int kDeferredLane = -1;
    // The binary tree as Build made it: its top levels and, when the build was split into
    // tasks, the subtrees built apart, each in preorder with indices local to its vector.
    // Top node t with partAt[t] = p >= 0 is a placeholder for part p, whose root is
    // parts[p][0]. A node is named by its vector (part -1: the top) and its index there.
    struct BinaryParts {
        const std::vector<Node>& top;
        const std::vector<std::vector<Node>>& parts;
        const std::vector<int>& partAt;  // by top node (empty when there are no parts)
    };
    struct NodeRef {
        int part, index;
    };
    // The node `ref` names, a placeholder replaced by the root of its part.
    static NodeRef Resolve(const BinaryParts& tree, NodeRef ref) {
        if (ref.part < 0 && !tree.partAt.empty() && tree.partAt[ref.index] >= 0)
            return {tree.partAt[ref.index], 0};
        return ref;
    }
    static const Node& NodeAt(const BinaryParts& tree, NodeRef ref) {
        return ref.part < 0 ? tree.top[ref.index] : tree.parts[ref.part][ref.index];
    }
    // Appends to `out` the wide node whose lanes are binary node `node`'s descendants two
    // levels down at most (the larger-area interior lane split first, until four),
    // recursively, and returns its index in out. Adds the node's and its leaf lanes' terms,
    // unscaled, to out.cost. With `deferredParts` (building the top), a lane that is an
    // interior part root is neither split nor built but appended to deferredParts. Wide
    // depth <= binary depth < 64.
    int BuildWide(const BinaryParts& tree, NodeRef node, WidePart& out,
                  std::vector<int>* deferredParts) const;
    // Builds wide_ and expectedCost_ from the binary tree: the top, then the parts below it
    // as tasks (RunBuildLoop), spliced in preorder (the tree does not depend on the thread
    // count: the parts are Build's, made by item counts).
    void BuildWideTree(const BinaryParts& tree);

    // The binary tree, kept for median builds only (TraverseInEntryOrder, VisitContaining).
    std::vector<Node> nodes_;
    // The wide tree in preorder (allocated without initialisation: the splice's tasks write
    // each node once, so a large tree's pages are first touched on the build's threads).
    std::unique_ptr<WideNode[]> wide_;
    int wideCount_ = 0;
    double scale_ = 0;  // the largest coordinate magnitude of the wide boxes
    double expectedCost_ = 0;
    std::vector<int> items_;
};

inline int BoundingVolumeHierarchy::WideNode::Clip(const FloatRay& ray, Float4 tMin, Float4 tMax,
                                                   float tNear[4]) const {
    // Per lane: the largest near-slab and smallest far-slab parameter, written as
    // comparisons so a NaN (0·inf: an origin on the plane of an axis-parallel ray's slab)
    // leaves the range alone. Every computed parameter is within a relative 2.1·2^-24 of
    // the exact one for the shifted origins (one rounding of 1/d, one of the product), so
    // lowering the entry and raising the exit by 2^-21 of their size (plus 2^-126 against
    // underflow) keeps every box the exact segment meets.
    Float4 near = tMin, far = tMax;
    for (int a = 0; a < 3; ++a) {
        const Float4 t0 = (planes[ray.nearPlane[a]] - ray.nearOrigin[a]) * ray.invDir[a];
        const Float4 t1 = (planes[ray.farPlane[a]] - ray.farOrigin[a]) * ray.invDir[a];
        near = LaneMax(t0, near);
        far = LaneMin(t1, far);
    }
    constexpr Float4 kRelative{0x1p-21f, 0x1p-21f, 0x1p-21f, 0x1p-21f};
    constexpr Float4 kAbsolute{0x1p-126f, 0x1p-126f, 0x1p-126f, 0x1p-126f};
    const Float4 lower = near - (Abs(near) * kRelative + kAbsolute);
    const Float4 upper = far + (Abs(far) * kRelative + kAbsolute);
    // An infinite entry (or exit at -inf) gives NaN here: an empty lane, or an
    // axis-parallel ray outside a slab, both misses.
    const auto met = lower <= upper;
    for (int k = 0; k < 4; ++k) tNear[k] = lower[k];
#ifdef __SSE__
    // The lanes' sign bits in one instruction (a vector cast reinterprets the bits).
    return __builtin_ia32_movmskps((Float4)met);
#else
    int mask = 0;
    for (int k = 0; k < 4; ++k) mask |= (met[k] & 1) << k;
    return mask;
#endif
}

}  // namespace rs
