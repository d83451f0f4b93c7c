#include "libshade/expression.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "libshade/expression_parser.h"
#include "libshade/symtab.h"

namespace rs {
namespace {

ExprPtr Parse(const std::string& text, const SymbolTable& symbols) {
    TokenStream tokens(text, "e.ray");
    ExprPtr e = ParseExpression(tokens, symbols);
    EXPECT_EQ(tokens.Peek().kind, TokenKind::End) << text;
    return e;
}

double Static(const std::string& text) {
    SymbolTable symbols;
    ExprPtr e = Parse(text, symbols);
    EXPECT_FALSE(e->IsTimeVarying()) << text;
    return e->Value();
}

std::string ParseError(const std::string& text, const SymbolTable& symbols = SymbolTable()) {
    try {
        Parse(text, symbols);
    } catch (const FatalError& e) {
        return e.what();
    }
    return "";
}

TEST(Expression, VerifiedPrecedenceExamples) {
    // Spec §1.4 (verified on the original).
    EXPECT_DOUBLE_EQ(Static("(2^3^0)"), 2);
    EXPECT_DOUBLE_EQ(Static("(-2^2+5)"), 1);
    EXPECT_DOUBLE_EQ(Static("(7%3+0.5)"), 1.5);
}

TEST(Expression, Precedence) {
    EXPECT_DOUBLE_EQ(Static("(1 + 2 * 3)"), 7);
    EXPECT_DOUBLE_EQ(Static("(10 - 4 - 3)"), 3);
    EXPECT_DOUBLE_EQ(Static("(8 / 4 / 2)"), 1);
    EXPECT_DOUBLE_EQ(Static("((1 + 2) * 3)"), 9);
    EXPECT_DOUBLE_EQ(Static("(2^-1)"), 0.5);
    EXPECT_DOUBLE_EQ(Static("(-2*3)"), -6);
    EXPECT_DOUBLE_EQ(Static("(- -2)"), 2);
    EXPECT_DOUBLE_EQ(Static("(+3)"), 3);
    EXPECT_DOUBLE_EQ(Static("(2*3^2)"), 18);
}

TEST(Expression, ModuloHasCSemantics) {
    EXPECT_DOUBLE_EQ(Static("(-7 % 3)"), -1);
    EXPECT_DOUBLE_EQ(Static("(7.9 % 3.9)"), 1);    // (int)7.9 % (int)3.9 = 7 % 3
    EXPECT_TRUE(std::isnan(Static("(7 % 0.5)")));  // (int)0.5 = 0: no crash, NaN
}

TEST(Expression, SignedNumbersOutsideParentheses) {
    EXPECT_DOUBLE_EQ(Static("-4.5"), -4.5);
    EXPECT_DOUBLE_EQ(Static("+.5"), 0.5);
    EXPECT_DOUBLE_EQ(Static("12"), 12);
}

TEST(Expression, Builtins) {
    EXPECT_DOUBLE_EQ(Static("(pi)"), 3.141592);
    EXPECT_DOUBLE_EQ(Static("(dtor)"), 0.017453);
    EXPECT_DOUBLE_EQ(Static("(rtod)"), 57.29578);
    EXPECT_DOUBLE_EQ(Static("(hypot(3, 4))"), 5);
    EXPECT_DOUBLE_EQ(Static("(sqrt(16))"), 4);
    EXPECT_NEAR(Static("(sin(pi/2))"), 1, 1e-12);
    EXPECT_NEAR(Static("(cos(0))"), 1, 1e-15);
    EXPECT_NEAR(Static("(atan(1) * 4)"), M_PI, 1e-15);
    EXPECT_NEAR(Static("(acos(-1))"), M_PI, 1e-15);
    EXPECT_NEAR(Static("(asin(1))"), M_PI / 2, 1e-15);
    EXPECT_NEAR(Static("(tan(0))"), 0, 1e-15);
}

TEST(Expression, TimeVaryingDetection) {
    SymbolTable symbols;
    EXPECT_TRUE(Parse("(time)", symbols)->IsTimeVarying());
    EXPECT_TRUE(Parse("(frame * 2)", symbols)->IsTimeVarying());
    EXPECT_TRUE(Parse("(linear(0, 0, 1, 1))", symbols)->IsTimeVarying());
    EXPECT_TRUE(Parse("(sin(time))", symbols)->IsTimeVarying());
    EXPECT_FALSE(Parse("(sin(1) + 2)", symbols)->IsTimeVarying());
    ASSERT_TRUE(symbols.Define("spin", Parse("(linear(0, 0, 30, 1440))", symbols)));
    ASSERT_TRUE(symbols.Define("k", Parse("(2 * 3)", symbols)));
    EXPECT_TRUE(Parse("(spin / 2)", symbols)->IsTimeVarying());
    ExprPtr k = Parse("(k + 1)", symbols);
    EXPECT_FALSE(k->IsTimeVarying());
    EXPECT_EQ(k->op(), Expr::Op::Constant);  // folded
    EXPECT_DOUBLE_EQ(k->Value(), 7);
}

TEST(Expression, TimeVaryingEvaluation) {
    SymbolTable symbols;
    ExprPtr lin = Parse("(linear(10, 1, 20, 3))", symbols);
    EXPECT_DOUBLE_EQ(lin->Evaluate(0), 1);
    EXPECT_DOUBLE_EQ(lin->Evaluate(15), 2);
    EXPECT_DOUBLE_EQ(lin->Evaluate(25), 3);
    ExprPtr degenerate = Parse("(linear(5, 1, 5, 3))", symbols);
    EXPECT_DOUBLE_EQ(degenerate->Evaluate(5), 1);
    ExprPtr t = Parse("(time * 2 + 1)", symbols);
    EXPECT_DOUBLE_EQ(t->Evaluate(1.5), 4);
    ExprPtr f = Parse("(frame + 0.5)", symbols);
    SetCurrentFrame(7);
    EXPECT_DOUBLE_EQ(f->Evaluate(0), 7.5);
    SetCurrentFrame(0);
    EXPECT_DOUBLE_EQ(f->Evaluate(0), 0.5);
}

TEST(Expression, LinearAtBeforeAfterAndOnItsEnds) {
    // linear(t0,v0,t1,v1): v0 up to t0, v1 from t1 on, the straight line in between
    // (spec §1.4). Here from (2, 10) to (6, −2): slope −3.
    EXPECT_DOUBLE_EQ(LinearAt(-100, 2, 10, 6, -2), 10);
    EXPECT_DOUBLE_EQ(LinearAt(2, 2, 10, 6, -2), 10);
    EXPECT_DOUBLE_EQ(LinearAt(3, 2, 10, 6, -2), 7);
    EXPECT_DOUBLE_EQ(LinearAt(5.5, 2, 10, 6, -2), -0.5);
    EXPECT_DOUBLE_EQ(LinearAt(6, 2, 10, 6, -2), -2);
    EXPECT_DOUBLE_EQ(LinearAt(1e9, 2, 10, 6, -2), -2);
}

TEST(Expression, LinearWithEqualTimesIsAStep) {
    // t0 ≈ t1 (within ε): v0 before and at the step, v1 after it.
    EXPECT_DOUBLE_EQ(LinearAt(4.9, 5, 1, 5, 3), 1);
    EXPECT_DOUBLE_EQ(LinearAt(5, 5, 1, 5, 3), 1);
    EXPECT_DOUBLE_EQ(LinearAt(5.1, 5, 1, 5, 3), 3);
    EXPECT_DOUBLE_EQ(LinearAt(5.000001, 5, 1, 5.000002, 3), 1);  // within ε of t0
    SymbolTable symbols;
    ExprPtr step = Parse("(linear(5, 1, 5, 3))", symbols);
    EXPECT_DOUBLE_EQ(step->Evaluate(4), 1);
    EXPECT_DOUBLE_EQ(step->Evaluate(6), 3);
}

TEST(Expression, LinearArgumentsMayThemselvesVaryInTime) {
    // linear(0, time, 10, 0): at time t the value is t·(1 − t/10) for t in [0, 10].
    SymbolTable symbols;
    ExprPtr e = Parse("(linear(0, time, 10, 0))", symbols);
    EXPECT_DOUBLE_EQ(e->Evaluate(5), 2.5);
    EXPECT_DOUBLE_EQ(e->Evaluate(2), 1.6);
    EXPECT_DOUBLE_EQ(e->Evaluate(12), 0);
}

TEST(Expression, FrameIsConstantWithinAFrame) {
    // `frame` is the frame number whatever the ray time; `time` follows the ray.
    SymbolTable symbols;
    ExprPtr e = Parse("(frame * 100 + time)", symbols);
    SetCurrentFrame(4);
    EXPECT_DOUBLE_EQ(e->Evaluate(4), 404);
    EXPECT_DOUBLE_EQ(e->Evaluate(4.75), 404.75);
    SetCurrentFrame(5);
    EXPECT_DOUBLE_EQ(e->Evaluate(4.75), 504.75);
    SetCurrentFrame(0);
}

TEST(Expression, CoinSceneIdiom) {
    SymbolTable symbols;
    symbols.Define("length", Parse("30", symbols));
    symbols.Define("shift", Parse("(linear(0,0,length,length) - length / 2)", symbols));
    symbols.Define("height", Parse("(7 * ( 1 - shift * shift / (length * length / 4) ))", symbols));
    ExprPtr h = symbols.Find("height")->value;
    EXPECT_DOUBLE_EQ(h->Evaluate(15), 7);  // the top of the flip
    EXPECT_NEAR(h->Evaluate(0), 0, 1e-12);
}

TEST(Expression, Redefinition) {
    SymbolTable symbols;
    EXPECT_TRUE(symbols.Define("x", Expr::Number(1)));
    EXPECT_FALSE(symbols.Define("x", Expr::Number(2)));
    EXPECT_FALSE(symbols.Define("pi", Expr::Number(3)));
    EXPECT_FALSE(symbols.Define("sin", Expr::Number(3)));
    EXPECT_FALSE(symbols.Define("time", Expr::Number(3)));
    EXPECT_DOUBLE_EQ(symbols.Find("x")->value->Value(), 1);
}

TEST(Expression, Errors) {
    EXPECT_EQ(ParseError("(a-1)"), "e.ray:1: Undefined variable 'a-1'");
    EXPECT_EQ(ParseError("(foo(1))"), "e.ray:1: Undefined function 'foo'");
    EXPECT_EQ(ParseError("(sin)"), "e.ray:1: 'sin' is a function; it needs arguments");
    EXPECT_EQ(ParseError("(pi(2))"), "e.ray:1: 'pi' is not a function");
    EXPECT_EQ(ParseError("(sin(1, 2))"), "e.ray:1: Function 'sin' takes 1 argument, not 2");
    EXPECT_EQ(ParseError("(hypot(1))"), "e.ray:1: Function 'hypot' takes 2 arguments, not 1");
    EXPECT_EQ(ParseError("(linear(1,2,3))"), "e.ray:1: Function 'linear' takes 4 arguments, not 3");
    EXPECT_EQ(ParseError("(1 +\n)"), "e.ray:2: Unexpected ')' in expression");
    EXPECT_EQ(ParseError("(1 2)"), "e.ray:1: Expected ')' in expression, found '2'");
    EXPECT_EQ(ParseError("(a/b)"), "e.ray:1: Unexpected 'a/b' in expression");
    EXPECT_EQ(ParseError("- (1)"), "e.ray:1: Expected a number or '(', found '-'");
    EXPECT_EQ(ParseError("x"), "e.ray:1: Expected a number or '(', found 'x'");
}

TEST(Expression, HostileNestingIsAnErrorNotACrash) {
    std::string deep = std::string(100000, '(') + "1" + std::string(100000, ')');
    EXPECT_EQ(ParseError(deep), "e.ray:1: Expression nested too deeply");
    std::string signs = "(" + std::string(100000, '-') + "1)";
    EXPECT_EQ(ParseError(signs), "e.ray:1: Expression nested too deeply");
    // A long static chain folds as it goes; a long time-varying one is refused.
    std::string chain = "(1";
    for (int i = 0; i < 50000; ++i) chain += "+1";
    EXPECT_DOUBLE_EQ(Static(chain + ")"), 50001);
    std::string tv = "(time";
    for (int i = 0; i < 50000; ++i) tv += "+time";
    EXPECT_EQ(ParseError(tv + ")"), "e.ray:1: Expression too complex");
}

TEST(Expression, SharedSubtreesCannotExplodeEvaluation) {
    // Each definition uses the previous one twice: evaluation cost doubles per level.
    SymbolTable symbols;
    symbols.Define("v0", Parse("(time)", symbols));
    std::string error;
    for (int i = 1; i < 100 && error.empty(); ++i) {
        TokenStream tokens(StringPrintf("(v%d + v%d)", i - 1, i - 1), "e.ray");
        try {
            symbols.Define(StringPrintf("v%d", i), ParseExpression(tokens, symbols));
        } catch (const FatalError& e) {
            error = e.what();
        }
    }
    EXPECT_EQ(error, "e.ray:1: Expression too complex");
}

std::optional<Expr::Affine> AffineOf(const std::string& text) {
    SymbolTable symbols;
    return Parse(text, symbols)->AffineInTime();
}

TEST(Expression, AffineInTimeReadsTheTreesShape) {
    struct Case {
        const char* text;
        double offset, slope;
    };
    const Case affine[] = {{"(time)", -0.0, 1},           {"(-time)", -0.0, -1},
                           {"(-1 + time)", -1, 1},        {"(time + 2)", 2, 1},
                           {"(3*0.2 + 0.3*time)", 3 * 0.2, 0.3},
                           {"(0.95*time - 0.25)", -0.25, 0.95},
                           {"(2 - time*0.5)", 2, -0.5},   {"(-(2*time))", -0.0, -2},
                           {"(2*-time)", -0.0, -2},       {"(1 + -time*4)", 1, -4}};
    for (const Case& c : affine) {
        const std::optional<Expr::Affine> a = AffineOf(c.text);
        ASSERT_TRUE(a) << c.text;
        EXPECT_EQ(std::bit_cast<uint64_t>(a->offset), std::bit_cast<uint64_t>(c.offset)) << c.text;
        EXPECT_EQ(a->slope, c.slope) << c.text;
    }
    // Not affine in time, static, or affine in a form whose rounding At would not reproduce.
    for (const char* text : {"(time*time)", "(sin(time))", "(frame)", "(frame + time)",
                             "(linear(0, 0, 1, 1))", "(1 + 2)", "(2*(1 + time))", "(time/3)",
                             "(2*(3*time))", "(-(1 + time))", "(1 + time + 2)"}) {
        EXPECT_FALSE(AffineOf(text)) << text;
    }
}

// How many of `times` give At(t) and Evaluate(t) differing in some bit.
int AffineMismatches(const Expr& e, const Expr::Affine& a, const std::vector<double>& times) {
    int mismatches = 0;
    for (double t : times) {
        mismatches += std::bit_cast<uint64_t>(a.At(t)) != std::bit_cast<uint64_t>(e.Evaluate(t));
    }
    return mismatches;
}

TEST(Expression, AffineInTimeIsEvaluateBitForBit) {
    std::mt19937_64 rng(14);
    std::uniform_real_distribution<double> uniform(-3, 3);
    std::vector<double> times = {0.0, -0.0, 1, -1, 1e300, -1e-310};
    for (int i = 0; i < 2000; ++i) times.push_back(uniform(rng) * std::pow(10, uniform(rng)));
    const char* forms[] = {"(%.17g + %.17g*time)", "(time*%.17g - %.17g)",
                           "(%.17g - -time*%.17g)", "(-(%.17g*time) + %.17g)"};
    for (int i = 0; i < 50; ++i) {
        for (const char* form : forms) {
            char text[128];
            std::snprintf(text, sizeof text, form, uniform(rng), uniform(rng));
            SymbolTable symbols;
            const ExprPtr e = Parse(text, symbols);
            const std::optional<Expr::Affine> a = e->AffineInTime();
            ASSERT_TRUE(a) << text;
            EXPECT_EQ(AffineMismatches(*e, *a, times), 0) << text;
            // The comparison sees a slope off by one ulp.
            const Expr::Affine perturbed{a->offset, std::nextafter(a->slope, 10.0)};
            EXPECT_GT(AffineMismatches(*e, perturbed, times), 0) << text;
        }
    }
}

}  // namespace
}  // namespace rs
