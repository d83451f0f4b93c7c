#include "rayshade/tracer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "liblight/directional_light.h"
#include "libobj/list.h"
#include "libobj/object.h"
#include "libobj/sphere.h"
#include "libsurf/surface.h"
#include "libtext/noise.h"

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

// Shadow rays of scenes without transparent surfaces only ask whether anything is hit; a
// transparent surface anywhere, here on an instance inside a nested list, keeps them
// accumulating through occluders, and with transparent shadows off it blocks like any other.
TEST(Tracer, TransparentSurfaceBelowAnInstanceStillFiltersShadowLight) {
    Surface filter = Matte(0, 0);
    filter.transp = 0.5;
    filter.body = Color(1, 0.5, 0.25);
    for (bool transparentShadows : {true, false}) {
        TestScene t;
        t.scene.options.shadowTransparency = transparentShadows;
        t.AddSphere(1, {0, 0, 0}, Matte(0, 0.5));
        auto inner = std::make_shared<ListAggregate>();
        inner->AddChild(Object::MakePrimitive(std::make_shared<Sphere>(0.2, Vec3{0, 0, 3})));
        auto instance = Object::MakeInstance(Object::MakeAggregate(inner));
        instance->surface = std::make_shared<Surface>(filter);
        auto outer = std::make_shared<ListAggregate>();
        outer->AddChild(instance);
        t.list->AddChild(Object::MakeAggregate(outer));
        bool hit = false;
        Vec3 top{0, 0, 1};
        Color c = t.Trace({top + Vec3{3, 0, 0.5}, Normalize(Vec3{-3, 0, -0.5}), 0}, hit);
        Color expected = transparentShadows ? Color(0.25) * Color(1, 0.25, 0.0625) * 0.5 : Color(0);
        ExpectColor(c, expected, 1e-6);
    }
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

// ---- Atmosphere (spec §3.8) ----------------------------------------------------------------
// The probe: a unit sphere at the origin, lit only by ambient 0.5, seen from (x, 0, 5)
// looking straight down, so the eye ray hits at distance 4 (at height 1 when x = 0).

// att(d, T) = ½^(d/T): the fraction of the original colour left after distance d.
double Half(double d, double t) { return std::pow(0.5, d / t); }

Color Fogged(const Color& c, const Color& fog, double ar, double ag, double ab) {
    return {ar * c.r + (1 - ar) * fog.r, ag * c.g + (1 - ag) * fog.g, ab * c.b + (1 - ab) * fog.b};
}

struct AtmosphereScene : TestScene {
    AtmosphereScene() {
        scene.lights.clear();
        AddSphere(1, {0, 0, 0}, Matte(0.5, 0));
    }
    Color Down(double x = 0) {
        bool hit = false;
        return Trace({{x, 0, 5}, {0, 0, -1}, 0}, hit);
    }
};

AtmosphereEffect Fog(const Color& c, const Color& thin) {
    AtmosphereEffect e;
    e.kind = AtmosphereEffect::Kind::Fog;
    e.color = c;
    e.thinness = thin;
    return e;
}

AtmosphereEffect Deck(double altitude, double offset, double chaoScale, int octaves,
                      const Vec3& scale, const Color& c, const Color& thin) {
    AtmosphereEffect e;
    e.kind = AtmosphereEffect::Kind::FogDeck;
    e.altitude = altitude;
    e.offset = offset;
    e.chaoScale = chaoScale;
    e.octaves = octaves;
    e.deckScale = scale;
    e.color = c;
    e.thinness = thin;
    return e;
}

TEST(Atmosphere, FogHalvesTheColourEveryThinnessPerChannel) {
    AtmosphereScene t;
    Color fog(1, 0.5, 0.25);
    t.scene.atmosphere.push_back(Fog(fog, {4, 8, 2}));
    ExpectColor(t.Down(), Fogged(Color(0.5), fog, Half(4, 4), Half(4, 8), Half(4, 2)));
}

TEST(Atmosphere, FogHidesMissesCompletely) {
    // A miss travels kFar: nothing of the background survives.
    AtmosphereScene t;
    t.scene.atmosphere.push_back(Fog({1, 0.5, 0.25}, {4, 8, 2}));
    bool hit = true;
    ExpectColor(t.Trace({{5, 5, 5}, {0, 0, 1}, 0}, hit), {1, 0.5, 0.25});
}

TEST(Atmosphere, ZeroThinnessIsOpaqueAndLongPathsCutOffAtTenHalvings) {
    AtmosphereScene t;
    // Channel r: T = 0 (opaque); g: d/T·ln2 > 10 (att 0); b: just under the cut-off.
    double tb = 4 * std::log(0.5) / -9.9;
    t.scene.atmosphere.push_back(Fog({1, 1, 1}, {0, 4 * std::log(2.0) / 10.5, tb}));
    ExpectColor(t.Down(), Fogged(Color(0.5), Color(1), 0, 0, std::exp(-9.9)), 1e-12);
}

TEST(Atmosphere, EffectsApplyInReverseOrderOfListing) {
    // Listed A then B: B fogs first, A last. On a miss both are opaque, so A's colour wins.
    AtmosphereScene t;
    t.scene.atmosphere.push_back(Fog({1, 0, 0}, Color(1)));
    t.scene.atmosphere.push_back(Fog({0, 0, 1}, Color(1)));
    bool hit = true;
    ExpectColor(t.Trace({{5, 5, 5}, {0, 0, 1}, 0}, hit), {1, 0, 0});
    // On the hit: B then A, each with att = ½^4.
    AtmosphereScene u;
    u.scene.atmosphere = t.scene.atmosphere;
    double a = Half(4, 1);
    ExpectColor(u.Down(), Fogged(Fogged(Color(0.5), {0, 0, 1}, a, a, a), {1, 0, 0}, a, a, a));
}

TEST(Atmosphere, MistOnALevelRayUsesTheDensityAtItsHeight) {
    // Density e^(zero − h/scale); at h = 0 with zero = ln 2 it is 2, doubling the distance.
    AtmosphereScene t;
    AtmosphereEffect mist = Fog({0, 0, 0}, Color(8));
    mist.kind = AtmosphereEffect::Kind::Mist;
    mist.zero = std::log(2.0);
    mist.scale = 3;
    t.scene.atmosphere.push_back(mist);
    bool hit = false;
    Color c = t.Trace({{-5, 0, 0}, {1, 0, 0}, 0}, hit);  // hits (−1, 0, 0) at distance 4
    ExpectColor(c, Color(0.5 * Half(4 * 2, 8)));
}

TEST(Atmosphere, MistOnASlopedRayUsesTheMeanDensityAlongIt) {
    // From height 5 down to height 1 with scale 2, zero 0: the mean of e^(−h/2) over [1, 5]
    // is 2(e^−½ − e^−5/2)/4.
    AtmosphereScene t;
    AtmosphereEffect mist = Fog({0.2, 0.4, 0.6}, {1, 2, 3});
    mist.kind = AtmosphereEffect::Kind::Mist;
    mist.zero = 0;
    mist.scale = 2;
    t.scene.atmosphere.push_back(mist);
    double rho = 2 * (std::exp(-0.5) - std::exp(-2.5)) / 4;
    double d = 4 * rho;
    ExpectColor(t.Down(), Fogged(Color(0.5), mist.color, Half(d, 1), Half(d, 2), Half(d, 3)));
}

TEST(Atmosphere, FogDeckFogsTheRayBeyondTheDeck) {
    // Deck at z = 3 with constant density ρ = offset = 2 (no noise): the ray crosses it at
    // distance 2 and travels 2 more to the sphere, through thinness T/ρ.
    AtmosphereScene t;
    Color fog(0.9, 0.8, 0.7);
    t.scene.atmosphere.push_back(Deck(3, 2, 0, 0, {1, 1, 1}, fog, {4, 2, 1}));
    ExpectColor(t.Down(), Fogged(Color(0.5), fog, Half(2, 2), Half(2, 1), Half(2, 0.5)));
}

TEST(Atmosphere, FogDeckIgnoresRaysThatDoNotCrossItBeforeTheirHit) {
    Color fog(0.9, 0.8, 0.7);
    for (double altitude : {0.5, 7.0}) {  // below the hit point; behind the eye
        AtmosphereScene t;
        t.scene.atmosphere.push_back(Deck(altitude, 2, 0, 0, {1, 1, 1}, fog, Color(1)));
        ExpectColor(t.Down(), Color(0.5));
    }
    AtmosphereScene level;  // parallel to the deck
    level.scene.atmosphere.push_back(Deck(0.5, 2, 0, 0, {1, 1, 1}, fog, Color(1)));
    bool hit = false;
    ExpectColor(level.Trace({{-5, 0, 0}, {1, 0, 0}, 0}, hit), Color(0.5));
}

TEST(Atmosphere, FogDeckWithoutDensityIsClear) {
    AtmosphereScene t;
    t.scene.atmosphere.push_back(Deck(3, 0, 0, 3, {1, 1, 1}, Color(1), Color(1)));
    ExpectColor(t.Down(), Color(0.5));
}

TEST(Atmosphere, FogDeckDensityIsOffsetPlusScaledAbsoluteOctaveSum) {
    // ρ = offset + cs·Σ_{k<2} 2^−k |Noise(2^k p)| at the crossing p = (0.3, 0, 3) scaled by
    // (0.5, 2, 0.25).
    AtmosphereScene t;
    Color fog(0.1, 0.2, 0.3);
    t.scene.atmosphere.push_back(Deck(3, 0.1, 4, 2, {0.5, 2, 0.25}, fog, {1, 2, 3}));
    Vec3 p{0.15, 0, 0.75};
    double rho = 0.1 + 4 * (std::fabs(Noise(p)) + 0.5 * std::fabs(Noise(p * 2.0)));
    double d = 3 - std::sqrt(1 - 0.3 * 0.3);  // from the deck down to the sphere's surface
    ExpectColor(t.Down(0.3),
                Fogged(Color(0.5), fog, Half(d, 1 / rho), Half(d, 2 / rho), Half(d, 3 / rho)),
                1e-9);
}

TEST(Atmosphere, OnlyRaysOutsideObjectsAreFogged) {
    // A clear index-1 glass ball in front of a matte one: the eye ray travels 2 outside
    // (from z = 7 to the glass top at z = 5), 2 inside the glass (not fogged) and 2 outside
    // again (from z = 3 to the matte top at z = 1).
    AtmosphereScene t;
    Surface glass = Matte(0, 0);
    glass.transp = 1;
    glass.index = 1;
    t.AddSphere(1, {0, 0, 4}, glass);
    t.scene.atmosphere.push_back(Fog(Color(1), Color(2)));
    bool hit = false;
    double a = Half(2, 2);
    Color behind = Fogged(Color(0.5), Color(1), a, a, a);
    ExpectColor(t.Trace({{0, 0, 7}, {0, 0, -1}, 0}, hit), Fogged(behind, Color(1), a, a, a));
}

// ---- Atmosphere index of refraction (spec §3.6) ---------------------------------------------

TEST(Atmosphere, IndexMatchedGlassDoesNotBendRays) {
    // A ball of index 1.5 seen off-centre; a red target sits straight behind the entry point.
    // In an atmosphere of index 1.5 the ray crosses the ball undeviated and finds the target;
    // in air (index 1) the ball lens bends it across the axis (focal length nR/(2(n−1)) = 1.5
    // from the centre), far from the target.
    for (double atmosphere : {1.5, 1.0}) {
        TestScene t;
        t.scene.lights.clear();
        t.scene.options.background = Color(0);
        t.scene.atmosphereIndex = atmosphere;
        Surface glass = Matte(0, 0);
        glass.transp = 1;
        glass.index = 1.5;
        t.AddSphere(1, {0, 0, 0}, glass);
        Surface red = Matte(0, 0);
        red.ambient = Color(1, 0, 0);
        t.AddSphere(0.2, {0.5, 0, -3}, red);
        bool hit = false;
        Color c = t.Trace({{0.5, 0, 5}, {0, 0, -1}, 0}, hit);
        ExpectColor(c, atmosphere == 1.5 ? Color(1, 0, 0) : Color(0));
    }
}

}  // namespace
}  // namespace rs
