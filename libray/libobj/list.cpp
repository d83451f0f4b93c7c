#include "libobj/list.h"

#include "libobj/object.h"

namespace rs {

bool ListAggregate::Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const {
    bool found = false;
    for (const Object* child : unbounded_)
        if (child->Intersect(ray, tMin, tMax, hit)) found = true;
    if (!hasBounded_) return found;
    if (!hierarchy_.IsEmpty()) return hierarchy_.Intersect(ray, tMin, tMax, hit) || found;
    // The box test uses tMax as shrunk by the unbounded children. Without them it would
    // repeat the owning node's pre-test of this same box (Object::Intersect), so it is
    // skipped; skipping it never changes the nearest hit, only how many children are tried.
    double t0 = tMin, t1 = tMax;
    if (!unbounded_.empty() && !bounds_.ClipRay(ray, t0, t1)) return found;
    for (const Object* child : bounded_)
        if (child->Intersect(ray, tMin, tMax, hit)) found = true;
    return found;
}

bool ListAggregate::Occluded(const Ray& ray, double tMin, double tMax,
                             const Object** blocker) const {
    for (const Object* child : unbounded_)
        if (child->Occluded(ray, tMin, tMax, blocker)) return true;
    if (!hasBounded_) return false;
    if (!hierarchy_.IsEmpty()) return hierarchy_.Occluded(ray, tMin, tMax, blocker);
    // The same box test as Intersect's: a ray missing every bounded child's box skips them
    // all, before any child maps the ray into its space (an animated transform evaluated
    // per shadow ray, in coin.ray).
    double t0 = tMin, t1 = tMax;
    if (!unbounded_.empty() && !bounds_.ClipRay(ray, t0, t1)) return false;
    for (const Object* child : bounded_)
        if (child->Occluded(ray, tMin, tMax, blocker)) return true;
    return false;
}

void ListAggregate::PrepareFrame(double /*frameTime*/, double /*shutter*/) {
    bounds_ = Bounds3{};
    unbounded_.clear();
    bounded_.clear();
    for (const auto& child : children_) {
        if (!child->IsBounded()) {
            unbounded_.push_back(child.get());
            continue;
        }
        bounded_.push_back(child.get());
        bounds_.Extend(child->BoundsInParent());
    }
    hasBounded_ = !bounded_.empty();
    hierarchy_ = ChildHierarchy{};
    if (bounded_.size() > kHierarchyThreshold) hierarchy_.Build(bounded_);
}

}  // namespace rs
