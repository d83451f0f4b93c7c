#include "libobj/hit_classify.h"

#include "libobj/object.h"

namespace rs {

bool HitEnters(const Ray& ray, const HitRecord& hit) {
    if (hit.enterOverride >= 0) return hit.enterOverride == 1;
    if (int known = hit.primitive->EntersFromHit(hit.prim); known >= 0) return known == 1;
    const Ray r = RayInPrimitiveSpace(ray, hit);
    const SurfaceNormals n = hit.primitive->Normal(r.At(hit.t()), hit.prim);
    return hit.primitive->Enters(r, hit.prim, n);
}

Ray RayInPrimitiveSpace(const Ray& ray, const HitRecord& hit) {
    Ray r = ray;
    for (int i = hit.pathLength - 1; i >= 0; --i) {
        const TransformList& parentFromObject = hit.path[i]->parentFromObject;
        if (parentFromObject.IsIdentity()) continue;
        r = parentFromObject.IsAnimated() ? parentFromObject.At(r.time).InverseRay(r)
                                          : parentFromObject.Static().InverseRay(r);
    }
    return r;
}

}  // namespace rs
