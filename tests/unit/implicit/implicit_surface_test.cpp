#include "libobj/implicit/implicit_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "libobj/blob.h"
#include "libobj/implicit/patches_method.h"
#include "token_reader.h"
#include "libsurf/surface.h"

namespace rs {
namespace {

// The patches of an object searched by method patches.
const PatchesMethod& PatchesOf(const ImplicitSurface& surface) {
    return dynamic_cast<const PatchesMethod&>(surface.SearchMethod());
}

std::shared_ptr<Primitive> Parse(const std::string& text) {
    TokenReader reader(text);
    std::shared_ptr<Primitive> p = ImplicitSurface::Create(reader);
    EXPECT_TRUE(reader.AtEnd());
    return p;
}

// Ray i of a deterministic spread: from `distance` away from the origin, its directions
// spiralling over the sphere, toward a point of the box [−spread, spread].
Ray SpreadRay(int i, double distance, const Vec3& spread) {
    const double a = 0.41 * i, b = 0.13 * i;
    const Vec3 o{distance * std::cos(a) * std::cos(b), distance * std::sin(a) * std::cos(b),
                 distance * std::sin(b)};
    const Vec3 target{spread.x * std::sin(1.7 * i), spread.y * std::cos(2.3 * i),
                      spread.z * std::sin(0.9 * i)};
    return Ray{o, Normalize(target - o)};
}

std::optional<double> Hit(const Primitive& p, const Ray& ray, PrimitiveHit* out = nullptr) {
    PrimitiveHit hit;
    if (!p.Intersect(ray, 1e-5, 1e9, hit)) return std::nullopt;
    if (out) *out = hit;
    return hit.t;
}

TEST(ImplicitSurface, SinglePointIsSphereWithOutwardNormal) {
    auto p = Parse("threshold 1 field quadratic 0.5 2 1.2 point a 0 0 0 end");
    ASSERT_TRUE(p);
    EXPECT_TRUE(p->IsClosed());
    PrimitiveHit hit;
    Ray ray{{0, 0, -5}, {0, 0, 1}};
    auto t = Hit(*p, ray, &hit);
    ASSERT_TRUE(t.has_value());
    EXPECT_NEAR(*t, 4.5, 1e-7);
    SurfaceNormals n = p->Normal(ray.At(*t), hit);
    EXPECT_NEAR(n.geometric.z, -1, 1e-9);
    // A tilted hit: the normal is radial.
    Ray tilted{{0.3, 0, -5}, {0, 0, 1}};
    auto t2 = Hit(*p, tilted, &hit);
    ASSERT_TRUE(t2.has_value());
    Vec3 q = tilted.At(*t2);
    SurfaceNormals n2 = p->Normal(q, hit);
    EXPECT_NEAR(Dot(n2.shading, Normalize(q)), 1, 1e-9);
    EXPECT_TRUE(p->Bounds().Contains(q));
}

TEST(ImplicitSurface, InvalidKernelFailsNamingTheSkeleton) {
    TokenReader reader("field linear 1 2 3 point arm 0 0 0 end");
    try {
        ImplicitSurface::Create(reader);
        FAIL() << "expected a failure";
    } catch (const FatalError& e) {
        EXPECT_NE(std::string(e.what()).find("'arm'"), std::string::npos) << e.what();
    }
}

TEST(ImplicitSurface, UnknownStatementAndUnknownBlendNameFail) {
    TokenReader bad("point a 0 0 0 sphere 1 end");
    EXPECT_THROW(ImplicitSurface::Create(bad), FatalError);
    TokenReader badBlend("point a 0 0 0 blend a b end");
    EXPECT_THROW(ImplicitSurface::Create(badBlend), FatalError);
    TokenReader twice("point a 0 0 0 point a 1 0 0 end");
    EXPECT_THROW(ImplicitSurface::Create(twice), FatalError);
}

TEST(ImplicitSurface, BlendStatementsSelectPairs) {
    // a and b overlap but do not blend (union, crease at x = 0 with y = ±0.4); b and c do.
    auto p = Parse("field quadratic 0.5 2 1.2 point a -0.3 0 0 point b 0.3 0 0 "
                   "point c 0.3 2 0 blend b c end");
    ASSERT_TRUE(p);
    auto t = Hit(*p, {{0, -5, 0}, {0, 1, 0}});
    ASSERT_TRUE(t.has_value());
    EXPECT_NEAR(*t, 4.6, 1e-7);
    auto blended = Parse("field quadratic 0.5 2 1.2 point a -0.3 0 0 point b 0.3 0 0 end");
    auto tb = Hit(*blended, {{0, -5, 0}, {0, 1, 0}});
    ASSERT_TRUE(tb.has_value());
    EXPECT_LT(*tb, 4.59);
}

TEST(ImplicitSurface, Kb89MethodMatchesPatches) {
    std::string body = "field quadratic 0.35 2.4 0.9 point a 0 0 0 point b 0.5 0.1 0 "
                       "segment s -0.5 -0.4 0 0.3 0.6 0.2 weight 0.8 "
                       "point hole 0.2 0 0.3 weight -0.5 field blob 1 0.4 "
                       "cylinder c 0.1 0 0 -1 0 0 -0.5 box bx 0.5 0.5 0.5 0.7 0.7 0.7 "
                       "triangle tr 1 0 0 1.2 0 0 1 0.2 0 circle ring 0.3 -0.8 0 0 0 1 0 "
                       "polyline pl 3 0 1 0 0.3 1 0 0.3 1.3 0.3 ";
    auto patches = Parse(body + "end");
    auto kb89 = Parse(body + "method kb89 octree 4 end");
    ASSERT_TRUE(patches && kb89);
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
        const Ray ray = SpreadRay(i, 5, {0.4, 0.4, 0.3});
        auto t1 = Hit(*patches, ray);
        auto t2 = Hit(*kb89, ray);
        ASSERT_EQ(t1.has_value(), t2.has_value()) << i;
        if (t1) {
            ++hits;
            EXPECT_NEAR(*t1, *t2, 2e-7) << i;
        }
    }
    EXPECT_GT(hits, 100);
}

// Many patches (found through the BVH over patch boxes) against one octree over the plain
// sum, on random rays.
TEST(ImplicitSurface, ManyPatchesMatchTheSingleOctree) {
    std::vector<FieldTerm> terms;
    for (int i = 0; i < 150; ++i) {
        // A deterministic scatter in [-3, 3]³ (golden-ratio sequences).
        Vec3 c{6 * std::fmod(0.618034 * i, 1.0) - 3, 6 * std::fmod(0.754878 * i, 1.0) - 3,
               6 * std::fmod(0.569840 * i, 1.0) - 3};
        terms.push_back({"p", PointSkeleton{c}, Kernel::GascuelQuadratic(0.35, 2.4, 0.9), 1});
    }
    ImplicitSurface patches(terms, ImplicitOptions{});
    ImplicitOptions single;
    single.method = ImplicitMethod::Kb89;
    ImplicitSurface whole(terms, single);
    EXPECT_EQ(PatchesOf(patches).Patches().size(), 150u);
    int hits = 0;
    for (int i = 0; i < 600; ++i) {
        const Ray ray = SpreadRay(i, 9, {3, 3, 3});
        PrimitiveHit h1, h2;
        bool got1 = patches.Intersect(ray, 1e-5, 1e9, h1);
        bool got2 = whole.Intersect(ray, 1e-5, 1e9, h2);
        ASSERT_EQ(got1, got2) << i;
        if (got1) {
            ++hits;
            EXPECT_NEAR(h1.t, h2.t, 2e-7) << i;
            EXPECT_TRUE(patches.Bounds().Contains(ray.At(h1.t)));
        }
    }
    EXPECT_GT(hits, 200);
}

// The blob kernel is Rayshade's metaball: point skeletons with `field blob s r` and the
// same threshold trace, with the LG octrees of method patches, the same surface as the
// `blob` primitive (closed-form quartics).
TEST(ImplicitSurface, BlobKernelMatchesTheBlobPrimitive) {
    std::vector<Metaball> balls{{{0, 0, 0}, 1.0, 1.0}, {{0.6, 0.2, 0}, 0.7, 0.8},
                                {{-0.4, 0.5, 0.3}, 1.2, 1.5}, {{0.2, -0.6, -0.3}, 0.5, 0.6}};
    Blob blob(0.5, balls);
    std::string text = "threshold 0.5 method patches ";
    for (size_t i = 0; i < balls.size(); ++i) {
        const Metaball& b = balls[i];
        text += StringPrintf("point b%zu %g %g %g field blob %g %g ", i, b.centre.x, b.centre.y,
                             b.centre.z, b.strength, b.radius);
    }
    auto implicit = Parse(text + "end");
    ASSERT_TRUE(implicit);
    int hits = 0;
    for (int i = 0; i < 500; ++i) {
        const Ray ray = SpreadRay(i, 5, {0.8, 0.8, 0.6});
        PrimitiveHit h1, h2;
        bool got1 = implicit->Intersect(ray, 1e-5, 1e9, h1);
        bool got2 = blob.Intersect(ray, 1e-5, 1e9, h2);
        ASSERT_EQ(got1, got2) << i;
        if (got1) {
            ++hits;
            EXPECT_NEAR(h1.t, h2.t, 1e-6) << i;
        }
    }
    EXPECT_GT(hits, 150);
}

TEST(ImplicitSurface, AnimatedSkeletonsRebuildPerFrame) {
    auto p = Parse("field quadratic 0.5 2 1.2 point a TIME 0 0 end");
    ASSERT_TRUE(p);
    Ray ray{{-5, 0, 0}, {1, 0, 0}};
    EXPECT_NEAR(*Hit(*p, ray), 4.5, 1e-7);
    p->PrepareFrame(1.0, 0);
    EXPECT_NEAR(*Hit(*p, ray), 5.5, 1e-7);
    EXPECT_TRUE(p->Bounds().Contains({1.5, 0, 0}));
}

// `method NAME [Step]`: every method finds the sphere of radius e = 0.5 at t = 4.5, the
// baselines hit with part −1 (no patch), rebuild per frame like the octree methods, and blend
// statements are ignored with a warning.
TEST(ImplicitSurface, MethodStatementSelectsTheBaselines) {
    for (const char* method : {"march", "march 0.01", "sphere", "segment", "exact", "kb89"}) {
        auto p = Parse(std::string("tolerance 1e-9 method ") + method +
                       " field quadratic 0.5 2 1.2 point a TIME 0 0 end");
        ASSERT_TRUE(p) << method;
        auto* surface = dynamic_cast<ImplicitSurface*>(p.get());
        ASSERT_TRUE(surface);
        const std::string name = std::string(method).substr(0, std::string(method).find(' '));
        EXPECT_EQ(ImplicitMethodName(surface->Method()), name);
        PrimitiveHit hit;
        Ray ray{{-5, 0, 0}, {1, 0, 0}};
        auto t = Hit(*p, ray, &hit);
        ASSERT_TRUE(t) << method;
        EXPECT_NEAR(*t, 4.5, 1e-9) << method;
        EXPECT_EQ(hit.part, -1) << method;
        EXPECT_EQ(surface->PatchName(hit), "") << method;
        EXPECT_NEAR(p->Normal(ray.At(*t), hit).geometric.x, -1, 1e-9) << method;
        p->PrepareFrame(1.0, 0);
        EXPECT_NEAR(*Hit(*p, ray), 5.5, 1e-9) << method;
    }
    TokenReader blended("method sphere point a 0 0 0 point b 1 0 0 blend a b end");
    ASSERT_TRUE(ImplicitSurface::Create(blended));
    ASSERT_EQ(blended.warnings.size(), 1u);
    EXPECT_NE(blended.warnings[0].find("'method sphere'"), std::string::npos);
}

// Without a method statement (or with `method auto`), blob-kernel points and segments that
// all blend are searched by polynomial, and its hits carry the automatic patch of the
// predominant skeleton: the same surface and the same patch names as method patches on
// random rays.
TEST(ImplicitSurface, AutoMethodIsPolynomialWithThePatchesOfMethodPatches) {
    const std::string body = "threshold 0.5 field blob 1 1 point a -0.4 0 0 point b 0.45 0.1 0 "
                             "point c 0 0.5 0.2 point d 0.1 -0.2 0.6 weight -0.3 "
                             "segment e 0.2 -0.5 -0.3 0.6 -0.1 -0.4 field blob 0.8 0.7 ";
    for (const char* method : {"", "method auto "}) {
        auto automatic = Parse(body + method + "end");
        auto patches = Parse(body + "method patches tolerance 1e-10 end");
        ASSERT_TRUE(automatic && patches);
        auto* a = dynamic_cast<ImplicitSurface*>(automatic.get());
        auto* p = dynamic_cast<ImplicitSurface*>(patches.get());
        EXPECT_EQ(a->Method(), ImplicitMethod::Polynomial) << method;
        int hits = 0;
        for (int i = 0; i < 400; ++i) {
            const Ray ray = SpreadRay(i, 4, {0.5, 0.4, 0.3});
            PrimitiveHit ha, hp;
            bool gotA = automatic->Intersect(ray, 1e-5, 1e9, ha);
            ASSERT_EQ(gotA, patches->Intersect(ray, 1e-5, 1e9, hp)) << i;
            if (!gotA) continue;
            ++hits;
            EXPECT_NEAR(ha.t, hp.t, 1e-8) << i;
            EXPECT_EQ(a->PatchName(ha), p->PatchName(hp)) << i;
            EXPECT_EQ(ha.part, hp.part) << i;
        }
        EXPECT_GT(hits, 150);
    }
    // Blend statements keep patches (only they honour them).
    auto blended = Parse(body + "blend a b end");
    ASSERT_TRUE(blended);
    EXPECT_EQ(dynamic_cast<ImplicitSurface*>(blended.get())->Method(), ImplicitMethod::Patches);
    // Other kernels too.
    auto gascuel = Parse("field quadratic 0.5 2 1.2 point a 0 0 0 end");
    ASSERT_TRUE(gascuel);
    EXPECT_EQ(dynamic_cast<ImplicitSurface*>(gascuel.get())->Method(), ImplicitMethod::Patches);
}

TEST(ImplicitSurface, MethodErrors) {
    for (const char* text : {"method bisection point a 0 0 0 end",
                             "method march 0 point a 0 0 0 end",
                             "method polynomial point a 0 0 0 end",
                             "method polynomial field blob 1 1 triangle t 0 0 0 1 0 0 0 1 0 end"}) {
        TokenReader reader(text);
        EXPECT_THROW(ImplicitSurface::Create(reader), FatalError) << text;
    }
    auto blob = Parse("threshold 0.5 method polynomial field blob 1 1 point a 0 0 0 end");
    ASSERT_TRUE(blob);
    auto t = Hit(*blob, Ray{{0, 0, -5}, {0, 0, 1}});
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 5 - std::sqrt(1 - std::sqrt(0.5)), 1e-12);
    // SetMethod refuses polynomial for Gascuel kernels and leaves the object as it was.
    auto gascuel = Parse("point a 0 0 0 end");
    auto* surface = dynamic_cast<ImplicitSurface*>(gascuel.get());
    EXPECT_NE(surface->SetMethod(ImplicitMethod::Polynomial).find("polynomial"), std::string::npos);
    EXPECT_EQ(surface->Method(), ImplicitMethod::Patches);
    EXPECT_EQ(surface->SetMethod(ImplicitMethod::Exact), "");
    EXPECT_EQ(surface->Method(), ImplicitMethod::Exact);
}

