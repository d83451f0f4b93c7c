#include "libshade/arg_reader_impl.h"

#include <climits>
#include <cmath>
#include <optional>

#include "libshade/expression_parser.h"

namespace rs {

namespace {
// Matches a keyword by canonical spelling (so Accept("polygon") matches `poly`), a name, or
// a punctuation character (Accept(":")).
bool Matches(const Token& t, const char* word) {
    if (t.kind == TokenKind::Keyword) return SpellsKeyword(word, t.keyword);
    return (t.kind == TokenKind::Name || t.kind == TokenKind::Char) && t.text == word;
}
}  // namespace

ExprPtr TokenArgReader::ReadExpression() {
    return ParseExpression(parser_.Tokens(), parser_.Symbols(), usage_);
}

double TokenArgReader::ReadNumber() {
    if (double v; ReadLiteral(parser_.Tokens(), v)) return v;  // finite (the lexer checks)
    SourceLocation where = parser_.Tokens().Peek().Location();
    ExprPtr e = ReadExpression();
    // Spec §3.15: only transform parameters may vary with time.
    if (e->IsTimeVarying())
        FailAt(where, usage_,
               "Illegal expression use: only transformation parameters may vary with time");
    double v = e->Value();
    if (!std::isfinite(v)) FailAt(where, usage_, "Expression value is not a finite number");
    return v;
}

int TokenArgReader::ReadInt() {
    SourceLocation where = parser_.Tokens().Peek().Location();
    double v = ReadNumber();
    if (!(v > INT_MIN - 1.0 && v < INT_MAX + 1.0)) FailAt(where, usage_, "Integer out of range");
    return static_cast<int>(v);  // truncation toward zero (spec `iexpr`)
}

AnimatedValue TokenArgReader::ReadAnimatedNumber() {
    AnimatedValue v;
    if (ReadLiteral(parser_.Tokens(), v.value)) return v;  // finite (the lexer checks)
    SourceLocation where = parser_.Tokens().Peek().Location();
    ExprPtr e = ReadExpression();
    if (e->IsTimeVarying()) {
        v.at = [e](double time) { return e->Evaluate(time); };
        v.range = [e](double t0, double t1) {
            const Expr::Range r = e->EvaluateRange(t0, t1);
            return std::pair<double, double>(r.lo, r.hi);
        };
        if (const std::optional<Expr::Affine> affine = e->AffineInTime()) {
            v.affine = true;
            v.affineOffset = affine->offset;
            v.affineSlope = affine->slope;
        }
        return v;
    }
    v.value = e->Value();
    if (!std::isfinite(v.value)) FailAt(where, usage_, "Expression value is not a finite number");
    return v;
}

bool TokenArgReader::PeekNumber() { return PeekExpression(parser_.Tokens()); }

bool TokenArgReader::Accept(const char* word) {
    if (!Peek(word)) return false;
    parser_.Tokens().Next();
    return true;
}

bool TokenArgReader::Peek(const char* word) { return Matches(parser_.Tokens().Peek(), word); }

std::string TokenArgReader::ReadName() {
    if (parser_.Tokens().Peek().kind != TokenKind::Name) FailExpected("a name");
    return std::string(parser_.Tokens().Next().text);
}

std::string TokenArgReader::ReadWord() {
    if (!PeekWord()) FailExpected("a name");
    return std::string(parser_.Tokens().Next().text);
}

bool TokenArgReader::PeekWord() {
    TokenKind k = parser_.Tokens().Peek().kind;
    return k == TokenKind::Name || k == TokenKind::Keyword;
}

std::string TokenArgReader::ReadFilename() {
    if (!PeekFilename()) FailExpected("a file name");
    return std::string(parser_.Tokens().Next().text);
}

bool TokenArgReader::PeekFilename() {
    TokenKind k = parser_.Tokens().Peek().kind;
    return k == TokenKind::Name || k == TokenKind::Filename;
}

Surface TokenArgReader::ReadSurface() { return parser_.ParseSurfaceValue(usage_); }

void TokenArgReader::Warn(const std::string& message) {
    Report(Severity::Warn, Location(), "%s", message.c_str());
}

void TokenArgReader::Advise(const std::string& message) {
    Report(Severity::Advise, Location(), "%s", message.c_str());
}

void TokenArgReader::Fail(const std::string& message) { FailAt(Location(), usage_, message); }

void TokenArgReader::WarnAtLocation(const SourceLocation& where, const std::string& message) {
    Report(Severity::Warn, where, "%s", message.c_str());
}

void TokenArgReader::FailAtLocation(const SourceLocation& where, const std::string& message) {
    rs::FailAt(where, usage_, message);
}

void TokenArgReader::FailExpected(const std::string& what) {
    const Token& t = parser_.Tokens().Peek();
    FailAt(t.Location(), usage_, "Expected " + what + ", found " + t.Describe());
}

}  // namespace rs
