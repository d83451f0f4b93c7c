// Aggregates (list, grid, CSG) hold child nodes and search them for the nearest hit.
#pragma once

#include <memory>
#include <vector>

#include "libobj/hit.h"

namespace rs {

class Object;

class Aggregate {
  public:
    virtual ~Aggregate() = default;

    virtual const char* TypeName() const = 0;  // "list", "grid", "union", ...

    // Nearest hit among the children with tMin < t < tMax, in the aggregate's object space.
    // On success shrinks tMax to the hit's t, fills `hit` (via the children) and returns
    // true; on failure leaves tMax and `hit` untouched.
    virtual bool Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const = 0;

    // Whether any child has a hit with tMin < t < tMax (the shadow-ray question); the same
    // answer as Intersect's return value. Aggregates that can stop at the first hit found
    // override it and pass `blocker` to the children's Object::Occluded, which then name
    // the blocking primitive below; the default runs the nearest-hit search and names none,
    // leaving *blocker as the caller set it (null). CSG gets null from Object anyway
    // (HitsAreChildHits).
    virtual bool Occluded(const Ray& ray, double tMin, double tMax,
                          const Object** /*blocker*/) const {
        HitRecord hit;
        return Intersect(ray, tMin, tMax, hit);
    }

    // Whether every hit of a child is a hit of this aggregate (lists, grids); false for
    // CSG, whose hits are only those on the combined solid's boundary.
    virtual bool HitsAreChildHits() const { return true; }

    // Box around the bounded children (object space) and whether there are any.
    virtual Bounds3 Bounds() const = 0;
    virtual bool IsBounded() const = 0;
    virtual bool IsClosed() const { return false; }

    // Recomputes bounds (and rebuilds grids) for the frame starting at frameTime, after the
    // children have been prepared. `shutter` is the exposure length (0: no motion blur).
    virtual void PrepareFrame(double frameTime, double shutter) = 0;

    const std::vector<std::shared_ptr<Object>>& Children() const { return children_; }
    void AddChild(std::shared_ptr<Object> child) { children_.push_back(std::move(child)); }

  protected:
    std::vector<std::shared_ptr<Object>> children_;
};

}  // namespace rs
