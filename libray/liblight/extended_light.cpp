#include "liblight/extended_light.h"

#include "liblight/lights.h"

namespace rs {

bool ExtendedLight::Sample(const Vec3& x, int sampleNumber, int samplesPerSide, Rng& rng,
                           LightSample& out) const {
    Vec3 toCentre = centre_ - x;
    double dist = Length(toCentre);
    if (!(dist > 0)) return false;
    out.shadeDir = toCentre / dist;
    out.color = intensity;

    // Stratify the target over the sampling grid by the eye ray's sample number m: cell
    // column m mod n along v, row ⌊m/n⌋ along u, always jittered inside the cell.
    int n = samplesPerSide > 0 ? samplesPerSide : 1;
    int m = sampleNumber >= 0 ? sampleNumber : static_cast<int>(rng.Uniform() * n * n);
    double cell = 2 * radius_ / n;
    double v = -radius_ + (m % n) * cell + rng.Uniform() * cell;
    double u = -radius_ + (m / n) * cell + rng.Uniform() * cell;
    Vec3 axisU, axisV;
    CoordinateSystem(out.shadeDir, axisU, axisV);
    Vec3 target = centre_ + axisU * u + axisV * v;
    Vec3 d = target - x;
    double shadowDist = Length(d);
    if (!(shadowDist > 0)) return false;
    out.shadowDir = d / shadowDist;
    out.shadowDist = shadowDist;
    return true;
}

LightList CreateExtendedLight(ArgReader& args, const Color& intensity) {
    double r = args.ReadNumber();
    Vec3 p = args.ReadVector();
    if (r < 0) args.Fail("extended light with a negative radius");
    return {std::make_shared<ExtendedLight>(intensity, r, p)};
}

}  // namespace rs
