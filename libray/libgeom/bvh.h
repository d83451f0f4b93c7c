// A bounding volume hierarchy over a set of boxes, used by `list` to test only the children
// a ray can reach (the original tests every child of a list; the nearest hit is the same,
// because every child whose box meets the remaining ray segment is still tested), by the
// metaball sums of `blob` and `method polynomial` (metaball_sum.h), and by the implicit
// patches (one item per patch box).
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "libcommon/bounds.h"

namespace rs {

class BoundingVolumeHierarchy {
  public:
    enum class Split {
        // At the median centroid of the widest axis, until at most kLeafSize items remain.
        Median,
        // Where the surface-area heuristic (binned centroids, all three axes) expects the
        // fewest box and item tests for rays through the node; a node stays a leaf (of at
        // most kMaxSahLeaf items) when no split is expected to pay. Below kMaxSahDepth
        // levels it falls back to median splits, so the depth stays under 64.
        SurfaceArea,
    };
    // Builds over `boxes` (item i has box boxes[i]).
    void Build(const std::vector<Bounds3>& boxes, Split split = Split::Median);
    bool IsEmpty() const { return nodes_.empty(); }

    // Calls visit(i) once for every item whose box meets the ray segment (tMin, tMax), nearer
    // subtrees first (items sharing a leaf with such an item may be visited too: item
    // boxes are not tested one by one). visit returns true when it found a hit, and may then have shrunk tMax;
    // later boxes are clipped against the shrunken segment. Returns whether any visit hit.
    // With kStopAtFirstHit the walk returns at the first visit that hits (occlusion).
    template <bool kStopAtFirstHit = false, class Visit>
    bool Traverse(const Ray& ray, double tMin, double& tMax, Visit&& visit) const {
        if (nodes_.empty()) return false;
        const Vec3 invDir{1 / ray.dir.x, 1 / ray.dir.y, 1 / ray.dir.z};
        const bool negative[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
        int stack[64];
        int top = 0;
        stack[top++] = 0;
        bool found = false;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!node.box.MeetsSegment(ray, invDir, tMin, tMax)) continue;
            if (node.count > 0) {
                for (int i = 0; i < node.count; ++i) {
                    if (!visit(items_[node.first + i])) continue;
                    if (kStopAtFirstHit) return true;
                    found = true;
                }
                continue;
            }
            // Push the far child first so the near one is visited next.
            int nearChild = static_cast<int>(&node - nodes_.data()) + 1, farChild = node.right;
            if (negative[node.axis]) std::swap(nearChild, farChild);
            if (top + 2 > 64) {
                // Deeper than any tree Build makes (see Split); visit the rest linearly
                // rather than overflow.
                for (int item : items_) {
                    if (!visit(item)) continue;
                    if (kStopAtFirstHit) return true;
                    found = true;
                }
                return found;
            }
            stack[top++] = farChild;
            stack[top++] = nearChild;
        }
        return found;
    }

    // As Traverse, with children ordered by the parameter at which the ray enters their
    // boxes rather than by the split axis, and a node skipped once its entry lies beyond the
    // shrunken tMax. Each box is clipped once, when its parent is visited, and stacked with
    // its entry `near`: the clip to (tMin, tMax) with a smaller tMax at its turn succeeds
    // exactly when near <= tMax (near does not depend on the far end, and the slab exits
    // already passed near). For items that are expensive to visit (an implicit patch may
    // build its octree), so that the nearest ones come first.
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
    // its leaf).
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

    // The items' boxes and their centres, by item.
    struct BuildInput {
        const std::vector<Bounds3>& boxes;
        std::vector<Vec3> centres;
    };
    int BuildNode(std::vector<int>& items, int begin, int end, const BuildInput& input,
                  Split split, int depth);
    // The SAH split of items[begin, end) (centroid bounds `centroids`, node box `box`): when
    // a split pays, partitions the items, sets `axis` and returns the first of the right
    // part; otherwise returns kSahLeaf, or kSahMedian when there are too many for a leaf.
    static constexpr int kSahLeaf = -1, kSahMedian = -2;
    static int SahPartition(std::vector<int>& items, int begin, int end,
                            const BuildInput& input, const Bounds3& box,
                            const Bounds3& centroids, int& axis);

    std::vector<Node> nodes_;
    std::vector<int> items_;
};

}  // namespace rs
