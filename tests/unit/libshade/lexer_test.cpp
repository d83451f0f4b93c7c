#include "libshade/lexer.h"

#include "libshade/expression_parser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace rs {
namespace {

// The tokens of `text`. Tokens view their lexer's text, so the lexers made here are kept for
// the rest of the test program.
std::vector<Token> LexAll(const std::string& text, const std::string& file = "t.ray") {
    static std::vector<std::unique_ptr<Lexer>> lexers;
    Lexer& lexer = *lexers.emplace_back(std::make_unique<Lexer>(text, file));
    std::vector<Token> out;
    while (true) {
        Token t = lexer.Next();
        if (t.kind == TokenKind::End) break;
        out.push_back(t);
    }
    return out;
}

// Runs the lexer to the end and returns the fatal error's message ("" when none).
std::string LexError(const std::string& text) {
    try {
        LexAll(text);
    } catch (const FatalError& e) {
        return e.what();
    }
    return "";
}

TEST(Lexer, NamesMayContainDashDotAndUnderscore) {
    auto t = LexAll("a-b x.y my_surf2 planet.map sphere1");
    ASSERT_EQ(t.size(), 5u);
    for (const Token& tok : t) EXPECT_EQ(tok.kind, TokenKind::Name) << tok.text;
    EXPECT_EQ(t[0].text, "a-b");
    EXPECT_EQ(t[3].text, "planet.map");
    EXPECT_EQ(t[4].text, "sphere1");
}

TEST(Lexer, KeywordsAndSynonymsAreCanonical) {
    auto t = LexAll("sphere polygon reflective transparent translucency resolution samples sample");
    ASSERT_EQ(t.size(), 8u);
    const char* expected[] = {"sphere",  "poly",   "reflect", "transp",
                              "translu", "screen", "sample",  "sample"};
    for (size_t i = 0; i < t.size(); ++i) {
        EXPECT_EQ(t[i].kind, TokenKind::Keyword);
        EXPECT_EQ(t[i].keyword, expected[i]);
    }
    EXPECT_EQ(t[1].text, "polygon");
}

TEST(Lexer, Numbers) {
    auto t = LexAll("42 42. .5 1e-3 2.5E4 7e");
    ASSERT_EQ(t.size(), 7u);
    EXPECT_DOUBLE_EQ(t[0].number, 42);
    EXPECT_DOUBLE_EQ(t[1].number, 42);
    EXPECT_DOUBLE_EQ(t[2].number, 0.5);
    EXPECT_DOUBLE_EQ(t[3].number, 0.001);
    EXPECT_DOUBLE_EQ(t[4].number, 25000);
    // "7e" is the number 7 followed by the name "e" (an exponent needs digits).
    EXPECT_EQ(t[5].kind, TokenKind::Number);
    EXPECT_DOUBLE_EQ(t[5].number, 7);
    EXPECT_EQ(t[6].kind, TokenKind::Name);
}

// Every number is the double strtod reads from its spelling (correctly rounded), on the
// lexer's fast path (few digits, small exponents) and off it (many digits, large exponents,
// subnormals).
TEST(Lexer, NumbersRoundAsStrtodDoes) {
    std::mt19937 random(15);
    std::uniform_int_distribution<int> digit(0, 9), count(0, 20), exponent(-330, 330);
    for (int i = 0; i < 20000; ++i) {
        std::string spelling;
        for (int d = count(random); d >= 0; --d) spelling += static_cast<char>('0' + digit(random));
        if (i % 2 == 0) {
            spelling += '.';
            for (int d = count(random); d > 0; --d) spelling += static_cast<char>('0' + digit(random));
        }
        if (i % 3 == 0) {
            const int e = i % 6 == 0 ? exponent(random) : exponent(random) / 15;
            spelling += 'e';
            spelling += std::to_string(e);
        }
        const double expected = std::strtod(spelling.c_str(), nullptr);
        if (!std::isfinite(expected)) continue;  // out of range: an error, tested above
        auto t = LexAll(spelling);
        ASSERT_EQ(t.size(), 1u) << spelling;
        EXPECT_EQ(t[0].number, expected) << spelling;
        // With text after it, the digits are read eight at a time up to a run's end;
        // every character that may follow a digit run ends it.
        const char* const kFollowers = " \n-+*/x,()";  // none continues a number
        const std::string longer =
            spelling + kFollowers[static_cast<size_t>(i) % 10] + " 12345678 abcdefgh";
        auto u = LexAll(longer);
        ASSERT_GE(u.size(), 2u) << longer;
        EXPECT_EQ(u[0].number, expected) << longer;
        EXPECT_EQ(u[0].text, spelling) << longer;
    }
}

TEST(Lexer, SignsAreSeparateTokens) {
    auto t = LexAll("-1 +2");
    ASSERT_EQ(t.size(), 4u);
    EXPECT_TRUE(t[0].IsChar('-'));
    EXPECT_EQ(t[1].kind, TokenKind::Number);
    EXPECT_TRUE(t[2].IsChar('+'));
}

TEST(Lexer, NumberOutOfRangeIsAnError) {
    EXPECT_NE(LexError("sphere 1e999 0 0 0").find("t.ray:1: Number out of range"),
              std::string::npos);
}

TEST(Lexer, Filenames) {
    auto t = LexAll("/usr/img/a.rle ../maps/x.map ./y //net/z a/b");
    ASSERT_EQ(t.size(), 5u);
    for (const Token& tok : t) EXPECT_EQ(tok.kind, TokenKind::Filename) << tok.text;
    EXPECT_EQ(t[0].text, "/usr/img/a.rle");
    EXPECT_EQ(t[1].text, "../maps/x.map");
    EXPECT_EQ(t[3].text, "//net/z");
}

TEST(Lexer, SlashBeforeADigitIsDivision) {
    // Spec §1.2: (a/2) works because 2 cannot start a name; (a / b) needs the spaces.
    auto t = LexAll("(a/2) (a / b)");
    ASSERT_EQ(t.size(), 10u);
    EXPECT_EQ(t[1].text, "a");
    EXPECT_TRUE(t[2].IsChar('/'));
    EXPECT_EQ(t[3].kind, TokenKind::Number);
    EXPECT_TRUE(t[7].IsChar('/'));
}

TEST(Lexer, CommentsAndCarriageReturns) {
    auto t = LexAll("a /* x\n y */ b\r\nc");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[1].Location().line, 2);
    EXPECT_EQ(t[2].text, "c");
    EXPECT_EQ(t[2].Location().line, 3);
}

