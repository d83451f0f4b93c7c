#include "libobj/bvh.h"

#include <algorithm>

namespace rs {

void BoundingVolumeHierarchy::Build(const std::vector<Bounds3>& boxes) {
    nodes_.clear();
    items_.resize(boxes.size());
    for (size_t i = 0; i < boxes.size(); ++i) items_[i] = static_cast<int>(i);
    if (boxes.empty()) return;
    nodes_.reserve(2 * boxes.size());
    BuildNode(items_, 0, static_cast<int>(items_.size()), boxes);
}

int BoundingVolumeHierarchy::BuildNode(std::vector<int>& items, int begin, int end,
                                       const std::vector<Bounds3>& boxes) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Bounds3 box, centroids;
    for (int i = begin; i < end; ++i) {
        box.Extend(boxes[items[i]]);
        centroids.Extend(boxes[items[i]].Center());
    }
    nodes_[index].box = box;
    if (end - begin <= kLeafSize) {
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return index;
    }
    Vec3 extent = centroids.Extent();
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    int mid = begin + (end - begin) / 2;
    std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                     [&](int a, int b) { return boxes[a].Center()[axis] < boxes[b].Center()[axis]; });
    BuildNode(items, begin, mid, boxes);
    int right = BuildNode(items, mid, end, boxes);
    nodes_[index].right = right;
    nodes_[index].axis = axis;
    return index;
}

}  // namespace rs