TEST(ImplicitSurface, NoPositiveSkeletonIsDiscardedWithWarning) {
    TokenReader reader("point a 0 0 0 weight -1 end");
    EXPECT_EQ(ImplicitSurface::Create(reader), nullptr);
    EXPECT_EQ(reader.warnings.size(), 1u);
}

// examples/implicit.ray: the articulated ring's two ends overlap without blending, so a ray
// through their overlap meets the union of two end caps of radius e = 0.42 around the end
// points (±0.4104, 0, 0.5724): half-chord sqrt(0.42² − 0.4104²) at x = 0.
TEST(ImplicitSurface, ExampleRingEndsDoNotBlend) {
    std::ifstream in(RAYSHADE_SOURCE_DIR "/examples/implicit.ray");
    ASSERT_TRUE(in.good());
    std::stringstream text;
    text << in.rdbuf();
    std::string scene = text.str();
    size_t begin = scene.find("implicit skin");
    ASSERT_NE(begin, std::string::npos);
    begin += std::string("implicit skin").size();
    size_t end = scene.find("\nend", begin);
    ASSERT_NE(end, std::string::npos);
    std::string block = scene.substr(begin, end + 4 - begin);
    for (char& c : block) {
        if (c == '\n' || c == '\t') c = ' ';
    }
    auto ring = Parse(block);
    ASSERT_TRUE(ring);
    auto t = Hit(*ring, {{0, -5, 0.5724}, {0, 1, 0}});
    ASSERT_TRUE(t.has_value());
    EXPECT_NEAR(*t, 5 - std::sqrt(0.42 * 0.42 - 0.4104 * 0.4104), 1e-6);
}

