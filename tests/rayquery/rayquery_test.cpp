// rayquery against analytic answers. Each test writes a scene and a ray file, runs the
// program as a child process and compares its lines with closed-form intersections.
//
// Tangency policy of the implicit primitive (libray/libobj/implicit/README.md,
// "Guarantee"): a root is reported only where a sign change of F − T is observed, so
// false hits never occur; a grazing ray may be reported as a miss only when its contact
// is shorter than the minimum width w (= the object's tolerance) and its excursion above
// T is below G·w²/32. Exact tangency (no sign change) is therefore a miss or, through
// rounding, a hit at the tangent point; rays whose chord through the surface is much longer
// than w must hit. The tests below assert exactly that: chords of at least 2e·sqrt(2·1e-9)
// (≈ 7e-5 for e = 0.8, far above w = 1e-9) hit, rays passing outside by any relative
// margin ≥ 1e-12 miss, and exact tangency is not asserted beyond "miss, or hit at the
// tangent point".
//
// Property tests are seeded; every failure message names the seed and the ray.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "libcommon/vector.h"

namespace rs {
namespace {

struct QueryLine {
    bool hit = false;
    double t = 0;
    Vec3 p, n;
    std::string object, patch;
    long evals = -1;
};

struct RunResult {
    int status = -1;
    std::vector<QueryLine> lines;
    std::string stdErr;
};

struct QueryRay {
    Vec3 o, d;
    double tMin = -1, tMax = -1;  // < 0: not written (program defaults)
};

std::string ReadAll(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs rayquery with `args` on `scene` and the given ray file text.
RunResult RunText(const std::string& scene, const std::string& rays, const std::string& args) {
    static int serial = 0;
    std::filesystem::create_directories(RAYQUERY_WORK_DIR);
    std::string base = std::string(RAYQUERY_WORK_DIR) + "/" +
                       ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                       std::to_string(serial++);
    std::ofstream(base + ".ray") << scene;
    std::ofstream(base + ".rays") << rays;
    std::string command = std::string(RAYQUERY_BINARY) + " " + args + " " + base + ".ray < " +
                          base + ".rays > " + base + ".out 2> " + base + ".err";
    RunResult r;
    int raw = std::system(command.c_str());
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.stdErr = ReadAll(base + ".err");
    std::istringstream out(ReadAll(base + ".out"));
    std::string line;
    while (std::getline(out, line)) {
        std::istringstream in(line);
        QueryLine q;
        std::string word;
        in >> word;
        if (word == "hit") {
            q.hit = true;
            in >> q.t >> q.p.x >> q.p.y >> q.p.z >> q.n.x >> q.n.y >> q.n.z >> q.object >> q.patch;
        } else {
            EXPECT_EQ(word, "miss") << line;
        }
        in >> q.evals;
        EXPECT_FALSE(in.fail()) << "malformed output line: " << line;
        r.lines.push_back(q);
    }
    return r;
}

std::string FormatRays(const std::vector<QueryRay>& rays) {
    std::string text;
    char buf[512];
    for (const QueryRay& r : rays) {
        std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g %.17g %.17g %.17g", r.o.x, r.o.y, r.o.z,
                      r.d.x, r.d.y, r.d.z);
        text += buf;
        if (r.tMin >= 0) {
            std::snprintf(buf, sizeof buf, " %.17g", r.tMin);
            text += buf;
        }
        if (r.tMax >= 0) {
            std::snprintf(buf, sizeof buf, " %.17g", r.tMax);
            text += buf;
        }
        text += "\n";
    }
    return text;
}

std::vector<QueryLine> RunQueries(const std::string& scene, const std::vector<QueryRay>& rays,
                           const std::string& args = "") {
    RunResult r = RunText(scene, FormatRays(rays), args);
    EXPECT_EQ(r.status, 0) << r.stdErr;
    EXPECT_EQ(r.lines.size(), rays.size()) << r.stdErr;
    r.lines.resize(rays.size());
    return r.lines;
}

std::string Describe(uint64_t seed, size_t i, const QueryRay& r) {
    char buf[400];
    std::snprintf(buf, sizeof buf, "seed %llu, ray %zu: %.17g %.17g %.17g %.17g %.17g %.17g",
                  static_cast<unsigned long long>(seed), i, r.o.x, r.o.y, r.o.z, r.d.x, r.d.y,
                  r.d.z);
    return buf;
}

Vec3 RandomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    for (;;) {
        Vec3 v{g(rng), g(rng), g(rng)};
        if (LengthSquared(v) > 1e-6) return Normalize(v);
    }
}

// A unit vector perpendicular to u.
Vec3 Perpendicular(const Vec3& u, std::mt19937_64& rng) {
    for (;;) {
        Vec3 v = RandomUnit(rng);
        Vec3 w = v - u * Dot(u, v);
        if (LengthSquared(w) > 1e-6) return Normalize(w);
    }
}

// First t > tMin with |o + t·d − c| = radius, or −1.
double SphereEntry(const Vec3& o, const Vec3& d, const Vec3& c, double radius, double tMin = 0) {
    Vec3 oc = o - c;
    double a = Dot(d, d), b = Dot(oc, d), cc = Dot(oc, oc) - radius * radius;
    double disc = b * b - a * cc;
    if (disc < 0) return -1;
    double s = std::sqrt(disc);
    double t0 = (-b - s) / a, t1 = (-b + s) / a;
    if (t0 > tMin) return t0;
    if (t1 > tMin) return t1;
    return -1;
}

constexpr const char* kSurface = "surface s diffuse 1 1 1\n";

// One point skeleton: the sphere of radius e (quadratic kernel) around c.
std::string SphereScene(const Vec3& c, const std::string& field, const std::string& extra = "") {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%sname ball implicit s\n tolerance 1e-9\n %s\n %s\n point c %.17g %.17g %.17g\n"
                  "end\nobject ball\n",
                  kSurface, extra.c_str(), field.c_str(), c.x, c.y, c.z);
    return buf;
}

