#include "libobj/heightfield.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "libcommon/random.h"

namespace rs {
namespace {

// Brute force: every present triangle of the field, the nearest hit in (tMin, tMax).
bool BruteForce(int n, const std::vector<float>& h, const Ray& ray, double tMin, double tMax,
                double& tBest) {
    auto vertex = [&](int x, int y) {
        return Vec3{x / double(n - 1), y / double(n - 1), h[y * n + x]};
    };
    auto present = [&](int x, int y) { return h[y * n + x] > -1000; };
    bool found = false;
    tBest = tMax;
    auto test = [&](Vec3 a, Vec3 b, Vec3 c) {
        // Intersect the plane, then an inside test by same-side signs.
        Vec3 nrm = Cross(b - a, c - a);
        double denom = Dot(nrm, ray.dir);
        if (denom == 0) return;
        double t = Dot(nrm, a - ray.origin) / denom;
        if (!(t > tMin && t < tBest)) return;
        Vec3 p = ray.At(t);
        double s1 = Dot(Cross(b - a, p - a), nrm), s2 = Dot(Cross(c - b, p - b), nrm),
               s3 = Dot(Cross(a - c, p - c), nrm);
        if (s1 >= 0 && s2 >= 0 && s3 >= 0) {
            tBest = t;
            found = true;
        }
    };
    for (int y = 0; y + 1 < n; ++y)
        for (int x = 0; x + 1 < n; ++x) {
            if (present(x, y) && present(x + 1, y) && present(x, y + 1))
                test(vertex(x, y), vertex(x + 1, y), vertex(x, y + 1));
            if (present(x + 1, y) && present(x + 1, y + 1) && present(x, y + 1))
                test(vertex(x + 1, y), vertex(x + 1, y + 1), vertex(x, y + 1));
        }
    return found;
}

TEST(HeightField, MatchesBruteForceOnRandomTerrainAndRays) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        Rng rng(seed);
        const int n = 9 + static_cast<int>(seed) * 5;
        std::vector<float> h(n * n);
        for (float& v : h) v = static_cast<float>(0.3 * rng.Uniform());
        if (seed % 2 == 0) h[n * (n / 2) + n / 2] = -2000;  // a hole
        HeightField field(n, h);
        int hits = 0;
        for (int i = 0; i < 3000; ++i) {
            Vec3 o{rng.Uniform() * 3 - 1, rng.Uniform() * 3 - 1, 0.5 + rng.Uniform()};
            Vec3 target{rng.Uniform(), rng.Uniform(), rng.Uniform() * 0.3};
            Ray ray{o, (target - o) * (0.5 + rng.Uniform()), 0};  // non-unit direction
            double tExpected = 0;
            bool expected = BruteForce(n, h, ray, 1e-5, 1e30, tExpected);
            PrimitiveHit hit;
            bool got = field.Intersect(ray, 1e-5, 1e30, hit);
            ASSERT_EQ(got, expected) << "seed " << seed << " ray " << i;
            if (got) {
                ++hits;
                ASSERT_NEAR(hit.t, tExpected, 1e-9) << "seed " << seed << " ray " << i;
            }
        }
        EXPECT_GT(hits, 1000) << "seed " << seed;
    }
}

TEST(HeightField, FlatFieldNormalPointsUp) {
    HeightField field(2, {0.5f, 0.5f, 0.5f, 0.5f});
    PrimitiveHit hit;
    Ray ray{{0.3, 0.4, 2}, {0, 0, -1}, 0};
    ASSERT_TRUE(field.Intersect(ray, 1e-5, 100, hit));
    EXPECT_NEAR(hit.t, 1.5, 1e-12);
    SurfaceNormals n = field.Normal(ray.At(hit.t), hit);
    EXPECT_NEAR(n.geometric.z, 1, 1e-12);
}

TEST(HeightField, ReadRejectsTruncatedAndAbsurdFiles) {
    std::string path = ::testing::TempDir() + "hf_test.bin";
    int n = 0;
    std::vector<float> h;
    std::string error;
    {
        std::ofstream out(path, std::ios::binary);
        int32_t side = 3;
        out.write(reinterpret_cast<const char*>(&side), 4);
        float v = 1;
        for (int i = 0; i < 5; ++i) out.write(reinterpret_cast<const char*>(&v), 4);
    }
    EXPECT_FALSE(ReadHeightFieldFile(path, n, h, error));
    EXPECT_NE(error.find("truncated"), std::string::npos) << error;
    {
        std::ofstream out(path, std::ios::binary);
        int32_t side = 1 << 30;
        out.write(reinterpret_cast<const char*>(&side), 4);
    }
    EXPECT_FALSE(ReadHeightFieldFile(path, n, h, error));
    EXPECT_NE(error.find("invalid size"), std::string::npos) << error;
    EXPECT_FALSE(ReadHeightFieldFile(path + ".missing", n, h, error));
    std::remove(path.c_str());
}

}  // namespace
}  // namespace rs