// The lone blob sphere of the benchmark kernel: s(1 − r²/R²)² = T at r = R·sqrt(1 − sqrt(T/s)).
constexpr const char* kBlobSphere = "threshold 0.6 field blob 1 1 point a 0 0 0 end";
const double kBlobRadius = std::sqrt(1 - std::sqrt(0.6));

// Rays along +z from z = −5 at seeded offsets inside the sphere's silhouette, with their
// analytic first root.
std::vector<std::pair<Ray, double>> SphereRays(int count, double radius) {
    std::mt19937 rng(4242);
    std::uniform_real_distribution<double> u(-0.9 * radius, 0.9 * radius);
    std::vector<std::pair<Ray, double>> rays;
    while (static_cast<int>(rays.size()) < count) {
        double x = u(rng), y = u(rng);
        if (x * x + y * y > 0.81 * radius * radius) continue;
        const double depth = std::sqrt(radius * radius - x * x - y * y);
        rays.push_back({Ray{{x, y, -5}, {0, 0, 1}}, 5 - depth});
    }
    return rays;
}

TEST(ImplicitSurface, AutoToleranceIsAnEighthOfTheFootprint) {
    auto p = Parse(kBlobSphere);  // tolerance auto is the default
    ASSERT_TRUE(p);
    // Footprints of 0.002 + 0.01t and 1e-6 + 1e-7t: the first is capped at 1e-6 (a tenth of
    // the renderer's spawn offset), the second sets 1.25e-7 + 1.25e-8t.
    for (auto [width, spread] : {std::pair{0.002, 0.01}, std::pair{1e-6, 1e-7}}) {
        for (auto [ray, exact] : SphereRays(100, kBlobRadius)) {
            auto fixed = Hit(*p, ray);  // no footprint: the fixed 1e-7
            ASSERT_TRUE(fixed.has_value());
            EXPECT_NEAR(*fixed, exact, 1e-7);
            ray.footprintWidth = width;
            ray.footprintSpread = spread;
            auto t = Hit(*p, ray);
            ASSERT_TRUE(t.has_value());
            const double tolerance = std::min(0.125 * (width + spread * exact), 1e-6);
            EXPECT_LE(std::abs(*t - exact), tolerance + 1e-12);
        }
    }
}