// Builds rays whose line passes at distance b from c, starting L before the closest point,
// with directions of random length (t is in units of the given direction).
QueryRay RayPassing(const Vec3& c, double b, double L, std::mt19937_64& rng, double& scale) {
    Vec3 v = RandomUnit(rng);
    Vec3 w = Perpendicular(v, rng);
    scale = std::uniform_real_distribution<double>(0.25, 4)(rng);
    QueryRay r;
    r.o = c + w * b - v * L;
    r.d = v * scale;
    return r;
}

// Appends RayPassing(c, b, L) and its analytic answer for a sphere of `radius` at c: the
// entry parameter (L − sqrt(radius² − b²))/scale when b < radius, else −1 (a miss).
void AddSphereRay(const Vec3& c, double radius, double b, double L, std::mt19937_64& rng,
                  std::vector<QueryRay>& rays, std::vector<double>& expected) {
    double scale;
    rays.push_back(RayPassing(c, b, L, rng, scale));
    expected.push_back(b < radius ? (L - std::sqrt(radius * radius - b * b)) / scale : -1);
}

void ExpectOnSphere(const QueryLine& q, const QueryRay& r, const Vec3& c, double radius,
                    double expectedT, const std::string& what) {
    ASSERT_TRUE(q.hit) << what;
    double dirLength = Length(r.d);
    // Tolerance 1e-9 in distance; 1e-7 leaves room for the rounding of the inputs.
    EXPECT_NEAR(q.t * dirLength, expectedT * dirLength, 1e-7) << what;
    EXPECT_NEAR(Length(q.p - c), radius, 1e-7) << what;
    Vec3 radial = Normalize(q.p - c);
    EXPECT_NEAR(Length(q.n - radial), 0, 1e-6) << what;  // outward, not flipped to the ray
    EXPECT_NEAR(Length(q.n), 1, 1e-12) << what;
}

TEST(RayQuery, PointSkeletonIsSphereOfRadiusThickness) {
    const uint64_t seed = 20261122;
    std::mt19937_64 rng(seed);
    const Vec3 c{0.3, -0.2, 0.1};
    struct Case {
        std::string field;
        double radius;
    };
    // Quadratic/linear: radius e exactly. Blob s(1 − r²/R²)² = 1: r = R·sqrt(1 − sqrt(1/s)).
    const Case cases[] = {{"field quadratic 0.8 1 2", 0.8},
                          {"field linear 0.8 1.5 2", 0.8},
                          {"field blob 2 1.5", 1.5 * std::sqrt(1 - std::sqrt(0.5))}};
    for (const Case& k : cases) {
        std::vector<QueryRay> rays;
        std::vector<double> expected;
        for (int i = 0; i < 200; ++i) {
            double e = k.radius;
            double L = std::uniform_real_distribution<double>(2, 30)(rng);
            bool hit = i % 2 == 0;
            double b = hit ? std::uniform_real_distribution<double>(0, 0.999)(rng) * e
                           : std::uniform_real_distribution<double>(1.001, 1.9)(rng) * e;
            AddSphereRay(c, e, b, L, rng, rays, expected);
        }
        std::vector<QueryLine> out = RunQueries(SphereScene(c, k.field), rays);
        for (size_t i = 0; i < rays.size(); ++i) {
            std::string what = k.field + ": " + Describe(seed, i, rays[i]);
            if (expected[i] < 0) {
                EXPECT_FALSE(out[i].hit) << what;
                continue;
            }
            ExpectOnSphere(out[i], rays[i], c, k.radius, expected[i], what);
            EXPECT_EQ(out[i].object, "ball") << what;
            EXPECT_EQ(out[i].patch, "c") << what;
            EXPECT_GT(out[i].evals, 0) << what;
        }
    }
}

TEST(RayQuery, GrazingRaysJustInsideHitJustOutsideMiss) {
    const uint64_t seed = 7;
    std::mt19937_64 rng(seed);
    const Vec3 c{-1, 2, 0.5};
    const double e = 0.8;
    std::vector<QueryRay> rays;
    std::vector<double> b;
    for (double delta : {1e-3, 1e-6, 1e-9}) {
        for (int i = 0; i < 10; ++i) {
            double scale;
            rays.push_back(RayPassing(c, e * (1 - delta), 5, rng, scale));
            b.push_back(e * (1 - delta));
            rays.push_back(RayPassing(c, e * (1 + delta), 5, rng, scale));
            b.push_back(e * (1 + delta));
        }
    }
    for (int i = 0; i < 10; ++i) {
        double scale;
        rays.push_back(RayPassing(c, e * (1 + 1e-12), 5, rng, scale));
        b.push_back(e * (1 + 1e-12));
    }
    std::vector<QueryLine> out = RunQueries(SphereScene(c, "field quadratic 0.8 1 2"), rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        std::string what = Describe(seed, i, rays[i]);
        // The ray's actual distance to c, from the rounded inputs.
        Vec3 u = Normalize(rays[i].d);
        Vec3 oc = c - rays[i].o;
        double miss = Length(oc - u * Dot(oc, u));
        if (b[i] < e) {
            double t = SphereEntry(rays[i].o, rays[i].d, c, e);
            ASSERT_GT(t, 0) << what;
            ASSERT_TRUE(out[i].hit) << what << " (passes at " << miss / e << " e)";
            EXPECT_NEAR(out[i].t * Length(rays[i].d), t * Length(rays[i].d), 1e-7) << what;
        } else {
            EXPECT_FALSE(out[i].hit) << what << " (passes at " << miss / e << " e)";
        }
    }
}

