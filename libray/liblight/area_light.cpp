#include "liblight/area_light.h"

#include "liblight/lights.h"

namespace rs {

bool AreaLightCell::Sample(const Vec3& x, int, int, Rng& rng, LightSample& out) const {
    double su = rng.Uniform(), sv = rng.Uniform();
    return SampleFromPoint(x, corner_ + edgeU_ * su + edgeV_ * sv, intensity, out);
}

LightList CreateAreaLight(ArgReader& args, const Color& intensity) {
    Vec3 p1 = args.ReadVector();
    Vec3 p2 = args.ReadVector();
    int nu = args.ReadInt();
    Vec3 p3 = args.ReadVector();
    int nv = args.ReadInt();
    if (nu < 1 || nv < 1) args.Fail("area light needs at least one sample along each edge");
    // Each sub-light is a full light, so cost grows with nu·nv: refuse absurd grids.
    constexpr long kMaxCells = 65536;
    if (static_cast<long>(nu) * nv > kMaxCells)
        args.Fail("area light has more than 65536 sub-lights (nu·nv)");
    Vec3 edgeU = (p2 - p1) / nu, edgeV = (p3 - p1) / nv;
    if (!(Length(Cross(edgeU, edgeV)) > 0)) args.Fail("degenerate area light (parallel or zero edges)");
    LightList lights;
    Color cellIntensity = intensity * (1.0 / (static_cast<double>(nu) * nv));
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j)
            lights.push_back(std::make_shared<AreaLightCell>(
                cellIntensity, p1 + edgeU * i + edgeV * j, edgeU, edgeV));
    return lights;
}

}  // namespace rs
