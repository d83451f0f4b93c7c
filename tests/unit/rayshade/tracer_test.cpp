#include "rayshade/tracer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "liblight/directional_light.h"
#include "libobj/list.h"
#include "libobj/object.h"
#include "libobj/sphere.h"
#include "libsurf/surface.h"

namespace rs {
namespace {

// A scene of spheres (radius, centre, surface) lit by one directional light from +z.
struct TestScene {
    Scene scene;
    std::shared_ptr<ListAggregate> list = std::make_shared<ListAggregate>();

    TestScene() {
        scene.world = Object::MakeAggregate(list);
        scene.lights.push_back(std::make_shared<DirectionalLight>(Color(1), Vec3{0, 0, 1}));
        scene.options.background = Color(0.2, 0.3, 0.4);
    }
    void AddSphere(double r, const Vec3& c, const Surface& s) {
        auto node = Object::MakePrimitive(std::make_shared<Sphere>(r, c));
        node->surface = std::make_shared<Surface>(s);
        list->AddChild(node);
    }
    Color Trace(const Ray& ray, bool& hit) {
        scene.world->PrepareFrame(0, 0);
        Tracer tracer(scene);
        Rng rng(1);
        SampleState state{0, 1, &rng};
        return tracer.TraceEye(ray, state, hit);
    }
};

Surface Matte(double ambient, double diffuse) {
    Surface s;
    s.ambient = Color(ambient);
    s.diffuse = Color(diffuse);
    return s;
}

void ExpectColor(const Color& c, const Color& expected, double tol = 1e-9) {
    EXPECT_NEAR(c.r, expected.r, tol);
    EXPECT_NEAR(c.g, expected.g, tol);
    EXPECT_NEAR(c.b, expected.b, tol);
}

TEST(Tracer, MissReturnsBackground) {
    TestScene t;
    t.AddSphere(1, {0, 0, 0}, Matte(0.1, 0.5));
    bool hit = true;
    ExpectColor(t.Trace({{5, 5, 5}, {0, 0, 1}, 0}, hit), {0.2, 0.3, 0.4});
    EXPECT_FALSE(hit);
}

TEST(Tracer, AmbientPlusLambertPlusPhong) {
    // Looking straight down at the top of a unit sphere with the light overhead:
    // cosθ = 1 and the mirror direction points at the light (cosα = 1).
    TestScene t;
    Surface s = Matte(0.1, 0.5);
    s.specular = Color(0.25);
    s.specpow = 10;
    t.AddSphere(1, {0, 0, 0}, s);
    bool hit = false;
    ExpectColor(t.Trace({{0, 0, 5}, {0, 0, -1}, 0}, hit), Color(0.1 + 0.5 + 0.25));
    EXPECT_TRUE(hit);
}

TEST(Tracer, LambertCosineOffAxis) {
    // Hit point at 60° from the light direction: diffuse term 0.5·cos 60°.
    TestScene t;
    t.AddSphere(1, {0, 0, 0}, Matte(0, 0.5));
    Vec3 p{std::sin(M_PI / 3), 0, std::cos(M_PI / 3)};
    bool hit = false;
    Color c = t.Trace({p * 3.0, -p, 0}, hit);
    ExpectColor(c, Color(0.25), 1e-9);
}

TEST(Tracer, OpaqueOccluderCastsShadow) {
    TestScene t;
    t.AddSphere(1, {0, 0, 0}, Matte(0.1, 0.5));
    t.AddSphere(0.2, {0, 0, 3}, Matte(0, 0));  // between the sphere top and the light
    bool hit = false;
    ExpectColor(t.Trace({{0.05, 0, 2.5}, Normalize(Vec3{-0.05, 0, -1.5}), 0}, hit), Color(0.1), 1e-9);
}

TEST(Tracer, TransparentOccluderFiltersShadowLight) {
    TestScene t;
    t.AddSphere(1, {0, 0, 0}, Matte(0, 0.5));
    Surface filter = Matte(0, 0);
    filter.transp = 0.5;
    filter.body = Color(1, 0.5, 0.25);
    t.AddSphere(0.2, {0, 0, 3}, filter);
    bool hit = false;
    // Eye ray from the side so it does not pass through the filter itself. The shadow ray
    // crosses the filter sphere twice (enter, leave): light × (0.5·body)², interior extinct 1.
    Vec3 top{0, 0, 1};
    Color c = t.Trace({top + Vec3{3, 0, 0.5}, Normalize(Vec3{-3, 0, -0.5}), 0}, hit);
    Color expectedLight = Color(0.25) * Color(1, 0.25, 0.0625);
    ExpectColor(c, expectedLight * 0.5, 1e-6);
}

TEST(Tracer, MirrorReflectsTheBackgroundTintedBySpecular) {
    TestScene t;
    Surface mirror = Matte(0, 0);
    mirror.specular = Color(0.8);
    mirror.specpow = 0;  // no highlight, only the reflection
    mirror.reflect = 0.5;
    t.AddSphere(1, {0, 0, 0}, mirror);
    bool hit = false;
    Color c = t.Trace({{0, 0, 5}, {0, 0, -1}, 0}, hit);
    ExpectColor(c, Color(0.2, 0.3, 0.4) * 0.4);
}

TEST(Tracer, IndexOneGlassPassesRaysStraightThrough) {
    TestScene t;
    Surface glass = Matte(0, 0);
    glass.transp = 1;
    glass.index = 1;
    t.AddSphere(1, {0, 0, 0}, glass);
    t.scene.lights.clear();
    bool hit = false;
    // Enters and leaves the sphere undeviated, then sees the background (body 1, clear).
    Color c = t.Trace({{0, 0, 5}, {0, 0, -1}, 0}, hit);
    ExpectColor(c, Color(0.2, 0.3, 0.4));
}

TEST(Tracer, ExtinctionAttenuatesByDistanceInside) {
    TestScene t;
    Surface glass = Matte(0, 0);
    glass.transp = 1;
    glass.index = 1;
    glass.extinct = 0.5;  // half the light survives each unit length inside
    t.AddSphere(1, {0, 0, 0}, glass);
    t.scene.lights.clear();
    bool hit = false;
    Color c = t.Trace({{0, 0, 5}, {0, 0, -1}, 0}, hit);
    ExpectColor(c, Color(0.2, 0.3, 0.4) * 0.25, 1e-9);  // chord 2 → 0.5²
}

TEST(Tracer, MaxDepthZeroDisablesSecondaryRays) {
    TestScene t;
    Surface mirror = Matte(0.1, 0);
    mirror.specular = Color(1);
    mirror.specpow = 0;
    mirror.reflect = 1;
    t.AddSphere(1, {0, 0, 0}, mirror);
    t.scene.options.maxDepth = 0;
    bool hit = false;
    ExpectColor(t.Trace({{0, 0, 5}, {0, 0, -1}, 0}, hit), Color(0.1));
}

}  // namespace
}  // namespace rs
