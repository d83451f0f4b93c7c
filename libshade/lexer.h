// Tokens of the scene language (spec §1.2, §1.3) and a streaming lexer over preprocessed text.
//
// The lexer also interprets line markers (`# n "file"`, `# n`, `#line n "file"`, with gcc's
// trailing flags) at the start of a line, so locations refer to the original files.
// Lexical errors (unterminated comments, unknown '#' controls, numbers out of range) are
// reported with rs::Report(Severity::Abort, ...) and therefore throw FatalError.
#pragma once

#include <cstddef>
#include <deque>
#include <memory>
#include <string>
#include <string_view>

#include "libcommon/error.h"

namespace rs {

// Longest name or file name (a limit, docs/robustness.md): longer ones are a lexical error, so
// that messages quoting names stay short.
inline constexpr size_t kMaxNameLength = 4096;

enum class TokenKind {
    End,       // end of input
    Number,    // unsigned literal; `number` holds its value
    Name,      // letter { letter | digit | . | _ | - }, not a keyword
    Filename,  // a name with directory components (contains '/')
    Keyword,   // `keyword` holds the canonical spelling (synonyms folded)
    Char,      // any other single character, in `text`
};

struct Token {
    TokenKind kind = TokenKind::End;
    std::string text;     // the spelling as written
    std::string keyword;  // canonical keyword (Keyword tokens only)
    double number = 0;
    // Where the token starts: the file name, shared by the tokens of a file (null only in a
    // default-constructed Token), and the line.
    std::shared_ptr<const std::string> file;
    int line = 0;

    SourceLocation Location() const { return {file ? *file : std::string(), line}; }

    bool IsKeyword(const char* k) const { return kind == TokenKind::Keyword && keyword == k; }
    bool IsChar(char c) const {
        return kind == TokenKind::Char && text.size() == 1 && text[0] == c;
    }
    // A short description for messages: "'sphere'", "end of input".
    std::string Describe() const;
};

// The canonical spelling of a keyword (`polygon` → `poly`, `samples` → `sample`, ...), or an
// empty string when `word` is not a keyword.
std::string CanonicalKeyword(const std::string& word);
// Whether `word` spells the keyword whose canonical spelling is `keyword` (it is that
// spelling or one of its synonyms); cheaper than comparing CanonicalKeyword(word).
bool SpellsKeyword(std::string_view word, std::string_view keyword);

class Lexer {
  public:
    // `fileName` names the text in locations until a line marker says otherwise.
    Lexer(std::string text, std::string fileName);

    Token Next();

  private:
    void SkipSpaceAndComments();
    void ReadLineMarker();
    size_t MatchFilename(size_t start) const;  // length of the longest name/filename at start
    size_t MatchNumber(size_t start) const;    // length of the number at start, 0 if none
    [[noreturn]] void Fail(const char* format, const std::string& arg) const;

    std::string text_;
    size_t pos_ = 0;
    std::shared_ptr<const std::string> file_;
    int line_ = 1;
    bool atLineStart_ = true;
};

// A lexer with arbitrary lookahead.
class TokenStream {
  public:
    TokenStream(std::string text, std::string fileName)
        : lexer_(std::move(text), std::move(fileName)) {}

    // The k-th token ahead (0 = next), without consuming it.
    const Token& Peek(size_t k = 0);
    Token Next();

  private:
    Lexer lexer_;
    std::deque<Token> ahead_;
};

}  // namespace rs
