#include <gtest/gtest.h>

#include "libshade/arg_reader_impl.h"

namespace rs {
namespace {

// Parser services over a fixed text; surfaces are always fresh ones with a marker field.
class FakeParser final : public ParserServices {
  public:
    explicit FakeParser(const std::string& text) : tokens_(text, "a.ray") {}
    TokenStream& Tokens() override { return tokens_; }
    const SymbolTable& Symbols() const override { return symbols_; }
    Surface ParseSurfaceValue(std::string_view) override {
        tokens_.Next();
        Surface s;
        s.specpow = 42;
        return s;
    }
    bool FlipNormals() const override { return true; }
    SymbolTable symbols_;

  private:
    TokenStream tokens_;
};

std::string Error(const std::function<void()>& f) {
    try {
        f();
    } catch (const FatalError& e) {
        return e.what();
    }
    return "";
}

TEST(TokenArgReader, NumbersAndIntegers) {
    FakeParser p("1.5 -2 (2 * 3) -2.7 (7.9) 1 2 3");
    TokenArgReader r(p, SourceLocation{"a.ray", 1}, "thing args");
    EXPECT_DOUBLE_EQ(r.ReadNumber(), 1.5);
    EXPECT_DOUBLE_EQ(r.ReadNumber(), -2);
    EXPECT_DOUBLE_EQ(r.ReadNumber(), 6);
    EXPECT_EQ(r.ReadInt(), -2);  // truncation toward zero
    EXPECT_EQ(r.ReadInt(), 7);
    Vec3 v = r.ReadVector();
    EXPECT_EQ(v.z, 3);
    EXPECT_FALSE(r.PeekNumber());
}

TEST(TokenArgReader, AnimatedNumbers) {
    FakeParser p("(time * 2) 3");
    TokenArgReader r(p, SourceLocation{"a.ray", 1}, "");
    AnimatedValue a = r.ReadAnimatedNumber();
    EXPECT_TRUE(a.IsAnimated());
    EXPECT_DOUBLE_EQ(a.At(1.25), 2.5);
    AnimatedValue s = r.ReadAnimatedNumber();
    EXPECT_FALSE(s.IsAnimated());
    EXPECT_DOUBLE_EQ(s.At(9), 3);
}

TEST(TokenArgReader, PeekNumberNeedsADigitAfterASign) {
    FakeParser p("- x");
    TokenArgReader r(p, SourceLocation{"a.ray", 1}, "");
    EXPECT_FALSE(r.PeekNumber());
}

TEST(TokenArgReader, KeywordsNamesAndFiles) {
    FakeParser p("polygon reflective maps/a.map planet.map name2 cursurf");
    TokenArgReader r(p, SourceLocation{"a.ray", 1}, "");
    EXPECT_TRUE(r.Peek("poly"));  // synonyms match by canonical spelling
    EXPECT_TRUE(r.Accept("polygon"));
    EXPECT_FALSE(r.Accept("transp"));
    EXPECT_TRUE(r.Accept("reflect"));
    EXPECT_TRUE(r.PeekFilename());
    EXPECT_EQ(r.ReadFilename(), "maps/a.map");
    EXPECT_EQ(r.ReadFilename(), "planet.map");  // a bare name is a file name too
    EXPECT_TRUE(r.Peek("name2"));
    EXPECT_EQ(r.ReadName(), "name2");
    EXPECT_FALSE(r.PeekFilename());  // keywords are not file names
    EXPECT_EQ(r.ReadSurface().specpow, 42);
    EXPECT_TRUE(r.FlipNormals());
}

TEST(TokenArgReader, ErrorsNameTheTokenAndTheUsage) {
    FakeParser p("\nsphere");
    TokenArgReader r(p, SourceLocation{"a.ray", 1}, "thing n");
    EXPECT_EQ(Error([&] { r.ReadNumber(); }),
              "a.ray:2: Expected a number or '(', found 'sphere' (usage: thing n)");
    EXPECT_EQ(Error([&] { r.ReadName(); }),
              "a.ray:2: Expected a name, found 'sphere' (usage: thing n)");
    EXPECT_EQ(Error([&] { r.ReadFilename(); }),
              "a.ray:2: Expected a file name, found 'sphere' (usage: thing n)");
    EXPECT_EQ(Error([&] { r.Fail("Bad thing"); }), "a.ray:1: Bad thing (usage: thing n)");
    EXPECT_EQ(r.Location().line, 1);
}

TEST(TokenArgReader, StaticArgumentsRejectTimeAndNonFiniteValues) {
    FakeParser p("(frame) (1/0) (2^40)");
    TokenArgReader r(p, SourceLocation{"a.ray", 1}, "");
    EXPECT_EQ(Error([&] { r.ReadNumber(); }),
              "a.ray:1: Illegal expression use: only transformation parameters may vary with time");
    EXPECT_EQ(Error([&] { r.ReadNumber(); }), "a.ray:1: Expression value is not a finite number");
    EXPECT_EQ(Error([&] { r.ReadInt(); }), "a.ray:1: Integer out of range");
}

}  // namespace
}  // namespace rs
