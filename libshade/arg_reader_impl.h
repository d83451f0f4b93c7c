// The ArgReader (libcommon/arg_reader.h) over the parser's token stream. The parser reads
// its own keyword arguments through the same class, so every number, name and file name
// is read, checked and reported in one way.
#pragma once

#include <string>
#include <string_view>

#include "libcommon/arg_reader.h"
#include "libshade/lexer.h"
#include "libshade/symtab.h"
#include "libsurf/surface.h"

namespace rs {

// What the reader needs from the parser besides the tokens.
class ParserServices {
  public:
    virtual ~ParserServices() = default;
    virtual TokenStream& Tokens() = 0;
    virtual const SymbolTable& Symbols() const = 0;
    // Parses a surface expression (spec §2 `surface`) in the current scope.
    virtual Surface ParseSurfaceValue(std::string_view usage) = 0;
    virtual bool FlipNormals() const = 0;
};

class TokenArgReader final : public ArgReader {
  public:
    // `keyword` locates the keyword being read (for Warn/Fail); `usage` is appended to
    // fatal messages and must outlive the reader (it is a literal or a table's text).
    TokenArgReader(ParserServices& parser, const SourceLocation& keyword, std::string_view usage)
        : parser_(parser), file_(InternFileName(keyword.file)), line_(keyword.line), usage_(usage) {}
    // The same at a token's location (kept as the token's interned file name and line: the
    // parser makes a reader per object, and building a location would copy the name).
    TokenArgReader(ParserServices& parser, const Token& keyword, std::string_view usage)
        : parser_(parser), file_(keyword.file ? keyword.file : InternFileName({})),
          line_(keyword.line), usage_(usage) {}

    double ReadNumber() override;
    int ReadInt() override;
    AnimatedValue ReadAnimatedNumber() override;
    bool PeekNumber() override;
    bool Accept(const char* word) override;
    bool Peek(const char* word) override;
    std::string ReadName() override;
    std::string ReadWord() override;
    bool PeekWord() override;
    std::string ReadFilename() override;
    bool PeekFilename() override;
    Surface ReadSurface() override;
    bool FlipNormals() const override { return parser_.FlipNormals(); }
    SourceLocation Location() const override { return {*file_, line_}; }
    void Warn(const std::string& message) override;
    void Advise(const std::string& message) override;
    [[noreturn]] void Fail(const std::string& message) override;
    SourceLocation NextLocation() override { return parser_.Tokens().Peek().Location(); }
    void WarnAtLocation(const SourceLocation& where, const std::string& message) override;
    [[noreturn]] void FailAtLocation(const SourceLocation& where,
                                     const std::string& message) override;

    // The expression of an animatable argument (spec `aexpr`), static or time-varying.
    ExprPtr ReadExpression();
    // Fails at the next token: "Expected <what>, found <token>".
    [[noreturn]] void FailExpected(const std::string& what);
    std::string_view usage() const { return usage_; }

  private:
    ParserServices& parser_;
    const std::string* file_;  // interned (InternFileName)
    int line_;
    std::string_view usage_;
};

}  // namespace rs