TEST(RayQuery, ExactTangencyIsMissOrTangentPoint) {
    std::mt19937_64 rng(11);
    const Vec3 c{0, 0, 0};
    std::vector<QueryRay> rays;
    for (int i = 0; i < 20; ++i) {
        double scale;
        rays.push_back(RayPassing(c, 0.8, 4, rng, scale));
    }
    std::vector<QueryLine> out = RunQueries(SphereScene(c, "field quadratic 0.8 1 2"), rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        if (!out[i].hit) continue;
        Vec3 tangent = rays[i].o + Normalize(rays[i].d) * 4;
        EXPECT_NEAR(Length(out[i].p - tangent), 0, 1e-3) << Describe(11, i, rays[i]);
    }
}

TEST(RayQuery, RaysStartingInsideFindTheExit) {
    const uint64_t seed = 99;
    std::mt19937_64 rng(seed);
    const Vec3 c{1, 1, 1};
    const double e = 0.8;
    std::vector<QueryRay> rays;
    for (int i = 0; i < 100; ++i) {
        QueryRay r;
        r.o = c + RandomUnit(rng) * (std::uniform_real_distribution<double>(0, 0.95)(rng) * e);
        r.d = RandomUnit(rng) * std::uniform_real_distribution<double>(0.5, 2)(rng);
        rays.push_back(r);
    }
    std::vector<QueryLine> out = RunQueries(SphereScene(c, "field quadratic 0.8 1 2"), rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        double t = SphereEntry(rays[i].o, rays[i].d, c, e);
        ExpectOnSphere(out[i], rays[i], c, e, t, Describe(seed, i, rays[i]));
    }
}

TEST(RayQuery, SearchIntervalAndTransformedInstances) {
    // The sphere of radius 0.8 scaled by 2 about the origin and moved to (1, 0, 0).
    std::string scene = std::string(kSurface) +
                        "name ball implicit s\n tolerance 1e-9 field quadratic 0.8 1 2\n"
                        " point c 0 0 0\nend\nobject ball scale 2 2 2 translate 1 0 0\n";
    std::vector<QueryRay> rays(5);
    rays[0] = {{1, -10, 0}, {0, 1, 0}, -1, -1};   // enters at y = −1.6: t = 8.4
    rays[1] = {{1, -10, 0}, {0, 1, 0}, 9, -1};    // tMin past the entry: exit at t = 11.6
    rays[2] = {{1, -10, 0}, {0, 1, 0}, 0, 8};     // tMax before the entry: miss
    rays[3] = {{1, -10, 0}, {0, 0.5, 0}, -1, -1}; // half-length direction: t = 16.8
    rays[4] = {{3, -10, 0}, {0, 1, 0}, -1, -1};   // passes at 2 > 1.6: miss
    std::vector<QueryLine> out = RunQueries(scene, rays);
    ASSERT_TRUE(out[0].hit);
    EXPECT_NEAR(out[0].t, 8.4, 1e-7);
    EXPECT_NEAR(Length(out[0].n - Vec3{0, -1, 0}), 0, 1e-9);
    ASSERT_TRUE(out[1].hit);
    EXPECT_NEAR(out[1].t, 11.6, 1e-7);
    EXPECT_NEAR(Length(out[1].n - Vec3{0, 1, 0}), 0, 1e-9);  // outward: not flipped
    EXPECT_FALSE(out[2].hit);
    EXPECT_EQ(out[2].evals, 0);  // the object's box is not reached within (0, 8)
    ASSERT_TRUE(out[3].hit);
    EXPECT_NEAR(out[3].t, 16.8, 2e-7);
    EXPECT_FALSE(out[4].hit);
}

// Entry t into the capsule of radius e around segment [a, b] for a ray starting outside:
// the smallest entry among the cylinder side (within the segment's span) and the two end
// spheres (the union's entry is the first of its parts' entries).
double CapsuleEntry(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, double e) {
    double best = -1;
    auto consider = [&best](double t) {
        if (t > 0 && (best < 0 || t < best)) best = t;
    };
    consider(SphereEntry(o, d, a, e));
    consider(SphereEntry(o, d, b, e));
    Vec3 axis = Normalize(b - a);
    Vec3 op = (o - a) - axis * Dot(o - a, axis), dp = d - axis * Dot(d, axis);
    double qa = Dot(dp, dp), qb = Dot(op, dp), qc = Dot(op, op) - e * e;
    double disc = qb * qb - qa * qc;
    if (qa > 0 && disc >= 0) {
        double t = (-qb - std::sqrt(disc)) / qa;
        double s = Dot(o + d * t - a, axis);
        if (s >= 0 && s <= Length(b - a)) consider(t);
    }
    return best;
}

