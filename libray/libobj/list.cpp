#include "libobj/list.h"

#include "libobj/object.h"

namespace rs {

bool ListAggregate::Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const {
    bool found = false;
    for (const auto& child : children_) {
        if (!child->IsBounded() && child->Intersect(ray, tMin, tMax, hit)) found = true;
    }
    if (!hasBounded_) return found;
    // The box test uses tMax as shrunk by the unbounded children.
    double t0 = tMin, t1 = tMax;
    if (!bounds_.ClipRay(ray, t0, t1)) return found;
    for (const auto& child : children_) {
        if (child->IsBounded() && child->Intersect(ray, tMin, tMax, hit)) found = true;
    }
    return found;
}

void ListAggregate::PrepareFrame(double /*frameTime*/, double /*shutter*/) {
    bounds_ = Bounds3{};
    hasBounded_ = false;
    for (const auto& child : children_) {
        if (!child->IsBounded()) continue;
        bounds_.Extend(child->BoundsInParent());
        hasBounded_ = true;
    }
}

}  // namespace rs
