// A ray o + t·d. The direction need not be unit length: transforms map rays into object
// space without renormalising, so a distance t means the same point in every space. Rays
// built by the renderer in world space have unit directions.
#pragma once

#include "libcommon/vector.h"

namespace rs {

struct Ray {
    Vec3 origin;
    Vec3 dir;
    double time = 0;  // scene time the ray samples (motion blur, animated transforms)

    Vec3 At(double t) const { return origin + dir * t; }
};

}  // namespace rs