TEST(RayQuery, SegmentSkeletonIsCapsule) {
    const uint64_t seed = 4242;
    std::mt19937_64 rng(seed);
    const Vec3 a{-1, 0.5, 0}, b{1.5, -0.5, 1};
    const double e = 0.6;
    std::string scene = std::string(kSurface) +
                        "name cap implicit s\n tolerance 1e-9 field quadratic 0.6 2 1.5\n"
                        " segment bone -1 0.5 0 1.5 -0.5 1\nend\nobject cap\n";
    std::vector<QueryRay> rays;
    std::uniform_real_distribution<double> u01(0, 1);
    for (int i = 0; i < 300; ++i) {
        QueryRay r;
        r.o = (a + b) * 0.5 + RandomUnit(rng) * std::uniform_real_distribution<double>(4, 10)(rng);
        // Aim at random points around the segment, some beyond its reach.
        Vec3 target = a + (b - a) * u01(rng) + RandomUnit(rng) * (1.5 * e * u01(rng));
        r.d = (target - r.o) * std::uniform_real_distribution<double>(0.3, 3)(rng);
        rays.push_back(r);
    }
    std::vector<QueryLine> out = RunQueries(scene, rays);
    int hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        std::string what = Describe(seed, i, rays[i]);
        double t = CapsuleEntry(rays[i].o, rays[i].d, a, b, e);
        if (t < 0) {
            EXPECT_FALSE(out[i].hit) << what;
            continue;
        }
        ++hits;
        ASSERT_TRUE(out[i].hit) << what;
        EXPECT_NEAR(out[i].t * Length(rays[i].d), t * Length(rays[i].d), 1e-7) << what;
        // Normal: from the closest segment point to the hit.
        Vec3 axis = Normalize(b - a);
        double s = std::fmin(std::fmax(Dot(out[i].p - a, axis), 0), Length(b - a));
        Vec3 radial = Normalize(out[i].p - (a + axis * s));
        EXPECT_NEAR(Length(out[i].n - radial), 0, 1e-6) << what;
        EXPECT_EQ(out[i].object, "cap") << what;
        EXPECT_EQ(out[i].patch, "bone") << what;
    }
    EXPECT_GT(hits, 100);
}

// Blended points along a random walk: automatic patches and the plain sum (kb89, one
// octree) are the same surface, so every ray must agree on hit/miss and t. A crack at a
// patch boundary would show as a miss or a later hit of the patches; a doubled surface as
// an earlier one.
TEST(RayQuery, AutomaticPatchesMatchPlainSum) {
    const uint64_t seed = 31337;
    std::mt19937_64 rng(seed);
    std::string scene = std::string(kSurface) +
                        "name chain implicit s\n tolerance 1e-9 field quadratic 0.5 1.5 1.4\n";
    Vec3 p{0, 0, 0}, lo = p, hi = p;
    for (int i = 0; i < 12; ++i) {
        char buf[200];
        std::snprintf(buf, sizeof buf, " point p%d %.17g %.17g %.17g\n", i, p.x, p.y, p.z);
        scene += buf;
        p += RandomUnit(rng) * 0.6;
        lo = Min(lo, p);
        hi = Max(hi, p);
    }
    scene += "end\nobject chain\n";
    std::vector<QueryRay> rays;
    std::uniform_real_distribution<double> u01(0, 1);
    Vec3 centre = (lo + hi) * 0.5;
    for (int i = 0; i < 600; ++i) {
        QueryRay r;
        r.o = centre + RandomUnit(rng) * 8;
        Vec3 target{lo.x - 0.5 + (hi.x - lo.x + 1) * u01(rng),
                    lo.y - 0.5 + (hi.y - lo.y + 1) * u01(rng),
                    lo.z - 0.5 + (hi.z - lo.z + 1) * u01(rng)};
        r.d = Normalize(target - r.o);
        rays.push_back(r);
    }
    std::vector<QueryLine> patches = RunQueries(scene, rays, "-m patches");
    std::vector<QueryLine> plain = RunQueries(scene, rays, "-m kb89");
    int hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        std::string what = Describe(seed, i, rays[i]);
        ASSERT_EQ(patches[i].hit, plain[i].hit) << what;
        if (!plain[i].hit) continue;
        ++hits;
        EXPECT_NEAR(patches[i].t, plain[i].t, 1e-7) << what;
        EXPECT_NEAR(Length(patches[i].n - plain[i].n), 0, 1e-5) << what;
        EXPECT_NE(patches[i].patch, "-") << what;
        EXPECT_EQ(plain[i].patch, "-") << what;
    }
    EXPECT_GT(hits, 150);
}

// With blend lists only declared pairs blend: a and b overlap but do not blend (a blends
// only with the far-away c), so the surface near them is the union of two spheres of
// radius e. Without the blend list the two merge into a larger blob.
TEST(RayQuery, ExplicitBlendListsGiveUnionOfSpheres) {
    const Vec3 a{0, 0, 0}, b{1.0, 0, 0};
    const double e = 0.6;
    auto sceneWith = [](const std::string& blend) {
        return std::string(kSurface) +
               "name pair implicit s\n tolerance 1e-9 field quadratic 0.6 1 1.5\n"
               " point a 0 0 0\n point b 1 0 0\n point c 0 0 50\n" + blend +
               "end\nobject pair\n";
    };
    const uint64_t seed = 5;
    std::mt19937_64 rng(seed);
    std::vector<QueryRay> rays;
    for (int i = 0; i < 300; ++i) {
        QueryRay r;
        r.o = Vec3{0.5, 0, 0} + RandomUnit(rng) * 6;
        Vec3 target = Vec3{-0.8 + 2.6 * std::uniform_real_distribution<double>(0, 1)(rng), 0, 0} +
                      RandomUnit(rng) * std::uniform_real_distribution<double>(0, 0.9)(rng);
        r.d = target - r.o;
        rays.push_back(r);
    }
    std::vector<QueryLine> out = RunQueries(sceneWith(" blend a c\n"), rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        std::string what = Describe(seed, i, rays[i]);
        double ta = SphereEntry(rays[i].o, rays[i].d, a, e);
        double tb = SphereEntry(rays[i].o, rays[i].d, b, e);
        if (ta < 0 && tb < 0) {
            EXPECT_FALSE(out[i].hit) << what;
            continue;
        }
        bool first = tb < 0 || (ta > 0 && ta < tb);
        double t = first ? ta : tb;
        ASSERT_TRUE(out[i].hit) << what;
        EXPECT_NEAR(out[i].t * Length(rays[i].d), t * Length(rays[i].d), 1e-7) << what;
        EXPECT_EQ(out[i].patch, first ? "a" : "b") << what;
    }
    // Blended (no blend list): the ray along the y axis through the midpoint, which passes
    // at 0.5 < e from both centres, enters earlier than either sphere: F at the sphere
    // entry is 1 plus b's positive contribution there, so the surface lies farther out.
    std::vector<QueryRay> mid{{{0.5, -5, 0}, {0, 1, 0}, -1, -1}};
    double tSphere = 5 - std::sqrt(e * e - 0.25);
    std::vector<QueryLine> merged = RunQueries(sceneWith(""), mid);
    ASSERT_TRUE(merged[0].hit);
    EXPECT_LT(merged[0].t, tSphere - 0.01);
}