TEST(Lexer, UnterminatedCommentIsAnError) {
    EXPECT_EQ(LexError("a\n/* never closed\n\n"), "t.ray:2: Unterminated comment");
}

TEST(Lexer, LineMarkersSetFileAndLine) {
    auto t = LexAll(
        "# 1 \"<stdin>\"\n# 10 \"scene.ray\" 1 3\na\nb\n#line 40 \"inc.ray\"\nc\n# 7\nd\n"
        "# 3 \"\"\ne");
    ASSERT_EQ(t.size(), 5u);
    EXPECT_EQ(t[0].Location().file, "scene.ray");
    EXPECT_EQ(t[0].Location().line, 10);
    EXPECT_EQ(t[1].Location().line, 11);
    EXPECT_EQ(t[2].Location().file, "inc.ray");
    EXPECT_EQ(t[2].Location().line, 40);
    EXPECT_EQ(t[3].Location().file, "inc.ray");
    EXPECT_EQ(t[3].Location().line, 7);
    EXPECT_EQ(t[4].Location().file, "stdin");
    EXPECT_EQ(t[4].Location().line, 3);
    EXPECT_EQ(LexAll("# 5 \"<stdin>\"\nx")[0].Location().file, "stdin");
}

TEST(Lexer, UnknownHashControlIsAnError) {
    EXPECT_EQ(LexError("a\n#include \"x.ray\"\n"),
              "t.ray:2: Unknown '#' control: #include \"x.ray\"");
}

TEST(Lexer, HashInsideALineIsACharacter) {
    auto t = LexAll("a # b");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_TRUE(t[1].IsChar('#'));
}

TEST(Lexer, OtherCharacters) {
    auto t = LexAll("( ) , * % ^ @");
    ASSERT_EQ(t.size(), 7u);
    for (const Token& tok : t) EXPECT_EQ(tok.kind, TokenKind::Char);
}

TEST(TokenStream, PeekDoesNotConsume) {
    TokenStream s("a b c", "t");
    EXPECT_EQ(s.Peek(1).text, "b");
    EXPECT_EQ(s.Peek(0).text, "a");
    EXPECT_EQ(s.Next().text, "a");
    EXPECT_EQ(s.Next().text, "b");
    EXPECT_EQ(s.Peek(5).kind, TokenKind::End);
    EXPECT_EQ(s.Next().text, "c");
}

// Reads `text` as the parser reads arguments: whether an expression starts, then a literal
// if one is there, else a token; one line per step with the answers, values, tokens and
// locations, and the lexical error's message if any. With `viaTokens`, a token is buffered
// before every step, so both answers come from tokens, not from the lexer directly.
std::vector<std::string> ReadLiterals(const std::string& text, bool viaTokens) {
    std::vector<std::string> out;
    try {
        TokenStream s(text, "lit.ray");
        while (true) {
            if (viaTokens) s.Peek();
            std::string step = PeekExpression(s) ? "expr " : "- ";
            if (double v; ReadLiteral(s, v)) {
                out.push_back(step + "literal " + std::to_string(v));
                continue;
            }
            const Token t = s.Next();
            out.push_back(step + std::to_string(static_cast<int>(t.kind)) + " " + std::string(t.text) +
                          " " + t.Location().file + ":" + std::to_string(t.line));
            if (t.kind == TokenKind::End) break;
        }
    } catch (const FatalError& e) {
        out.push_back(std::string("error: ") + e.what());
    }
    return out;
}

// The lexer answers ReadLiteral and PeekExpression itself when no token is buffered;
// comparing that with answers from buffered tokens checks that the direct answers, values,
// consumed text, locations and errors are the tokens' own.
TEST(TokenStream, DirectLiteralsMatchTheTokens) {
    const char* const kPieces[] = {"-", "+", "1.5", ".5", "7", "2e3", "(", ")", "x", ".", " ",
                                   "\n", "/* c\n */", "\n# 5 \"f.ray\"\n", "#", "*", "1e999"};
    std::mt19937 random(7);
    std::uniform_int_distribution<size_t> piece(0, std::size(kPieces) - 1), length(1, 12);
    int literals = 0;
    for (int i = 0; i < 3000; ++i) {
        std::string text;
        for (size_t n = length(random); n > 0; --n) text += kPieces[piece(random)];
        const std::vector<std::string> direct = ReadLiterals(text, false);
        EXPECT_EQ(direct, ReadLiterals(text, true)) << text;
        for (const std::string& step : direct) literals += step.find("literal") != std::string::npos;
    }
    EXPECT_GT(literals, 1000);  // literals were read
}

}  // namespace
}  // namespace rs
