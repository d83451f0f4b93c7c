#include "libobj/list.h"

#include "libcommon/constants.h"
#include "libobj/object.h"

namespace rs {

bool ListAggregate::Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const {
    bool found = false;
    for (const Object* child : unbounded_)
        if (child->Intersect(ray, tMin, tMax, hit)) found = true;
    if (!hasBounded_) return found;
    if (!hierarchy_.IsEmpty()) {
        return hierarchy_.Traverse(ray, tMin, tMax, [&](int i) {
                   return bounded_[i]->Intersect(ray, tMin, tMax, hit);
               }) || found;
    }
    // The box test uses tMax as shrunk by the unbounded children. Without them it would
    // repeat the owning node's pre-test of this same box (Object::Intersect), so it is
    // skipped; skipping it never changes the nearest hit, only how many children are tried.
    double t0 = tMin, t1 = tMax;
    if (!unbounded_.empty() && !bounds_.ClipRay(ray, t0, t1)) return found;
    for (const Object* child : bounded_)
        if (child->Intersect(ray, tMin, tMax, hit)) found = true;
    return found;
}

bool ListAggregate::Occluded(const Ray& ray, double tMin, double tMax) const {
    for (const Object* child : unbounded_)
        if (child->Occluded(ray, tMin, tMax)) return true;
    if (!hasBounded_) return false;
    if (!hierarchy_.IsEmpty()) {
        return hierarchy_.Traverse<true>(ray, tMin, tMax, [&](int i) {
            return bounded_[i]->Occluded(ray, tMin, tMax);
        });
    }
    // The same box test as Intersect's: a ray missing every bounded child's box skips them
    // all, before any child maps the ray into its space (an animated transform evaluated
    // per shadow ray, in coin.ray).
    double t0 = tMin, t1 = tMax;
    if (!unbounded_.empty() && !bounds_.ClipRay(ray, t0, t1)) return false;
    for (const Object* child : bounded_)
        if (child->Occluded(ray, tMin, tMax)) return true;
    return false;
}

void ListAggregate::PrepareFrame(double /*frameTime*/, double /*shutter*/) {
    bounds_ = Bounds3{};
    unbounded_.clear();
    bounded_.clear();
    std::vector<Bounds3> boxes;
    for (const auto& child : children_) {
        if (!child->IsBounded()) {
            unbounded_.push_back(child.get());
            continue;
        }
        bounded_.push_back(child.get());
        // Padded so flat children (polygons, discs) keep boxes of non-zero thickness.
        boxes.push_back(child->BoundsInParent().Padded(kEpsilon));
        bounds_.Extend(child->BoundsInParent());
    }
    hasBounded_ = !bounded_.empty();
    if (bounded_.size() > kHierarchyThreshold)
        hierarchy_.Build(boxes, BoundingVolumeHierarchy::Split::SurfaceArea);
    else
        hierarchy_ = BoundingVolumeHierarchy{};
}

}  // namespace rs