// Two identical unit spheres (point skeletons, e = 1) at x = ±0.8 in contact, with bulges:
// the contact surface is the symmetry plane x = 0 (libray/libobj/implicit/README.md,
// Contact). From inside either sphere, rays through the contact disk (ρ < 0.6) in random
// directions stop on the plane to the tolerance (1e-9; 1e-8 allows for the input
// rounding). Rays lying in the plane find the rim circle ρ = 0.6, where the undeformed
// spheres cross (f_a = f_b = 1 and the bulge term vanishes there): nothing of either
// deformed surface crosses the plane outside the rim. Those rays are tangent to the
// deformed surfaces at the rim (G1: the bulge leaves the rim tangent to the plane); in the
// plane F − T = −u + δ(u) with u = 1 − f, which is −3u³/w² for b's height 1, so F − T stays
// within rounding (1e-16) of 0 for u up to about 1e-6: the rim is found to 1e-5 only.
TEST(RayQuery, ContactSurfaceOfTwoSpheresIsTheSymmetryPlane) {
    const std::string scene = std::string(kSurface) +
                              "name pair implicit s\n tolerance 1e-9\n point a -0.8 0 0\n"
                              " point b 0.8 0 0\n contact a b\n propagation a 0.3\n"
                              " propagation b 0.3 1\nend\nobject pair\n";
    const uint64_t seed = 55;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<QueryRay> inside, inPlane;
    while (inside.size() < 400) {
        double side = inside.size() % 2 == 0 ? -1 : 1;
        double phi = 2 * M_PI * unit(rng), rho = 0.55 * std::sqrt(unit(rng));
        Vec3 target{0, rho * std::cos(phi), rho * std::sin(phi)};
        Vec3 d = RandomUnit(rng);
        if (d.x * side > 0) d = -d;  // from the `side` half towards the plane
        if (std::abs(d.x) < 0.05) continue;
        QueryRay r;
        r.o = target - d * (0.1 / std::abs(d.x));
        if (r.o.y * r.o.y + r.o.z * r.o.z > 0.3) continue;  // keep the start inside
        r.d = d * std::uniform_real_distribution<double>(0.5, 2)(rng);
        inside.push_back(r);
    }
    for (int i = 0; i < 200; ++i) {
        double phi = 2 * M_PI * unit(rng);
        Vec3 u{0, std::cos(phi), std::sin(phi)}, v{0, -u.z, u.y};
        QueryRay r;
        r.o = u * 4 + v * (0.5 * (unit(rng) - 0.5));  // offsets up to 0.25 from the axis
        r.d = -u;
        inPlane.push_back(r);
    }
    std::vector<QueryLine> out = RunQueries(scene, inside);
    for (size_t i = 0; i < inside.size(); ++i) {
        std::string what = Describe(seed, i, inside[i]);
        ASSERT_TRUE(out[i].hit) << what;
        EXPECT_LE(std::abs(out[i].p.x), 1e-8) << what;
        EXPECT_NEAR(std::abs(out[i].n.x), 1, 1e-6) << what;
        EXPECT_TRUE(out[i].patch == "a" || out[i].patch == "b") << what;
    }
    std::vector<QueryLine> rim = RunQueries(scene, inPlane);
    for (size_t i = 0; i < inPlane.size(); ++i) {
        std::string what = Describe(seed, 1000 + i, inPlane[i]);
        ASSERT_TRUE(rim[i].hit) << what;
        EXPECT_NEAR(std::sqrt(rim[i].p.y * rim[i].p.y + rim[i].p.z * rim[i].p.z), 0.6, 1e-5)
            << what;
        EXPECT_LE(std::abs(rim[i].p.x), 1e-8) << what;
    }
}

