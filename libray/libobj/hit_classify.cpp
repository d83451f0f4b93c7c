#include "libobj/hit_classify.h"

#include "libobj/object.h"

namespace rs {

bool HitEnters(const Ray& ray, const HitRecord& hit) {
    if (hit.enterOverride >= 0) return hit.enterOverride == 1;
    if (int known = hit.primitive->EntersFromHit(hit.prim); known >= 0) return known == 1;
    // Map from the outermost node's parent space down to the primitive's object space; t
    // is preserved by every mapping (directions are not renormalised).
    Ray r = ray;
    for (int i = hit.pathLength - 1; i >= 0; --i) {
        const TransformList& parentFromObject = hit.path[i]->parentFromObject;
        if (parentFromObject.IsIdentity()) continue;
        r = parentFromObject.IsAnimated() ? parentFromObject.At(r.time).InverseRay(r)
                                          : parentFromObject.Static().InverseRay(r);
    }
    const SurfaceNormals n = hit.primitive->Normal(r.At(hit.t()), hit.prim);
    return hit.primitive->Enters(r, hit.prim, n);
}

}  // namespace rs
