#include "libobj/implicit/implicit_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "libobj/blob.h"
#include "libsurf/surface.h"

namespace rs {
namespace {

// An ArgReader over whitespace-separated tokens. The token TIME reads as the animated
// number equal to the frame time.
class TokenReader final : public ArgReader {
  public:
    explicit TokenReader(const std::string& text) {
        size_t i = 0;
        while (i < text.size()) {
            size_t j = text.find_first_of(" \n", i);
            if (j == std::string::npos) j = text.size();
            if (j > i) tokens_.push_back(text.substr(i, j - i));
            i = j + 1;
        }
    }
    double ReadNumber() override {
        if (!PeekNumber()) Fail("expected a number");
        return std::strtod(tokens_[pos_++].c_str(), nullptr);
    }
    int ReadInt() override { return static_cast<int>(ReadNumber()); }
    AnimatedValue ReadAnimatedNumber() override {
        AnimatedValue v;
        if (Accept("TIME")) {
            v.at = [](double t) { return t; };
        } else {
            v.value = ReadNumber();
        }
        return v;
    }
    bool PeekNumber() override {
        if (pos_ >= tokens_.size()) return false;
        if (tokens_[pos_] == "TIME") return true;
        char* end = nullptr;
        std::strtod(tokens_[pos_].c_str(), &end);
        return *end == '\0';
    }
    bool Accept(const char* word) override {
        if (!Peek(word)) return false;
        ++pos_;
        return true;
    }
    bool Peek(const char* word) override { return pos_ < tokens_.size() && tokens_[pos_] == word; }
    std::string ReadName() override {
        if (pos_ >= tokens_.size() || PeekNumber()) Fail("expected a name");
        return tokens_[pos_++];
    }
    std::string ReadFilename() override { return ReadName(); }
    bool PeekFilename() override { return pos_ < tokens_.size() && !PeekNumber(); }
    Surface ReadSurface() override { return Surface{}; }
    bool FlipNormals() const override { return false; }
    SourceLocation Location() const override { return {}; }
    void Warn(const std::string& message) override { warnings.push_back(message); }
    void Advise(const std::string& message) override { warnings.push_back(message); }
    [[noreturn]] void Fail(const std::string& message) override {
        throw FatalError(Severity::Abort, message);
    }
    bool AtEnd() const { return pos_ == tokens_.size(); }

    std::vector<std::string> warnings;

  private:
    std::vector<std::string> tokens_;
    size_t pos_ = 0;
};

std::shared_ptr<Primitive> Parse(const std::string& text) {
    TokenReader reader(text);
    std::shared_ptr<Primitive> p = ImplicitSurface::Create(reader);
    EXPECT_TRUE(reader.AtEnd());
    return p;
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
        double a = 0.1 * i, b = 0.037 * i;
        Vec3 o{5 * std::cos(a) * std::cos(b), 5 * std::sin(a) * std::cos(b), 5 * std::sin(b)};
        Vec3 target{0.4 * std::sin(3.1 * i), 0.4 * std::cos(1.7 * i), 0.3 * std::sin(0.7 * i)};
        Ray ray{o, Normalize(target - o)};
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
    EXPECT_EQ(patches.PatchCount(), 150);
    int hits = 0;
    for (int i = 0; i < 600; ++i) {
        double a = 0.37 * i, b = 0.11 * i;
        Vec3 o{9 * std::cos(a) * std::cos(b), 9 * std::sin(a) * std::cos(b), 9 * std::sin(b)};
        Vec3 target{3 * std::sin(1.3 * i), 3 * std::cos(2.9 * i), 3 * std::sin(0.53 * i)};
        Ray ray{o, Normalize(target - o)};
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
// same threshold trace the same surface as the `blob` primitive (closed-form quartics).
TEST(ImplicitSurface, BlobKernelMatchesTheBlobPrimitive) {
    std::vector<Blob::Ball> balls{{1.0, 1.0, {0, 0, 0}}, {0.8, 0.7, {0.6, 0.2, 0}},
                                  {1.5, 1.2, {-0.4, 0.5, 0.3}}, {0.6, 0.5, {0.2, -0.6, -0.3}}};
    Blob blob(0.5, balls);
    std::string text = "threshold 0.5 ";
    for (size_t i = 0; i < balls.size(); ++i) {
        const Blob::Ball& b = balls[i];
        text += StringPrintf("point b%zu %g %g %g field blob %g %g ", i, b.centre.x, b.centre.y,
                             b.centre.z, b.strength, b.radius);
    }
    auto implicit = Parse(text + "end");
    ASSERT_TRUE(implicit);
    int hits = 0;
    for (int i = 0; i < 500; ++i) {
        double a = 0.41 * i, b = 0.13 * i;
        Vec3 o{5 * std::cos(a) * std::cos(b), 5 * std::sin(a) * std::cos(b), 5 * std::sin(b)};
        Vec3 target{0.8 * std::sin(1.7 * i), 0.8 * std::cos(2.3 * i), 0.6 * std::sin(0.9 * i)};
        Ray ray{o, Normalize(target - o)};
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
    p->PrepareFrame(1.0);
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
        p->PrepareFrame(1.0);
        EXPECT_NEAR(*Hit(*p, ray), 5.5, 1e-9) << method;
    }
    TokenReader blended("method sphere point a 0 0 0 point b 1 0 0 blend a b end");
    ASSERT_TRUE(ImplicitSurface::Create(blended));
    ASSERT_EQ(blended.warnings.size(), 1u);
    EXPECT_NE(blended.warnings[0].find("'method sphere'"), std::string::npos);
}

TEST(ImplicitSurface, MethodErrors) {
    for (const char* text : {"method bisection point a 0 0 0 end",
                             "method march 0 point a 0 0 0 end",
                             "method polynomial point a 0 0 0 end",
                             "method polynomial field blob 1 1 segment s 0 0 0 1 0 0 end"}) {
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

}  // namespace
}  // namespace rs
