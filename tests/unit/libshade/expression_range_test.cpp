// Expr::EvaluateRange against analytic ranges and dense sampling: every sampled value
// lies inside the computed interval, and for monotone or simple expressions the interval
// is tight to a few ulps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "libshade/expression.h"
#include "libshade/expression_parser.h"
#include "libshade/symtab.h"

namespace rs {
namespace {

ExprPtr Parse(const std::string& text) {
    SymbolTable symbols;
    TokenStream tokens(text, "e.ray");
    ExprPtr e = ParseExpression(tokens, symbols);
    EXPECT_EQ(tokens.Peek().kind, TokenKind::End) << text;
    return e;
}

// Every value at 2001 evenly spread times and both ends lies in the range.
void ExpectContainsSamples(const std::string& text, double t0, double t1) {
    ExprPtr e = Parse(text);
    const Expr::Range r = e->EvaluateRange(t0, t1);
    for (int i = 0; i <= 2000; ++i) {
        const double t = i == 2000 ? t1 : t0 + (t1 - t0) * i / 2000.0;
        const double v = e->Evaluate(t);
        EXPECT_LE(r.lo, v) << text << " at " << t;
        EXPECT_GE(r.hi, v) << text << " at " << t;
    }
}

TEST(ExpressionRange, AnalyticRanges) {
    struct Case {
        const char* text;
        double t0, t1, lo, hi;
    } cases[] = {
        {"(time)", 0.25, 0.75, 0.25, 0.75},
        {"(-1 + 2*time)", 0, 1, -1, 1},
        {"(3 - time)", 0, 1, 2, 3},
        {"(time*time)", -1, 2, -2, 4},  // interval product: t·t over [-1, 2] is [-2, 4]
        {"(time^2)", -1, 2, 0, 4},      // an even power knows the sign
        {"(sin(time))", 0, 3.2, std::sin(3.2), 1},
        {"(cos(time))", 0.5, 7, -1, 1},
        {"(sqrt(time))", 1, 4, 1, 2},
        {"(linear(0, 2, 1, 4))", 0.25, 0.5, 2.5, 3},
        {"(linear(0, 2, 1, 4))", -1, 2, 2, 4},
        {"(1 / time)", 1, 2, 0.5, 1},
        {"(hypot(time, 1))", 0, 1, 1, std::sqrt(2.0)},
        {"(atan(time))", 0, 1, 0, std::atan(1.0)},
    };
    for (const Case& c : cases) {
        const Expr::Range r = Parse(c.text)->EvaluateRange(c.t0, c.t1);
        // sin and cos widen by a slack of 1e-12·(1 + |x|) for the shifted ends.
        const double tolerance = 1e-11 * (1 + std::abs(c.lo) + std::abs(c.hi));
        EXPECT_LE(r.lo, c.lo) << c.text;
        EXPECT_GE(r.hi, c.hi) << c.text;
        EXPECT_NEAR(r.lo, c.lo, tolerance) << c.text;
        EXPECT_NEAR(r.hi, c.hi, tolerance) << c.text;
    }
}

TEST(ExpressionRange, UnboundedWhereNoBoundExists) {
    const double inf = std::numeric_limits<double>::infinity();
    for (const char* text : {"(1 / time)", "(tan(time*2))", "(asin(time*2))", "(sqrt(time - 0.5))",
                             "(time % 0.5)"}) {
        const Expr::Range r = Parse(text)->EvaluateRange(0, 1);
        EXPECT_TRUE(r.lo == -inf && r.hi == inf) << text << ": " << r.lo << " " << r.hi;
    }
}

TEST(ExpressionRange, ContainsDenseSamplesOfRandomIntervals) {
    const char* texts[] = {
        "(sin(3*time) * cos(time) + time^3)",
        "(linear(0.2, -1, 0.7, 3) * (time + 1))",
        "(hypot(sin(time), time - 0.5) / (2 + cos(time)))",
        "(2^time - sqrt(1 + time*time))",
        "((time*7) % 3 + atan(time))",
        "(-(time - 0.3)^3 + acos(time/10))",
    };
    std::mt19937_64 rng(14);
    std::uniform_real_distribution<double> start(-3, 3), width(0, 2);
    for (const char* text : texts) {
        for (int k = 0; k < 50; ++k) {
            const double t0 = start(rng);
            ExpectContainsSamples(text, t0, t0 + width(rng));
        }
    }
}

}  // namespace
}  // namespace rs
