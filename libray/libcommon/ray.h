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
    // Footprint: the width of the beam of rays this ray stands for (a pixel's, for eye
    // rays) at parameter t is footprintWidth + footprintSpread·t, measured in units of t
    // (a length divided by |dir|: world units for the renderer's unit world directions).
    // Transforms keep t, so the footprint needs no transforming. Both 0: unknown (a point
    // query); methods that adapt their accuracy to it then use their fixed accuracy.
    double footprintWidth = 0;
    double footprintSpread = 0;

    Vec3 At(double t) const { return origin + dir * t; }
};

}  // namespace rs