TEST(ImplicitSurface, ExplicitToleranceIgnoresTheFootprint) {
    auto p = Parse("threshold 0.6 tolerance 1e-9 octree auto 2 field blob 1 1 point a 0 0 0 end");
    ASSERT_TRUE(p);
    for (auto [ray, exact] : SphereRays(50, kBlobRadius)) {
        ray.footprintSpread = 0.05;
        auto t = Hit(*p, ray);
        ASSERT_TRUE(t.has_value());
        EXPECT_NEAR(*t, exact, 1e-9 + 1e-14);
    }
    TokenReader bad("tolerance fine point a 0 0 0 end");
    EXPECT_THROW(ImplicitSurface::Create(bad), FatalError);
    EXPECT_TRUE(Parse("octree 5 tolerance auto point a 0 0 0 end"));
}

// Octrees are built by the first ray reaching each patch, on any thread: concurrent first
// rays must see the same trees (and hits) as one thread does.
TEST(ImplicitSurface, LazyTreesGiveTheSameHitsFromManyThreads) {
    std::string text = "threshold 0.6 field blob 1 1";
    for (int i = 0; i < 40; ++i) {
        text += " point p" + std::to_string(i) + " " + std::to_string(0.6 * i) + " " +
                std::to_string(0.3 * std::sin(i)) + " 0";
    }
    text += " end";
    std::vector<Ray> rays;
    for (int i = 0; i < 400; ++i) rays.push_back({{0.06 * i, -5, 0.02 * (i % 17)}, {0, 1, 0}});
    auto serial = Parse(text);
    std::vector<double> expected;
    for (const Ray& r : rays) expected.push_back(Hit(*serial, r).value_or(-1));
    auto shared = Parse(text);
    std::vector<std::vector<double>> got(4);
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k) {
        threads.emplace_back([&, k] {
            for (size_t i = 0; i < rays.size(); ++i) {
                const Ray& r = rays[(i + 97 * k) % rays.size()];
                got[k].push_back(Hit(*shared, r).value_or(-1));
            }
        });
    }
    for (std::thread& t : threads) t.join();
    for (int k = 0; k < 4; ++k) {
        for (size_t i = 0; i < rays.size(); ++i) {
            EXPECT_EQ(got[k][i], expected[(i + 97 * k) % rays.size()]) << k << " " << i;
        }
    }
}