TEST(RayQuery, BadInputIsReportedWithLineNumbers) {
    std::string scene = SphereScene({0, 0, 0}, "field quadratic 0.8 1 2");
    struct Case {
        std::string rays, message;
    };
    const Case cases[] = {
        {"0 -5 0 0 1 0\n# comment\n0 -5 0 0 1\n", "standard input:3: expected"},
        {"0 -5 0 0 1 0 0 1 0 3\n", "standard input:1: expected"},
        {"0 -5 0 0 1 0 0 1 2\n", "standard input:1: time 2 is outside the frame's exposure"},
        {"0 -5 0 0 1 zero\n", "standard input:1: 'zero' is not a number"},
        {"0 -5 0 0 0 0\n", "standard input:1: the direction is zero"},
        {"0 -5 0 0 1 0 3 2\n", "standard input:1: tmin 3 is not below tmax 2"},
        {"0 -5 0 0 1 0 nan\n", "standard input:1: 'nan' is not a finite number"},
    };
    for (const Case& c : cases) {
        RunResult r = RunText(scene, c.rays, "");
        EXPECT_NE(r.status, 0) << c.rays;
        EXPECT_NE(r.stdErr.find(c.message), std::string::npos) << c.rays << " -> " << r.stdErr;
    }
    // Lines before the bad one are answered.
    RunResult first = RunText(scene, cases[0].rays, "");
    ASSERT_EQ(first.lines.size(), 1u);
    EXPECT_TRUE(first.lines[0].hit);

    RunResult badMethod = RunText(scene, "", "-m nosuch");
    EXPECT_NE(badMethod.status, 0);
    EXPECT_NE(badMethod.stdErr.find("-m: unknown method 'nosuch'"), std::string::npos);

    RunResult badScene = RunText("name ball implicit s\n point c 0 0 0\nend\n", "", "");
    EXPECT_NE(badScene.status, 0);
    EXPECT_NE(badScene.stdErr.find(".ray:1:"), std::string::npos) << badScene.stdErr;
}

// -m with every method: non-grazing rays (impact parameter <= 0.95e, directions of random
// length) find the sphere of radius e within the tolerance (-e 1e-9, checked to 1e-7 as
// above), and misses passing outside by 0.1 % or more are misses. Only patches names a patch.
TEST(RayQuery, EveryMethodFindsTheSphere) {
    const uint64_t seed = 606;
    const Vec3 c{0.3, -0.2, 0.1};
    const double e = 0.8;
    for (const char* method : {"patches", "kb89", "march", "sphere", "segment", "exact"}) {
        std::mt19937_64 rng(seed);
        std::vector<QueryRay> rays;
        std::vector<double> expected;
        for (int i = 0; i < 60; ++i) {
            double L = std::uniform_real_distribution<double>(2, 30)(rng);
            bool hit = i % 3 != 0;
            double b = hit ? std::uniform_real_distribution<double>(0, 0.95)(rng) * e
                           : std::uniform_real_distribution<double>(1.001, 1.9)(rng) * e;
            AddSphereRay(c, e, b, L, rng, rays, expected);
        }
        std::vector<QueryLine> out =
            RunQueries(SphereScene(c, "field quadratic 0.8 1 2"), rays,
                       std::string("-e 1e-9 -m ") + method);
        for (size_t i = 0; i < rays.size(); ++i) {
            std::string what = std::string(method) + ": " + Describe(seed, i, rays[i]);
            if (expected[i] < 0) {
                EXPECT_FALSE(out[i].hit) << what;
                continue;
            }
            ExpectOnSphere(out[i], rays[i], c, e, expected[i], what);
            EXPECT_EQ(out[i].patch, std::string(method) == "patches" ? "c" : "-") << what;
            EXPECT_GT(out[i].evals, 0) << what;
        }
    }
}

// -e is each method's final accuracy: the depth error stays within it, coarse and fine.
TEST(RayQuery, ToleranceOverrideBoundsTheError) {
    const uint64_t seed = 77;
    const double e = 0.8;
    for (const char* method : {"patches", "kb89", "march", "sphere", "segment"}) {
        for (double eps : {1e-2, 1e-5}) {
            std::mt19937_64 rng(seed);
            std::vector<QueryRay> rays;
            std::vector<double> expected;
            for (int i = 0; i < 40; ++i) {
                double b = std::uniform_real_distribution<double>(0, 0.9)(rng) * e;
                AddSphereRay({0, 0, 0}, e, b, 5, rng, rays, expected);
            }
            char args[64];
            std::snprintf(args, sizeof args, "-m %s -e %g", method, eps);
            std::vector<QueryLine> out =
                RunQueries(SphereScene({0, 0, 0}, "field quadratic 0.8 1 2"), rays, args);
            for (size_t i = 0; i < rays.size(); ++i) {
                std::string what = std::string(args) + ": " + Describe(seed, i, rays[i]);
                ASSERT_TRUE(out[i].hit) << what;
                EXPECT_LE(std::abs(out[i].t - expected[i]) * Length(rays[i].d), eps * (1 + 1e-9))
                    << what;
            }
        }
    }
}

// -k sets the march step; a `method march Step` statement is overridden by it. A sphere of
// diameter 0.1 lies between two samples 0.5 apart (missed) and is found with steps of 0.01.
TEST(RayQuery, MarchStepOverride) {
    const std::string tiny = std::string(kSurface) +
                             "name dot implicit s\n method march 0.5\n tolerance 1e-10\n"
                             " field quadratic 0.05 1 0.1\n point c 0 0 0\nend\nobject dot\n";
    const std::vector<QueryRay> rays = {{{-3, 0, 0}, {1, 0, 0}}};
    EXPECT_FALSE(RunQueries(tiny, rays)[0].hit);
    std::vector<QueryLine> fine = RunQueries(tiny, rays, "-k 0.01");
    ASSERT_TRUE(fine[0].hit);
    EXPECT_NEAR(fine[0].t, 2.95, 1e-9);
    EXPECT_FALSE(RunQueries(tiny, rays, "-m march -k 0.5")[0].hit);
    // The bound-based methods do not depend on a step.
    for (const char* method : {"sphere", "segment", "exact", "patches"}) {
        std::vector<QueryLine> out = RunQueries(tiny, rays, std::string("-m ") + method);
        ASSERT_TRUE(out[0].hit) << method;
        EXPECT_NEAR(out[0].t, 2.95, 1e-9) << method;
    }
}

