// Light sources (spec §3.7). No light falls off with distance.
#pragma once

#include "libcommon/random.h"
#include "libcommon/vector.h"

namespace rs {

// How one light reaches a shading point.
struct LightSample {
    Vec3 shadeDir;       // unit direction toward the light used for shading
    Vec3 shadowDir;      // unit direction of the shadow ray
    double shadowDist;   // length of the shadow ray (kFar for directional lights)
    Color color;         // intensity arriving before occlusion (spot cone applied)
};

// Fills `out` for light of colour `color` arriving at `x` from the point `source` (same
// direction for shading and shadow ray). False when x is at the source.
inline bool SampleFromPoint(const Vec3& x, const Vec3& source, const Color& color, LightSample& out) {
    Vec3 d = source - x;
    double dist = Length(d);
    if (!(dist > 0)) return false;
    out.shadeDir = out.shadowDir = d / dist;
    out.shadowDist = dist;
    out.color = color;
    return true;
}

class Light {
  public:
    virtual ~Light() = default;

    // Computes the light's contribution geometry at point `x`. `sampleNumber` is the eye
    // ray's sample number (−1 when none) and `samplesPerSide` the sampling grid's n; lights
    // that are sampled (extended, area) use them with `rng`. Returns false when the light
    // cannot reach x at all (outside a spot cone).
    virtual bool Sample(const Vec3& x, int sampleNumber, int samplesPerSide, Rng& rng,
                        LightSample& out) const = 0;

    Color intensity{1, 1, 1};
    bool noshadow = false;
};

}  // namespace rs