// An object of more than 2,048 patches (per-cell trees, neighbour lists made by the first
// ray needing each patch): a chain of 2,500 Gascuel points 0.6 apart on a seeded random
// walk. Hits from four threads sharing the object equal one thread's bit for bit, and
// agree with method exact (no miss, no false hit, depth within 10 tolerances of 1e-7).
TEST(ImplicitSurface, LazyPatchesOfALargeObjectMatchExactFromManyThreads) {
    std::mt19937 rng(19);
    std::normal_distribution<double> step(0, 1);
    std::string text = "field linear 0.45 2 1";
    Vec3 c{0, 0, 0};
    for (int i = 0; i < 2500; ++i) {
        Vec3 d{step(rng), step(rng), step(rng)};
        c = c + Normalize(d) * 0.6;
        // Confined to a cube of edge 16 (reflected at its faces).
        for (int a = 0; a < 3; ++a) {
            if (std::abs(c[a]) > 8) c[a] = std::copysign(16, c[a]) - c[a];
        }
        std::ostringstream line;
        line.precision(17);
        line << " point p" << i << " " << c.x << " " << c.y << " " << c.z;
        text += line.str();
    }
    auto lazy = Parse(text + " end");
    auto exact = Parse(text + " method exact end");
    ASSERT_GT(PatchesOf(static_cast<ImplicitSurface&>(*lazy)).Patches().size(), 2048u);
    std::vector<Ray> rays;
    for (int i = 0; i < 240; ++i) rays.push_back(SpreadRay(i, 30, {8, 8, 8}));
    std::vector<std::vector<double>> got(4);
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k) {
        threads.emplace_back([&, k] {
            for (size_t i = 0; i < rays.size(); ++i) {
                got[k].push_back(Hit(*lazy, rays[(i + 61 * k) % rays.size()]).value_or(-1));
            }
        });
    }
    for (std::thread& t : threads) t.join();
    int hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const double want = Hit(*exact, rays[i]).value_or(-1);
        const double serial = got[0][i];
        ASSERT_EQ(want < 0, serial < 0) << i;
        if (want >= 0) {
            ++hits;
            EXPECT_NEAR(serial, want, 1e-6) << i;
        }
        for (int k = 1; k < 4; ++k) {
            EXPECT_EQ(got[k][(i + rays.size() - 61 * k % rays.size()) % rays.size()], serial)
                << k << " " << i;
        }
    }
    EXPECT_GT(hits, 60);
}

}  // namespace
}  // namespace rs