// polynomial: blob-kernel points and segments only; exact for a blob ball of radius R·sqrt(1 − sqrt(T/s)).
TEST(RayQuery, PolynomialMethodOnBlobsOnly) {
    const double s = 2, radius = 1.5;
    const double r = radius * std::sqrt(1 - std::sqrt(1 / s));
    const uint64_t seed = 31;
    std::mt19937_64 rng(seed);
    std::vector<QueryRay> rays;
    std::vector<double> expected;
    for (int i = 0; i < 50; ++i) {
        double b = std::uniform_real_distribution<double>(0, 0.95)(rng) * r;
        double L = std::uniform_real_distribution<double>(2, 1000)(rng);
        AddSphereRay({1, 2, 3}, r, b, L, rng, rays, expected);
    }
    std::vector<QueryLine> out =
        RunQueries(SphereScene({1, 2, 3}, "field blob 2 1.5", "method polynomial"), rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        ExpectOnSphere(out[i], rays[i], {1, 2, 3}, r, expected[i], Describe(seed, i, rays[i]));
        // The predominant skeleton's automatic patch, the one method patches reports.
        EXPECT_EQ(out[i].patch, "c");
    }
    RunResult wrong =
        RunText(SphereScene({0, 0, 0}, "field quadratic 0.8 1 2"), "", "-m polynomial");
    EXPECT_EQ(wrong.status, 1);
    EXPECT_NE(wrong.stdErr.find("method polynomial needs point or segment skeletons with the "
                                "blob kernel"),
              std::string::npos)
        << wrong.stdErr;
    RunResult inScene =
        RunText(SphereScene({0, 0, 0}, "field quadratic 0.8 1 2", "method polynomial"), "", "");
    EXPECT_EQ(inScene.status, 1);
    EXPECT_NE(inScene.stdErr.find(".ray:"), std::string::npos) << inScene.stdErr;
}

// The octree overrides (-d, -r, -H) change the work, not the answers.
TEST(RayQuery, OctreeOverridesKeepTheAnswers) {
    const uint64_t seed = 99;
    const double e = 0.8;
    std::mt19937_64 rng(seed);
    std::vector<QueryRay> rays;
    std::vector<double> expected;
    for (int i = 0; i < 40; ++i) {
        double b = std::uniform_real_distribution<double>(0, 0.95)(rng) * e;
        AddSphereRay({0, 0, 0}, e, b, 6, rng, rays, expected);
    }
    const std::string scene = SphereScene({0, 0, 0}, "field quadratic 0.8 1 2");
    for (const char* args :
         {"-d 0", "-d 9 -r -1", "-m kb89 -d 3", "-H 1bis=off -H 2bis=off -H 3bis=off",
          "-H t3=off -H t1=off -H 0bis=off", "-H range=off -H patch=off -H 1=off -H 4=off -H 5=off",
          "-H 3=off -d 4", "-m kb89 -H 1bis=on -H 2bis=on"}) {
        std::vector<QueryLine> out = RunQueries(scene, rays, args);
        for (size_t i = 0; i < rays.size(); ++i) {
            ExpectOnSphere(out[i], rays[i], {0, 0, 0}, e, expected[i],
                           std::string(args) + ": " + Describe(seed, i, rays[i]));
        }
    }
    // Depth changes the octree: -v reports fewer cells at depth 1 than at depth 6. Trees are
    // built by the first ray reaching them, hence one ray through the sphere.
    const std::string ray = "0 0 -6 0 0 1\n";
    RunResult shallow = RunText(scene, ray, "-v -d 1"), deep = RunText(scene, ray, "-v -d 6");
    auto cells = [](const std::string& text) {
        size_t at = text.find("Implicit object 1: octree cells:");
        return at == std::string::npos ? -1L
                                       : std::atol(text.c_str() + text.find(':', at + 18) + 1);
    };
    EXPECT_GT(cells(deep.stdErr), cells(shallow.stdErr)) << shallow.stdErr << deep.stdErr;
}

// -f gives every query ray a footprint: `tolerance auto` (the default) then keeps each root
// within an eighth of the footprint at the hit (capped at 1e-6 in units of t, never finer
// than 1e-7 in distance), and a fixed `-e` ignores it. A sphere of radius e = 0.8 seen
// from distance 6.
TEST(RayQuery, FootprintSetsTheAutomaticTolerance) {
    std::mt19937_64 rng(7);
    std::vector<QueryRay> rays;
    std::vector<double> expected;
    const double e = 0.8;
    for (int i = 0; i < 30; ++i) {
        double b = std::uniform_real_distribution<double>(0, 0.9)(rng) * e;
        AddSphereRay({0, 0, 0}, e, b, 6, rng, rays, expected);
    }
    const std::string scene = SphereScene({0, 0, 0}, "field quadratic 0.8 1 2");
    for (const char* args : {"-f 1e-6", "-f 1e-7 2e-6", "-f 0.01 -e 1e-9"}) {
        std::vector<QueryLine> out = RunQueries(scene, rays, args);
        ASSERT_EQ(out.size(), rays.size());
        for (size_t i = 0; i < rays.size(); ++i) {
            ASSERT_TRUE(out[i].hit) << args << " ray " << i;
            const double length = Length(rays[i].d), distance = expected[i] * length;
            double tolerance = 1e-9;  // in distance: -e 1e-9
            if (std::string(args) == "-f 1e-6") tolerance = 0.125 * 1e-6 * distance;
            if (std::string(args) == "-f 1e-7 2e-6") tolerance = 0.125 * (2e-6 + 1e-7 * distance);
            // The cap 1e-6 is in units of t; rounding of the printed inputs adds ~1e-12.
            if (tolerance != 1e-9) tolerance = std::max(std::min(tolerance, 1e-6 * length), 1e-7);
            EXPECT_NEAR(out[i].t * length, distance, tolerance + 1e-11) << args << " ray " << i;
        }
    }
    RunResult bad = RunText(scene, "", "-f -1");
    EXPECT_NE(bad.status, 0);
}

