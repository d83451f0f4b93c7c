// Enter/leave classification of a hit (spec §3.10 CSG, §3.6 refraction).
#pragma once

#include "libcommon/ray.h"
#include "libobj/hit.h"

namespace rs {

// Whether the ray enters the solid at `hit`. `ray` is in the space the outermost recorded
// node (hit.path[hit.pathLength - 1]) was intersected from, i.e. that node's PARENT space;
// it is mapped down the path to the primitive's object space, where the primitive's Normal
// and Enters decide. A CSG override (hit.enterOverride >= 0) wins over the primitive.
//
// Primitives whose Enters looks at the ray origin (sphere, box: "ray start outside") are
// only reliable when the origin lies strictly on the ray's side of the surface before the
// hit, with no other surface of that solid between the origin and the hit.
bool HitEnters(const Ray& ray, const HitRecord& hit);

// `ray` (as for HitEnters, in the outermost recorded node's parent space) mapped down the
// path to the hit primitive's object space. Every mapping keeps t (directions are not
// renormalised), so r.At(hit.t()) is the hit point there.
Ray RayInPrimitiveSpace(const Ray& ray, const HitRecord& hit);

}  // namespace rs