namespace rs {
namespace {

// Two unit spheres (default kernel: e = 1, R = 2) centred at x = ±0.8, in contact.
constexpr const char* kContactPair =
    "point a -0.8 0 0 point b 0.8 0 0 contact a b propagation a 0.3 propagation b 0.3 0.5 end";

TEST(ImplicitContact, StatementsParseAndFailLocated) {
    auto p = Parse(kContactPair);
    ASSERT_TRUE(p);
    EXPECT_EQ(PatchesOf(static_cast<ImplicitSurface&>(*p)).Patches().size(), 2u);
    for (const char* bad : {"point a 0 0 0 contact a c end", "point a 0 0 0 contact a a end",
                            "point a 0 0 0 point b 1 0 0 blend a b contact a b end",
                            "point a 0 0 0 point b 1 0 0 contact a b propagation a -1 end",
                            "point a 0 0 0 point b 1 0 0 contact a b propagation a 1 2 end",
                            "point a 0 0 0 point b 1 0 0 contact a b propagation c 1 end"}) {
        TokenReader reader(bad);
        EXPECT_THROW(ImplicitSurface::Create(reader), FatalError) << bad;
    }
    TokenReader lonely("point a 0 0 0 point b 3 0 0 propagation a 0.2 end");
    EXPECT_TRUE(ImplicitSurface::Create(lonely));
    EXPECT_EQ(lonely.warnings.size(), 1u);
}

// From inside either sphere, in any direction through the contact disk, the first hit is on
// the symmetry plane to the tolerance (1e-7). From outside, the rim is where the undeformed
// spheres cross (x = 0, ρ = 0.6): there f_a = f_b = 1 and the bulge term is 0.
TEST(ImplicitContact, SymmetricSpheresMeetOnTheSymmetryPlane) {
    auto p = Parse(kContactPair);
    ASSERT_TRUE(p);
    for (int i = 0; i < 400; ++i) {
        double phi = 2 * 3.14159265358979 * i / 400, r = 0.5 * (i % 7) / 6;
        Vec3 target{0, r * std::cos(phi), r * std::sin(phi)};
        for (double side : {-1.0, 1.0}) {
            Vec3 origin{0.05 * side, target.y * 0.5, target.z * 0.5 + 0.01 * (i % 3)};
            Ray ray{origin, Normalize(target - origin)};
            PrimitiveHit hit;
            auto t = Hit(*p, ray, &hit);
            ASSERT_TRUE(t.has_value()) << i;
            EXPECT_LE(std::abs(ray.At(*t).x), 1e-7) << i;
            Vec3 n = p->Normal(ray.At(*t), hit).geometric;
            // Leaving one sphere and entering the other at the same point (either patch may
            // report it): the normal is ±x.
            EXPECT_NEAR(std::abs(n.x), 1, 1e-6) << i;
        }
    }
    auto rim = Hit(*p, {{0, -5, 0}, {0, 1, 0}});
    ASSERT_TRUE(rim.has_value());
    EXPECT_NEAR(*rim, 4.4, 1e-7);
    // The far sides are untouched spheres.
    EXPECT_NEAR(*Hit(*p, {{-5, 0, 0}, {1, 0, 0}}), 3.2, 1e-7);
}

// Contacts follow animated skeletons: b moves from interpenetration (t = 0.8) to a gap of
// 0.1 (t = 1.3), narrower than the zone; the bulge switches off and a is a plain sphere.
TEST(ImplicitContact, ContactFollowsAnimation) {
    auto p = Parse("point a -0.8 0 0 point b TIME 0 0 contact a b propagation a 0.3 "
                   "propagation b 0.3 end");
    ASSERT_TRUE(p);
    p->PrepareFrame(0.8, 0);
    EXPECT_NEAR(*Hit(*p, {{0, -5, 0}, {0, 1, 0}}), 4.4, 1e-7);
    p->PrepareFrame(1.3, 0);
    Ray between{{0.25, 0, 0}, {-1, 0, 0}};  // in the gap, towards a's surface at x = 0.2
    EXPECT_NEAR(*Hit(*p, between), 0.05, 1e-7);
    // In that frame a point of the gap between the two undeformed spheres is outside both.
    EXPECT_NEAR(*Hit(*p, {{0.25, 0, 0}, {1, 0, 0}}), 0.05, 1e-7);
}

// The wire boxes drawn in examples/implicit/fig7.ray are the deformation boxes of its
// deformed patches (DeformedPatch::affected), rounded outward to 0.01, as its comment says.
TEST(ImplicitContact, Figure7BoxesAreTheDeformationBoxes) {
    std::ifstream in(RAYSHADE_SOURCE_DIR "/examples/implicit/fig7.ray");
    ASSERT_TRUE(in.good());
    std::stringstream text;
    text << in.rdbuf();
    const std::string scene = text.str();
    size_t begin = scene.find("implicit clay");
    ASSERT_NE(begin, std::string::npos);
    begin += std::string("implicit clay").size();
    size_t end = scene.find("\nend", begin);
    ASSERT_NE(end, std::string::npos);
    std::string block = scene.substr(begin, end + 4 - begin);
    for (char& c : block) {
        if (c == '\n' || c == '\t') c = ' ';
    }
    auto p = Parse(block);
    ASSERT_TRUE(p);
    const auto& surface = static_cast<const ImplicitSurface&>(*p);
    // The boxes in the file, one per "deformation box of NAME" comment, from the corners of
    // the wire cylinders that follow it.
    std::map<std::string, Bounds3> drawn;
    std::string current;
    std::istringstream lines(scene);
    std::string line;
    while (std::getline(lines, line)) {
        const std::string marker = "/* deformation box of ";
        if (line.rfind(marker, 0) == 0) {
            current = line.substr(marker.size(), line.find(' ', marker.size()) - marker.size());
        } else if (line.rfind("cylinder wire", 0) == 0) {
            std::istringstream numbers(line.substr(std::string("cylinder wire").size()));
            double r;
            Vec3 a, b;
            numbers >> r >> a.x >> a.y >> a.z >> b.x >> b.y >> b.z;
            drawn[current].Extend(a);
            drawn[current].Extend(b);
        }
    }
    int deformed = 0;
    for (const DeformedPatch& d : PatchesOf(surface).Contacts()) {
        if (!d.deformed) continue;
        ++deformed;
        std::string name = surface.Terms()[d.patch].name;  // one patch per term here
        ASSERT_TRUE(drawn.count(name)) << name;
        const Bounds3& box = drawn[name];
        for (int axis = 0; axis < 3; ++axis) {  // rounded outward by less than 0.01
            EXPECT_LE(box.lo[axis], d.affected.lo[axis] + 1e-6) << name;
            EXPECT_GT(box.lo[axis], d.affected.lo[axis] - 0.01) << name;
            EXPECT_GE(box.hi[axis], d.affected.hi[axis] - 1e-6) << name;
            EXPECT_LT(box.hi[axis], d.affected.hi[axis] + 0.01) << name;
        }
    }
    EXPECT_EQ(deformed, static_cast<int>(drawn.size()));
}

}  // namespace
}  // namespace rs
