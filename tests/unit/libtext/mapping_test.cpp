#include "libtext/mapping.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fake_args.h"
#include "libcommon/constants.h"

namespace rs {
namespace {

// A primitive whose UV is the object-space point's (x, y), with derivatives x̂ and ẑ.
class FlatPrimitive : public Primitive {
  public:
    const IntersectionCounters& Counters() const override {
        static IntersectionCounters counters("FlatTest");
        return counters;
    }
    Bounds3 Bounds() const override { return {}; }
    bool Intersect(const Ray&, double, double, PrimitiveHit&) const override { return false; }
    SurfaceNormals Normal(const Vec3&, const PrimitiveHit&) const override { return {}; }
    SurfaceUV UV(const Vec3& p, const Vec3&, const PrimitiveHit&) const override {
        return {{p.x, p.y}, {1, 0, 0}, {0, 0, 1}};
    }
};

void ExpectVecNear(const Vec3& a, const Vec3& b, double tol = 1e-12) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TextureContext At(const Vec3& p) {
    TextureContext ctx;
    ctx.point = p;
    return ctx;
}

TEST(UVMapping, UsesPrimitiveSpacePointAndCarriesDerivativesToNodeSpace) {
    FlatPrimitive prim;
    TextureContext ctx = At({100, 100, 100});  // node-space point: must not be used
    ctx.primitive = &prim;
    ctx.pointPrimitive = {0.25, 0.75, 0};
    ctx.nodeFromPrimitive = *Transform::Rotate({0, 0, 1}, 90);  // x̂ → ŷ
    SurfaceUV s = UVMapping().Map(ctx);
    EXPECT_DOUBLE_EQ(s.uv.u, 0.25);
    EXPECT_DOUBLE_EQ(s.uv.v, 0.75);
    ExpectVecNear(s.dpdu, {0, 1, 0});
    ExpectVecNear(s.dpdv, {0, 0, 1});
}

TEST(UVMapping, WithoutPrimitiveGivesDefaults) {
    SurfaceUV s = UVMapping().Map(At({3, 4, 5}));
    EXPECT_EQ(s.uv.u, 0.0);
    EXPECT_EQ(s.uv.v, 0.0);
}

TEST(SphereUV, FollowsTheSphereRule) {
    // Equator: v = acos(0)/π = ½; u = acos(n_x)/2π, 1 − u unless n_y > 0.
    Vec2 a = SphereUV(0, 1, 0);
    EXPECT_NEAR(a.u, 0.25, 1e-12);
    EXPECT_NEAR(a.v, 0.5, 1e-12);
    EXPECT_NEAR(SphereUV(0, -1, 0).u, 0.75, 1e-12);
    EXPECT_NEAR(SphereUV(1, 0, 0).u, 1.0, 1e-12);   // n_y = 0 is not > 0
    EXPECT_NEAR(SphereUV(-1, 0, 0).u, 0.5, 1e-12);
    // Poles: u = 0; v = 0 at −z, 1 at +z.
    Vec2 south = SphereUV(0, 0, -1), north = SphereUV(0, 0, 1);
    EXPECT_EQ(south.u, 0.0);
    EXPECT_NEAR(south.v, 0.0, 1e-12);
    EXPECT_EQ(north.u, 0.0);
    EXPECT_NEAR(north.v, 1.0, 1e-12);
    // 45° north of +y: v = acos(−sin 45°)/π = 3/4.
    double h = std::sqrt(0.5);
    EXPECT_NEAR(SphereUV(0, h, h).v, 0.75, 1e-12);
    EXPECT_NEAR(SphereUV(0, h, h).u, 0.25, 1e-12);
}

TEST(SphericalMapping, UsesOriginAndFrame) {
    // Frame: up = x̂, u axis = ŷ → N̂ = x̂, V̂ = normalize(x̂ × ŷ) = ẑ, Û = ẑ × x̂ = ŷ.
    std::optional<MappingFrame> f = MappingFrame::Make({1, 1, 1}, {2, 0, 0}, {0, 3, 0});
    ASSERT_TRUE(f);
    ExpectVecNear(f->u, {0, 1, 0});
    ExpectVecNear(f->v, {0, 0, 1});
    ExpectVecNear(f->n, {1, 0, 0});
    SphericalMapping m(*f);
    // Direction +z from the origin is +V̂: n = (0, 1, 0) in the frame → u = ¼, v = ½.
    SurfaceUV s = m.Map(At({1, 1, 6}));
    EXPECT_NEAR(s.uv.u, 0.25, 1e-12);
    EXPECT_NEAR(s.uv.v, 0.5, 1e-12);
    // At the origin itself: (0, 0).
    SurfaceUV o = m.Map(At({1, 1, 1}));
    EXPECT_EQ(o.uv.u, 0.0);
    EXPECT_EQ(o.uv.v, 0.0);
}

TEST(CylindricalMapping, HeightAndAzimuth) {
    CylindricalMapping m(*MappingFrame::Make({0, 0, 0}, {0, 0, 1}, {1, 0, 0}));
    SurfaceUV s = m.Map(At({0, 2, 3}));
    EXPECT_NEAR(s.uv.u, 0.25, 1e-12);
    EXPECT_NEAR(s.uv.v, 3.0, 1e-12);
    ExpectVecNear(s.dpdv, {0, 0, 1});
    ExpectVecNear(s.dpdu, {-1, 0, 0});  // ẑ × ŷ
    EXPECT_NEAR(m.Map(At({0, -2, 0})).uv.u, 0.75, 1e-12);
    EXPECT_EQ(m.Map(At({0, 0, 7})).uv.u, 0.0);  // on the axis
}

TEST(PlanarMapping, DefaultIsXY) {
    testing::FakeArgs args({"planar"});
    std::shared_ptr<Mapping> m = ReadMapping(args);
    SurfaceUV s = m->Map(At({0.3, -2.5, 9}));
    EXPECT_NEAR(s.uv.u, 0.3, 1e-12);
    EXPECT_NEAR(s.uv.v, -2.5, 1e-12);
}

TEST(PlanarMapping, HonoursOriginAndSkewedAxes) {
    // X = o + u·ua + v·va + w·(ua × va): o = (1, 1, 0), ua = (1, 0, 0), va = (1, 2, 0).
    // X = (1, 1, 0) + 2·(1, 0, 0) + 1.5·(1, 2, 0) + 0.25·(0, 0, 2) = (4.5, 4, 0.5).
    std::shared_ptr<PlanarMapping> m = PlanarMapping::Make({1, 1, 0}, {1, 2, 0}, {1, 0, 0});
    ASSERT_TRUE(m);
    SurfaceUV s = m->Map(At({4.5, 4, 0.5}));
    EXPECT_NEAR(s.uv.u, 2.0, 1e-12);
    EXPECT_NEAR(s.uv.v, 1.5, 1e-12);
    ExpectVecNear(s.dpdu, {1, 0, 0});
    ExpectVecNear(s.dpdv, Normalize({1, 2, 0}));
}

TEST(ReadMapping, ParsesEveryFormAndRejectsBadInput) {
    testing::FakeArgs uv({"uv"});
    EXPECT_NE(dynamic_cast<UVMapping*>(ReadMapping(uv).get()), nullptr);
    testing::FakeArgs sph({"spherical", "0", "0", "0", "0", "0", "1", "1", "0", "0"});
    EXPECT_NE(dynamic_cast<SphericalMapping*>(ReadMapping(sph).get()), nullptr);
    EXPECT_TRUE(sph.AtEnd());
    testing::FakeArgs cyl({"cylindrical"});
    EXPECT_NE(dynamic_cast<CylindricalMapping*>(ReadMapping(cyl).get()), nullptr);

    testing::FakeArgs unknown({"conical"});
    EXPECT_THROW(ReadMapping(unknown), FatalError);
    testing::FakeArgs parallel({"cylindrical", "0", "0", "0", "0", "0", "1", "0", "0", "2"});
    EXPECT_THROW(ReadMapping(parallel), FatalError);
    testing::FakeArgs flat({"planar", "0", "0", "0", "1", "0", "0", "2", "0", "0"});
    EXPECT_THROW(ReadMapping(flat), FatalError);
}

TEST(BumpNormal, TiltsAgainstTheSlopeAndStaysUnit) {
    // n = ẑ, ∂u = x̂, ∂v = ŷ: n × ∂v = −x̂, so fu > 0 tilts toward −x.
    Vec3 n = BumpNormal({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 1, 0);
    ExpectVecNear(n, Normalize({-1, 0, 1}));
    Vec3 m = BumpNormal({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 0, 1);  // −fv(n × ∂u) = −ŷ
    ExpectVecNear(m, Normalize({0, -1, 1}));
}

}  // namespace
}  // namespace rs
