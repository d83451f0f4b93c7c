#include "libsurf/surface.h"

#include "libcommon/constants.h"

namespace rs {

Surface BlendSurfaces(const Surface& a, double wa, const Surface& b, double wb) {
    Surface s;
    s.ambient = a.ambient * wa + b.ambient * wb;
    s.diffuse = a.diffuse * wa + b.diffuse * wb;
    s.specular = a.specular * wa + b.specular * wb;
    s.body = a.body * wa + b.body * wb;
    s.translucentColor = a.translucentColor * wa + b.translucentColor * wb;
    s.specpow = a.specpow * wa + b.specpow * wb;
    s.translucentPow = a.translucentPow * wa + b.translucentPow * wb;
    s.reflect = a.reflect * wa + b.reflect * wb;
    s.transp = a.transp * wa + b.transp * wb;
    s.extinct = a.extinct * wa + b.extinct * wb;
    s.index = a.index * wa + b.index * wb;
    s.translucency = a.translucency * wa + b.translucency * wb;
    s.noshadow = wa < kEpsilon ? b.noshadow : (a.noshadow && b.noshadow);
    return s;
}

}  // namespace rs
