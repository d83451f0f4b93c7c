// Command-line overrides of implicit objects (implicit_overrides.h): the one parser both
// programs use, and their application through the primitive.
#include "libobj/implicit/implicit_overrides.h"

#include <gtest/gtest.h>

#include <string>

#include "libobj/implicit/implicit_surface.h"

namespace rs {
namespace {

// Parses one value; returns the error message ("" when accepted).
std::string Parse(ImplicitOverrideKind kind, const std::string& value,
                  ImplicitOverrides& overrides) {
    std::string error;
    const bool accepted = ParseImplicitOverride(kind, value, overrides, error);
    EXPECT_EQ(accepted, error.empty()) << value;
    return error;
}

TEST(ImplicitOverrides, EveryKindParsesItsValue) {
    ImplicitOverrides o;
    EXPECT_TRUE(o.Empty());
    EXPECT_EQ(Parse(ImplicitOverrideKind::Method, "kb89", o), "");
    EXPECT_EQ(o.method, ImplicitMethod::Kb89);
    EXPECT_EQ(Parse(ImplicitOverrideKind::Tolerance, "1e-4", o), "");
    EXPECT_EQ(o.tolerance, 1e-4);
    EXPECT_EQ(Parse(ImplicitOverrideKind::Depth, "7", o), "");
    EXPECT_EQ(o.maxDepth, 7);
    EXPECT_EQ(Parse(ImplicitOverrideKind::DRatio, "-1", o), "");
    EXPECT_EQ(o.dRatio, -1);
    EXPECT_EQ(Parse(ImplicitOverrideKind::Step, "0.02", o), "");
    EXPECT_EQ(o.step, 0.02);
    EXPECT_EQ(Parse(ImplicitOverrideKind::Switch, "1bis=off", o), "");
    EXPECT_EQ(Parse(ImplicitOverrideKind::Switch, "t3=on", o), "");
    ASSERT_EQ(o.switches.size(), 2u);
    EXPECT_EQ(o.switches[0], (std::pair<std::string, bool>{"1bis", false}));
    EXPECT_EQ(o.switches[1], (std::pair<std::string, bool>{"t3", true}));
    EXPECT_FALSE(o.Empty());
}

TEST(ImplicitOverrides, BadValuesAreRejectedWithoutEffect) {
    ImplicitOverrides o;
    EXPECT_EQ(Parse(ImplicitOverrideKind::Method, "bisection", o),
              "unknown method 'bisection' (expected patches, kb89, march, sphere, segment, "
              "polynomial, exact, auto)");
    EXPECT_EQ(Parse(ImplicitOverrideKind::Tolerance, "0", o), "the tolerance must be > 0");
    EXPECT_EQ(Parse(ImplicitOverrideKind::Tolerance, "x", o), "'x' is not a finite number");
    EXPECT_EQ(Parse(ImplicitOverrideKind::Tolerance, "inf", o), "'inf' is not a finite number");
    EXPECT_EQ(Parse(ImplicitOverrideKind::Depth, "17", o),
              "the octree depth must be an integer in [0, 16]");
    EXPECT_EQ(Parse(ImplicitOverrideKind::Depth, "2.5", o),
              "the octree depth must be an integer in [0, 16]");
    EXPECT_EQ(Parse(ImplicitOverrideKind::Step, "-1", o), "the march step must be > 0");
    EXPECT_EQ(Parse(ImplicitOverrideKind::DRatio, "", o), "'' is not a finite number");
    EXPECT_EQ(Parse(ImplicitOverrideKind::Switch, "1bis", o),
              "octree switch '1bis' needs =on or =off");
    EXPECT_NE(Parse(ImplicitOverrideKind::Switch, "zz=on", o).find("unknown octree switch 'zz'"),
              std::string::npos);
    EXPECT_TRUE(o.Empty());
}

TEST(ImplicitOverrides, AppliedThroughThePrimitive) {
    const std::vector<FieldTerm> terms = {
        {"a", PointSkeleton{{0, 0, 0}}, Kernel::GascuelQuadratic(0.8, 1, 2), 1}};
    ImplicitSurface surface(terms, ImplicitOptions{});
    const Ray ray{{0, 0, -5}, {0, 0, 1}};
    for (const char* method : {"exact", "march", "sphere", "segment", "kb89", "patches"}) {
        ImplicitOverrides o;
        ASSERT_EQ(Parse(ImplicitOverrideKind::Method, method, o), "");
        ASSERT_EQ(Parse(ImplicitOverrideKind::Tolerance, "1e-9", o), "");
        EXPECT_EQ(surface.ApplyOverrides(o), "") << method;
        EXPECT_STREQ(ImplicitMethodName(surface.Method()), method);
        PrimitiveHit hit;
        ASSERT_TRUE(surface.Intersect(ray, 0, 100, hit)) << method;
        EXPECT_NEAR(hit.t, 4.2, 1e-8) << method;  // a sphere of radius e = 0.8
    }
    // polynomial serves blob kernels only: refused, the object keeps its method.
    ImplicitOverrides polynomial;
    polynomial.method = ImplicitMethod::Polynomial;
    EXPECT_NE(surface.ApplyOverrides(polynomial).find("polynomial"), std::string::npos);
    EXPECT_EQ(surface.Method(), ImplicitMethod::Patches);
    // auto resolves once, from the terms: patches for a Gascuel kernel.
    ImplicitOverrides automatic;
    automatic.method = ImplicitMethod::Auto;
    EXPECT_EQ(surface.ApplyOverrides(automatic), "");
    EXPECT_EQ(surface.Method(), ImplicitMethod::Patches);
}

}  // namespace
}  // namespace rs
