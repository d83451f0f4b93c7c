// Tokens of the scene language (spec §1.2, §1.3) and a streaming lexer over preprocessed text.
//
// The lexer also interprets line markers (`# n "file"`, `# n`, `#line n "file"`, with gcc's
// trailing flags) at the start of a line, so locations refer to the original files.
// Lexical errors (unterminated comments, unknown '#' controls, numbers out of range) are
// reported with rs::Report(Severity::Abort, ...) and therefore throw FatalError.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

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

// A token views its spelling in the lexer's text, so it is valid while the Lexer (or the
// TokenStream) that made it lives; copying one copies no characters.
struct Token {
    TokenKind kind = TokenKind::End;
    std::string_view text;     // the spelling as written (in the lexer's text)
    std::string_view keyword;  // canonical keyword (Keyword tokens only; a static string)
    double number = 0;
    // Where the token starts: the file name, interned for the whole process (InternFileName;
    // null only in a default-constructed Token), and the line.
    const std::string* file = nullptr;
    int line = 0;

    SourceLocation Location() const { return {file ? *file : std::string(), line}; }

    bool IsKeyword(std::string_view k) const { return kind == TokenKind::Keyword && keyword == k; }
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

// The one copy of `name` kept for the rest of the process (thread-safe; there are few
// distinct file names, and tokens then carry a plain pointer instead of a counted one).
const std::string* InternFileName(const std::string& name);

class Lexer {
  public:
    // `fileName` names the text in locations until a line marker says otherwise; the text
    // starts at line `firstLine` of it (a piece of a larger text starts further down).
    Lexer(std::string text, std::string fileName, int firstLine = 1);

    Token Next();
    // The same into `tok`.
    void Next(Token& tok);

    // ReadLiteral and PeekExpression (expression_parser.h) without making tokens: the same
    // answers, values and lexical errors (reported) as Next's tokens give them. When the
    // answer is false, only the blanks, comments and line markers before the next token are
    // consumed.
    bool NextLiteral(double& value);
    bool StartsExpression();

    // The text lexed; tokens view it.
    const std::string& Text() const { return text_; }
    // Continues at byte `offset` of the text, a token's start on line `line` of the file
    // named last (no line marker may lie between the current position and `offset`).
    void SeekTo(size_t offset, int line) {
        pos_ = offset;
        line_ = line;
        atLineStart_ = offset == 0 || text_[offset - 1] == '\n';
    }

  private:
    // Where the lexer is, to go back to after looking past a sign.
    struct Position {
        size_t pos;
        const std::string* file;
        int line;
        bool atLineStart;
    };
    Position Save() const { return {pos_, file_, line_, atLineStart_}; }
    void Restore(const Position& p) {
        pos_ = p.pos, file_ = p.file, line_ = p.line, atLineStart_ = p.atLineStart;
    }
    // Whether a Number token starts at pos_ (after SkipSpaceAndComments).
    bool AtNumber() const;
    // Reads the Number token at pos_ into `value`, if one starts there.
    bool ReadNumberValue(double& value);

    // Moves past blanks, newlines, comments and line markers to the next token.
    void SkipSpaceAndComments() {
        // Inline for what usually lies between tokens: spaces, then a token's first
        // character (not a NUL, which may end the text, nor one that may start a comment
        // or a line marker).
        const char* text = text_.c_str();
        size_t p = pos_;
        while (text[p] == ' ') ++p;
        pos_ = p;
        const unsigned char c = static_cast<unsigned char>(text[p]);
        if (c <= ' ' || c == '/' || c == '#') SkipSpaceAndCommentsSlowly();
    }
    void SkipSpaceAndCommentsSlowly();  // the same in general
    void ReadLineMarker();
    size_t MatchFilename(size_t start) const;  // length of the longest name/filename at start
    // Lexes the number at pos_, if one starts there, into tok (kind, text, value) and moves
    // past it; returns false (and leaves everything unchanged) when none does.
    bool ReadNumber(Token& tok);
    [[noreturn]] void Fail(const char* format, const std::string& arg) const;

    std::string text_;
    size_t pos_ = 0;
    const std::string* file_;  // interned
    int line_ = 1;
    bool atLineStart_ = true;
};

// A lexer with arbitrary lookahead, buffered in a ring that is reused (no allocation per
// token). Its tokens view its text: they are valid while the stream lives.
class TokenStream {
  public:
    TokenStream(std::string text, std::string fileName, int firstLine = 1);
    TokenStream(const TokenStream&) = delete;
    TokenStream& operator=(const TokenStream&) = delete;

    // The k-th token ahead (0 = next), without consuming it. The reference stays valid until
    // the next call of Next, or of Peek with a k of kInitialRing or more (which grows the ring;
    // the parser looks at most one token past the next).
    const Token& Peek(size_t k = 0) {
        while (count_ <= k) Push();
        return ring_[(head_ + k) & (ring_.size() - 1)];
    }
    // Drops the next token.
    void Skip() {
        if (count_ == 0) Push();
        head_ = (head_ + 1) & (ring_.size() - 1);
        --count_;
    }
    // The lexer, when ReadLiteral and PeekExpression may ask it directly (NextLiteral,
    // StartsExpression): no token is buffered; else null.
    Lexer* DirectLexer() { return count_ == 0 ? &lexer_ : nullptr; }
    // Where a token of this stream starts in its text (Lexer::Text).
    size_t Offset(const Token& t) const {
        return static_cast<size_t>(t.text.data() - lexer_.Text().data());
    }
    const std::string& Text() const { return lexer_.Text(); }
    // Drops the buffered tokens and continues at `offset` (Lexer::SeekTo).
    void SeekTo(size_t offset, int line) {
        head_ = count_ = 0;
        lexer_.SeekTo(offset, line);
    }
    Token Next() {
        if (count_ == 0) Push();
        Token t = std::move(ring_[head_]);
        head_ = (head_ + 1) & (ring_.size() - 1);
        --count_;
        return t;
    }

  private:
    static constexpr size_t kInitialRing = 4;  // a power of two, like every later size
    void Push();  // lexes one more token into the ring, growing it when full

    Lexer lexer_;
    std::vector<Token> ring_;
    size_t head_ = 0, count_ = 0;  // ring_[head_] is the next token; count_ are buffered
};

}  // namespace rs