// `method NAME` in a scene file, through the real parser (several method names, such as
// sphere and segment, are keywords of the language).
TEST(RayQuery, SceneMethodStatements) {
    const std::vector<QueryRay> rays = {{{0, -5, 0}, {0, 1, 0}}};
    for (const char* method :
         {"patches", "kb89", "march", "march 0.1", "sphere", "segment", "exact"}) {
        std::vector<QueryLine> out = RunQueries(
            SphereScene({0, 0, 0}, "field quadratic 0.8 1 2", std::string("method ") + method),
            rays);
        ASSERT_TRUE(out[0].hit) << method;
        EXPECT_NEAR(out[0].t, 4.2, 1e-8) << method;
    }
    RunResult bad =
        RunText(SphereScene({0, 0, 0}, "field quadratic 0.8 1 2", "method cone"), "", "");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.stdErr.find("expected a method after 'method': patches, kb89"),
              std::string::npos)
        << bad.stdErr;
}

TEST(RayQuery, BadOverridesAreRejected) {
    const std::string scene = SphereScene({0, 0, 0}, "field quadratic 0.8 1 2");
    struct Case {
        const char *args, *message;
    };
    const Case cases[] = {
        {"-m bisection",
         "-m: unknown method 'bisection' (expected patches, kb89, march, sphere, segment"},
        {"-e 0", "-e: the tolerance must be > 0"},
        {"-e x", "-e: 'x' is not a finite number"},
        {"-d 17", "-d: the octree depth"},
        {"-d 2.5", "-d: the octree depth"},
        {"-k -1", "-k: the march step must be > 0"},
        {"-r", "-r: '"},  // the scene path after it is not a number
        {"-H 1bis", "octree switch '1bis' needs =on or =off"},
        {"-H zz=on", "unknown octree switch 'zz'"},
    };
    for (const Case& c : cases) {
        RunResult r = RunText(scene, "", c.args);
        EXPECT_EQ(r.status, 1) << c.args;
        EXPECT_NE(r.stdErr.find(c.message), std::string::npos) << c.args << " -> " << r.stdErr;
        EXPECT_NE(r.stdErr.find("usage: rayquery"), std::string::npos) << c.args;
    }
}

// The character of the block reference (docs/implicit-reference.md, its last example),
// written from the page alone: limbs blend with the torso only, so the two forearms, whose
// hands end 0.24 apart (thickness e = 0.1) at y = −0.6, z = 1.5, form a union there. A ray
// from the middle of the gap along +x meets the right hand's lone capsule, the surface at
// distance e from the forearm's end (0.12, −0.6, 1.5): t = 0.02; a vertical ray through the
// gap meets nothing. With every pair blending (the same skeletons without blend and contact
// lines) the two hands' fields add up to about 1.8 > T in the gap: a bridge, which both rays
// meet elsewhere, so the test can tell a union from a blend.
std::string CharacterBlock() {
    const std::string page = ReadAll(RAYSHADE_REFERENCE_PAGE);
    const size_t section = page.find("## A character");
    EXPECT_NE(section, std::string::npos);
    const size_t begin = page.find("```ray\n", section) + 7;
    return page.substr(begin, page.find("```", begin) - begin);
}

TEST(RayQuery, ReferenceCharacterLimbsDoNotBlendWithEachOther) {
    const std::string block = CharacterBlock();
    // The rendered example (examples/implicit/character.ray) is this block.
    std::string named = block;
    named.replace(0, std::string("implicit").size(), "implicit skin");
    EXPECT_NE(ReadAll(RAYSHADE_CHARACTER_SCENE).find(named), std::string::npos);

    const std::vector<QueryRay> rays = {{{0, -0.6, 1.5}, {1, 0, 0}},
                                        {{0, -0.6, 5}, {0, 0, -1}}};
    const std::string scene = "surface skin diffuse 1 1 1\n" + block;
    std::vector<QueryLine> out = RunQueries(scene, rays);
    ASSERT_TRUE(out[0].hit);
    EXPECT_NEAR(out[0].t, 0.02, 1e-6);
    EXPECT_EQ(out[0].patch, "farmR");
    EXPECT_NEAR(out[0].n.x, -1, 1e-6);  // the capsule's end cap, facing the gap
    EXPECT_FALSE(out[1].hit) << "t " << out[1].t << " patch " << out[1].patch;

    std::string blended;
    std::istringstream lines(block);
    for (std::string line; std::getline(lines, line);) {
        if (line.find("blend") == std::string::npos && line.find("contact") == std::string::npos)
            blended += line + "\n";
    }
    std::vector<QueryLine> bridge = RunQueries(scene.substr(0, scene.find("implicit")) + blended,
                                               rays);
    EXPECT_TRUE(!bridge[0].hit || std::abs(bridge[0].t - 0.02) > 0.1);
    EXPECT_TRUE(bridge[1].hit);
}

}  // namespace
}  // namespace rs
