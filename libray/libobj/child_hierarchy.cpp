#include "libobj/child_hierarchy.h"

#include "libcommon/constants.h"
#include "libobj/object.h"

namespace rs {

void ChildHierarchy::Build(std::vector<const Object*> children) {
    children_ = std::move(children);
    std::vector<Bounds3> boxes;
    boxes.reserve(children_.size());
    for (const Object* child : children_) boxes.push_back(child->BoundsInParent().Padded(kEpsilon));
    hierarchy_.Build(boxes, BoundingVolumeHierarchy::Split::SurfaceArea);
}

bool ChildHierarchy::Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const {
    return hierarchy_.Traverse(ray, tMin, tMax, [&](int i) {
        return children_[i]->Intersect(ray, tMin, tMax, hit);
    });
}

bool ChildHierarchy::Occluded(const Ray& ray, double tMin, double tMax) const {
    return hierarchy_.Traverse<true>(ray, tMin, tMax, [&](int i) {
        return children_[i]->Occluded(ray, tMin, tMax);
    });
}

}  // namespace rs
