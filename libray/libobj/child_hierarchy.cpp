#include "libobj/child_hierarchy.h"

#include "libcommon/constants.h"
#include "libobj/object.h"

namespace rs {

void ChildHierarchy::Build(std::vector<const Object*> children) {
    std::vector<Bounds3> boxes;
    boxes.reserve(children.size());
    for (const Object* child : children) boxes.push_back(child->BoundsInParent().Padded(kEpsilon));
    Build(std::move(children), boxes);
}

void ChildHierarchy::Build(std::vector<const Object*> children,
                           const std::vector<Bounds3>& paddedBoxes) {
    children_ = std::move(children);
    hierarchy_.Build(paddedBoxes, BoundingVolumeHierarchy::Split::SurfaceArea);
}

bool ChildHierarchy::Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const {
    return hierarchy_.Traverse(ray, tMin, tMax, [&](int i) {
        return children_[i]->Intersect(ray, tMin, tMax, hit);
    });
}

bool ChildHierarchy::Occluded(const Ray& ray, double tMin, double tMax,
                              const Object** blocker) const {
    return hierarchy_.Traverse<true>(ray, tMin, tMax, [&](int i) {
        return children_[i]->Occluded(ray, tMin, tMax, blocker);
    });
}

}  // namespace rs
