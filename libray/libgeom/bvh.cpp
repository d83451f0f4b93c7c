#include "libgeom/bvh.h"

#include <algorithm>

namespace rs {

namespace {

// Half the surface area of a box (the SAH only compares areas); 0 for an empty box.
double HalfArea(const Bounds3& b) {
    if (b.IsEmpty()) return 0;
    const Vec3 e = b.Extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

}  // namespace

void BoundingVolumeHierarchy::Build(const std::vector<Bounds3>& boxes, Split split) {
    nodes_.clear();
    items_.resize(boxes.size());
    for (size_t i = 0; i < boxes.size(); ++i) items_[i] = static_cast<int>(i);
    if (boxes.empty()) return;
    nodes_.reserve(2 * boxes.size());
    // The centres in an array of their own: every level of the build reads them.
    BuildInput input{boxes, {}};
    input.centres.reserve(boxes.size());
    for (const Bounds3& b : boxes) input.centres.push_back(b.Center());
    BuildNode(items_, 0, static_cast<int>(items_.size()), input, split, 0);
}

int BoundingVolumeHierarchy::SahPartition(std::vector<int>& items, int begin, int end,
                                          const BuildInput& input, const Bounds3& box,
                                          const Bounds3& centroids, int& axis) {
    constexpr int kBins = 16;
    const int count = end - begin;
    // Costs in units of one item test, a box test of a child counted as one as well:
    // splitting costs 1 + (A_left·N_left + A_right·N_right) / A; a leaf costs N.
    double bestCost = count;
    int bestAxis = -1, bestBin = 0;
    const double area = HalfArea(box);
    const Vec3 cLo = centroids.lo, cExtent = centroids.Extent();
    const auto binOf = [&](int item, int a) {
        const int b = static_cast<int>(kBins * (input.centres[item][a] - cLo[a]) / cExtent[a]);
        return b < 0 ? 0 : (b >= kBins ? kBins - 1 : b);
    };
    for (int a = 0; a < 3; ++a) {
        if (!(cExtent[a] > 0)) continue;
        Bounds3 binBox[kBins];
        int binCount[kBins] = {};
        for (int i = begin; i < end; ++i) {
            const int b = binOf(items[i], a);
            ++binCount[b];
            binBox[b].Extend(input.boxes[items[i]]);
        }
        // rightCost[k]: A·N of bins k.. (the right part when splitting before bin k).
        double rightCost[kBins];
        Bounds3 acc;
        int n = 0;
        for (int k = kBins - 1; k > 0; --k) {
            acc.Extend(binBox[k]);
            n += binCount[k];
            rightCost[k] = HalfArea(acc) * n;
        }
        acc = Bounds3{};
        n = 0;
        for (int k = 1; k < kBins; ++k) {
            acc.Extend(binBox[k - 1]);
            n += binCount[k - 1];
            if (n == 0 || n == count) continue;
            const double cost = 1 + (HalfArea(acc) * n + rightCost[k]) / area;
            if (cost < bestCost) {
                bestCost = cost;
                bestAxis = a;
                bestBin = k;
            }
        }
    }
    if (bestAxis < 0) return count <= kMaxSahLeaf ? kSahLeaf : kSahMedian;
    axis = bestAxis;
    const auto middle = std::partition(items.begin() + begin, items.begin() + end,
                                       [&](int item) { return binOf(item, bestAxis) < bestBin; });
    return static_cast<int>(middle - items.begin());
}

int BoundingVolumeHierarchy::BuildNode(std::vector<int>& items, int begin, int end,
                                       const BuildInput& input, Split split, int depth) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Bounds3 box, centroids;
    for (int i = begin; i < end; ++i) {
        box.Extend(input.boxes[items[i]]);
        centroids.Extend(input.centres[items[i]]);
    }
    nodes_[index].box = box;
    const auto leaf = [&] {
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return index;
    };
    Vec3 extent = centroids.Extent();
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    int mid = kSahMedian;
    if (split == Split::SurfaceArea && depth < kMaxSahDepth) {
        if (end - begin <= 1) return leaf();
        mid = SahPartition(items, begin, end, input, box, centroids, axis);
        if (mid == kSahLeaf) return leaf();
    } else if (end - begin <= kLeafSize) {
        return leaf();
    }
    if (mid == kSahMedian) {
        mid = begin + (end - begin) / 2;
        std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                         [&](int a, int b) {
                             // Ties broken by item, so which items go to each half
                             // does not depend on the standard library.
                             const double ca = input.centres[a][axis], cb = input.centres[b][axis];
                             return ca < cb || (ca == cb && a < b);
                         });
    }
    BuildNode(items, begin, mid, input, split, depth + 1);
    int right = BuildNode(items, mid, end, input, split, depth + 1);
    nodes_[index].right = right;
    nodes_[index].axis = axis;
    return index;
}

}  // namespace rs
