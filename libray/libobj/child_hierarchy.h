// The bounded children of an aggregate searched through a bounding volume hierarchy over
// their boxes: the search `list` runs, and `grid` too when it expects the hierarchy to be
// cheaper than its voxels (grid.h). Finds the nearest hit a loop over every child finds.
#pragma once

#include <vector>

#include "libgeom/bvh.h"
#include "libobj/hit.h"

namespace rs {

class Object;

class ChildHierarchy {
  public:
    // Builds over `children` (all bounded), from their BoundsInParent() padded by kEpsilon
    // (flat children, polygons and discs, keep boxes of non-zero thickness).
    void Build(std::vector<const Object*> children);
    // The same, with those padded boxes already at hand (boxes[i] for children[i]; a grid
    // has them for its voxels, and on a large scene they are megabytes to write again).
    void Build(std::vector<const Object*> children, const std::vector<Bounds3>& paddedBoxes);
    // Whether nothing is built (a default-constructed or reset hierarchy).
    bool IsEmpty() const { return hierarchy_.IsEmpty(); }
    // The hierarchy's expected cost of one ray through the children's union box, in units
    // of one box or child test (BoundingVolumeHierarchy::ExpectedCost).
    double ExpectedCost() const { return hierarchy_.ExpectedCost(); }

    // Nearest hit among the children with tMin < t < tMax (shrinks tMax, fills hit).
    bool Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const;
    // Whether any child has a hit with tMin < t < tMax; returns at the first found, naming
    // the blocker through the child's Object::Occluded when `blocker` is not null.
    bool Occluded(const Ray& ray, double tMin, double tMax, const Object** blocker) const;

  private:
    std::vector<const Object*> children_;
    BoundingVolumeHierarchy hierarchy_;
};

}  // namespace rs
