// Test doubles and helpers for the primitive tests: an ArgReader that feeds numbers from a
// vector and records diagnostics, plus vector comparisons.
#pragma once

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"
#include "libsurf/surface.h"

namespace rs::testing {

class TestArgReader final : public ArgReader {
  public:
    explicit TestArgReader(std::vector<double> numbers, bool flip = false)
        : numbers_(std::move(numbers)), flip_(flip) {}

    double ReadNumber() override {
        if (next_ >= numbers_.size()) Fail("ran out of numbers");
        return numbers_[next_++];
    }
    int ReadInt() override { return static_cast<int>(ReadNumber()); }
    AnimatedValue ReadAnimatedNumber() override { return {ReadNumber(), {}, {}}; }
    bool PeekNumber() override { return next_ < numbers_.size(); }
    bool Accept(const char*) override { return false; }
    bool Peek(const char*) override { return false; }
    std::string ReadName() override { Fail("no names in this test"); }
    std::string ReadFilename() override { Fail("no file names in this test"); }
    bool PeekFilename() override { return false; }
    Surface ReadSurface() override { return Surface{}; }
    bool FlipNormals() const override { return flip_; }
    SourceLocation Location() const override { return {}; }
    void Warn(const std::string& message) override { warnings.push_back(message); }
    void Advise(const std::string& message) override { advisories.push_back(message); }
    [[noreturn]] void Fail(const std::string& message) override {
        throw FatalError(Severity::Abort, message);
    }

    bool AllConsumed() const { return next_ == numbers_.size(); }

    std::vector<std::string> warnings;
    std::vector<std::string> advisories;

  private:
    std::vector<double> numbers_;
    size_t next_ = 0;
    bool flip_;
};

inline void ExpectVecNear(const Vec3& actual, const Vec3& expected, double tol = 1e-12) {
    EXPECT_NEAR(actual.x, expected.x, tol);
    EXPECT_NEAR(actual.y, expected.y, tol);
    EXPECT_NEAR(actual.z, expected.z, tol);
}

// Runs Intersect and returns the hit t, or -1 for a miss.
inline double HitT(const Primitive& prim, const Ray& ray, double tMin = 1e-5,
                   double tMax = 1e14) {
    PrimitiveHit hit;
    return prim.Intersect(ray, tMin, tMax, hit) ? hit.t : -1;
}

// Intersects and returns the hit, failing the test on a miss.
inline PrimitiveHit MustHit(const Primitive& prim, const Ray& ray, double tMin = 1e-5,
                            double tMax = 1e14) {
    PrimitiveHit hit;
    EXPECT_TRUE(prim.Intersect(ray, tMin, tMax, hit));
    return hit;
}

}  // namespace rs::testing
