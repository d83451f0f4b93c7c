// Surface (material) description, spec §3.5.
#pragma once

#include "libcommon/vector.h"

namespace rs {

struct Surface {
    Color ambient;
    Color diffuse;
    Color specular;
    Color body{1, 1, 1};
    Color translucentColor;   // Kt
    double specpow = 15;      // p_s
    double translucentPow = 15;  // p_t
    double reflect = 0;
    double transp = 0;
    double extinct = 1;       // per-unit-length transmittance of the interior (1 = clear)
    double index = 1;
    double translucency = 0;  // τ
    bool noshadow = false;

    // The record every attribute list starts from (spec §3.5, "fresh surface").
    static Surface Fresh() { return Surface{}; }
    // Used when nothing is bound to a hit object: a light-grey plastic.
    static Surface Default() {
        Surface s;
        s.ambient = Color(0.1);
        s.diffuse = Color(0.6);
        s.specular = Color(0.5);
        s.specpow = 12;
        s.translucentPow = 12;
        return s;
    }
};

// Weighted blend of every numeric field: wa·a + wb·b (blotch texture, image alpha).
// `noshadow` is the AND of both, or b's alone when wa < ε.
Surface BlendSurfaces(const Surface& a, double wa, const Surface& b, double wb);

}  // namespace rs
