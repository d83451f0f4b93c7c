#include "libshade/builtin_preprocessor.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>

#include "libcommon/error.h"
#include "libcommon/limits.h"
#include "libcommon/parallel_build.h"

namespace rs {

namespace {

// Thrown inside this file to abandon the built-in path; PreprocessBuiltin turns it into
// "no result".
struct NeedsCpp {};
// Thrown by Expand at the top level when the tokens end inside a function-like macro's
// invocation (its arguments may continue on the next line).
struct Incomplete {};

// Deeper includes or macro-argument nesting go to cpp (which allows 200 include levels).
constexpr int kMaxDepth = 64;

enum class PpKind { Identifier, Blank, Newline, Other };

struct PpToken {
    PpKind kind;
    std::string text;
};
using PpTokens = std::vector<PpToken>;

struct Macro {
    bool functionLike = false;
    std::vector<std::string> params;
    PpTokens body;  // single blanks between tokens, none at either end

    bool operator==(const Macro& o) const {
        if (functionLike != o.functionLike || params != o.params || body.size() != o.body.size())
            return false;
        for (size_t i = 0; i < body.size(); ++i)
            if (body[i].kind != o.body[i].kind || body[i].text != o.body[i].text) return false;
        return true;
    }
};

constexpr bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
constexpr bool IsDigit(char c) { return c >= '0' && c <= '9'; }
constexpr bool IsIdentifierStart(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
constexpr bool IsIdentifierChar(char c) { return IsIdentifierStart(c) || IsDigit(c); }

// The characters that start a name cpp may define on its own: '_' and the first letters
// of kCppPredefinedNames (most words of a scene start with none of them).
constexpr std::array<bool, 256> kPredefinedStarts = [] {
    std::array<bool, 256> table{};
    table['_'] = true;
    for (std::string_view name : kCppPredefinedNames) table[static_cast<unsigned char>(name[0])] = true;
    return table;
}();

// An identifier cpp may define on its own: reserved names and the traditional ones.
bool IsPredefinedByCpp(std::string_view word) {
    if (!kPredefinedStarts[static_cast<unsigned char>(word[0])]) return false;
    if (word[0] == '_') return true;
    return std::find(std::begin(kCppPredefinedNames), std::end(kCppPredefinedNames), word) !=
           std::end(kCppPredefinedNames);
}

// A pp-number (C's preprocessing number: `1e5`, `.5`, `2x`) starts at s[i] when it is a digit,
// or a '.' followed by one; PpNumberEnd is the index just past it. Its letters are never an
// identifier, so they are never macro names.
bool StartsPpNumber(std::string_view s, size_t i) {
    return IsDigit(s[i]) || (s[i] == '.' && i + 1 < s.size() && IsDigit(s[i + 1]));
}
// The characters that continue any pp-number: identifier characters and '.' (looked up in
// a table: large scenes are mostly numbers).
constexpr std::array<bool, 256> kPpNumberChars = [] {
    std::array<bool, 256> table{};
    for (int c = 0; c < 256; ++c) table[c] = IsIdentifierChar(static_cast<char>(c)) || c == '.';
    return table;
}();
size_t PpNumberEnd(std::string_view s, size_t i) {
    for (++i; i < s.size(); ++i) {
        const char d = s[i];
        if (kPpNumberChars[static_cast<unsigned char>(d)]) continue;
        const char before = s[i - 1];
        const bool exponentSign =
            (d == '+' || d == '-') && (before == 'e' || before == 'E' || before == 'p' || before == 'P');
        if (!exponentSign) break;
    }
    return i;
}

// Whether a token may stand next to a macro name or parameter: then cpp's spacing of the
// expansion cannot join it to, or split it from, its neighbours in the scene language.
bool IsSeparator(const PpToken& t) {
    return t.kind == PpKind::Blank || t.kind == PpKind::Newline ||
           (t.kind == PpKind::Other && (t.text == "(" || t.text == ")" || t.text == ","));
}

// Splits comment-free text into tokens: identifiers, pp-numbers (one Other token, so the
// letters of `1e5` are not an identifier), blank runs (one blank), newlines and single
// characters. Throws NeedsCpp on quotes and on identifiers cpp predefines.
PpTokens Tokenize(std::string_view s) {
    PpTokens out;
    for (size_t i = 0; i < s.size();) {
        const char c = s[i];
        size_t j = i + 1;
        if (c == '\n') {
            out.push_back({PpKind::Newline, "\n"});
        } else if (IsBlank(c)) {
            while (j < s.size() && IsBlank(s[j])) ++j;
            out.push_back({PpKind::Blank, " "});
        } else if (IsIdentifierStart(c)) {
            while (j < s.size() && IsIdentifierChar(s[j])) ++j;
            const std::string_view word = s.substr(i, j - i);
            if (IsPredefinedByCpp(word)) throw NeedsCpp{};
            out.push_back({PpKind::Identifier, std::string(word)});
        } else if (StartsPpNumber(s, i)) {
            j = PpNumberEnd(s, i);
            out.push_back({PpKind::Other, std::string(s.substr(i, j - i))});
        } else if (c == '"' || c == '\'') {
            throw NeedsCpp{};
        } else {
            out.push_back({PpKind::Other, std::string(1, c)});
        }
        i = j;
    }
    return out;
}

// How MentionsMacro treats a character: skipped, the start of a pp-number (a '.' only
// when a digit follows), of an identifier, or a quote (which goes to cpp).
enum class ScanClass : unsigned char { Skip, Digit, Dot, Identifier, Quote };
constexpr std::array<ScanClass, 256> kScanClasses = [] {
    std::array<ScanClass, 256> table{};
    for (int c = 0; c < 256; ++c) {
        const char ch = static_cast<char>(c);
        table[c] = IsDigit(ch)                 ? ScanClass::Digit
                   : ch == '.'                 ? ScanClass::Dot
                   : IsIdentifierStart(ch)     ? ScanClass::Identifier
                   : ch == '"' || ch == '\'' ? ScanClass::Quote
                                               : ScanClass::Skip;
    }
    return table;
}();
ScanClass ScanClassOf(char c) { return kScanClasses[static_cast<unsigned char>(c)]; }

// Whether a line names one of `macros` (so it must be tokenized and expanded). Applies
// Tokenize's checks, without building tokens: most lines of large scenes mention none.
template <class Macros>
bool MentionsMacro(std::string_view line, const Macros& macros) {
    const size_t n = line.size();
    for (size_t i = 0; i < n;) {
        switch (ScanClassOf(line[i])) {
            case ScanClass::Skip:
                ++i;
                continue;
            case ScanClass::Quote:
                throw NeedsCpp{};
            case ScanClass::Dot:
                if (!StartsPpNumber(line, i)) {
                    ++i;
                    continue;
                }
                [[fallthrough]];
            case ScanClass::Digit:
                i = PpNumberEnd(line, i);  // its letters are not an identifier (as in Tokenize)
                continue;
            case ScanClass::Identifier:
                break;
        }
        size_t j = i + 1;
        while (j < n && IsIdentifierChar(line[j])) ++j;
        const std::string_view word = line.substr(i, j - i);
        if (IsPredefinedByCpp(word)) throw NeedsCpp{};
        if (!macros.empty() && macros.find(word) != macros.end()) return true;
        i = j;
    }
    return false;
}

// Whether StripComments copies `c` without looking at it: not the start of a comment or
// quote, nor anything it rejects.
constexpr bool IsPlainCharacter(unsigned char u) {
    const char c = static_cast<char>(u);
    return (u >= 0x20 || c == '\t' || c == '\n' || c == '\r') && u != 0x7f && c != '/' &&
           c != '"' && c != '\\' && c != '\'';
}
constexpr std::array<bool, 256> kPlainCharacters = [] {
    std::array<bool, 256> table{};
    for (int c = 0; c < 256; ++c) table[c] = IsPlainCharacter(static_cast<unsigned char>(c));
    return table;
}();
bool IsPlain(char c) { return kPlainCharacters[static_cast<unsigned char>(c)]; }

// What IsPlainText makes of a character: nothing to do, a letter or '_' (which may start an
// identifier), or anything that needs the full preprocessor: what IsPlainCharacter rejects
// ('/' (a comment may start), quotes, backslashes, control characters other than tab,
// newline and return, DEL) and '#'.
enum class PlainClass : unsigned char { Plain, IdentifierStart, Special };
constexpr std::array<PlainClass, 256> kPlainClasses = [] {
    std::array<PlainClass, 256> table{};
    for (int c = 0; c < 256; ++c) {
        const char ch = static_cast<char>(c);
        table[c] = IsIdentifierStart(ch) ? PlainClass::IdentifierStart
                   : !IsPlainCharacter(static_cast<unsigned char>(c)) || ch == '#'
                       ? PlainClass::Special
                       : PlainClass::Plain;
    }
    return table;
}();

// Runs of digits, blanks, newlines, '.' and '-' (most of a large scene's text: its numbers)
// are crossed sixteen bytes at a time.
constexpr char kCommonPlain[] = "0123456789 \n.-";
static_assert([] {
    for (const char* c = kCommonPlain; *c != '\0'; ++c)
        if (kPlainClasses[static_cast<unsigned char>(*c)] != PlainClass::Plain) return false;
    return true;
}());

// Whether the 16 bytes at p are all characters of kCommonPlain.
bool AllCommonPlain(const char* p) {
    typedef unsigned char Bytes16 __attribute__((vector_size(16)));
    Bytes16 v;
    std::memcpy(&v, p, sizeof v);
    const Bytes16 common = (v - '0' < 10) | (v == ' ') | (v == '\n') | (v == '.') | (v == '-');
    uint64_t halves[2];
    std::memcpy(halves, &common, sizeof halves);
    return (halves[0] & halves[1]) == ~uint64_t{0};
}

// The first index from i on of a character that is not Plain (the NUL at p[n] is not).
size_t SkipPlain(const char* p, size_t n, size_t i) {
    for (;;) {
        while (i + 16 <= n && AllCommonPlain(p + i)) i += 16;
        // Byte by byte up to the next sixteen (not past the NUL at p[n], which stops it).
        for (const size_t stop = i + 16; i < stop; ++i)
            if (kPlainClasses[static_cast<unsigned char>(p[i])] != PlainClass::Plain) return i;
    }
}

// Whether the characters of p[from, to) and the words that start there are plain (see
// IsPlainText; p has n characters and the NUL after them). A word that starts before `to`
// is read to its end, and one that starts before `from` is not a word start here, so spans
// that tile [0, n) together look at every character and every word once (a scan may also
// look past `to`, up to the next word start or special character: that only repeats a
// verdict on characters that are there).
bool IsPlainSpan(const char* p, size_t n, size_t from, size_t to) {
    for (size_t i = from; i < to;) {
        i = SkipPlain(p, n, i);
        if (kPlainClasses[static_cast<unsigned char>(p[i])] == PlainClass::Special)
            return i == n;  // the NUL after the text, or a special character
        // p[i] may start an identifier.
        const bool wordStart = i == 0 || !IsIdentifierChar(p[i - 1]);
        size_t j = i + 1;
        while (j < n && IsIdentifierChar(p[j])) ++j;
        if (wordStart && IsPredefinedByCpp(std::string_view(p + i, j - i))) return false;
        i = j;
    }
    return true;
}

// Whether `text` is plain: no directive, comment, quote, backslash or control character,
// and no word a cpp predefines. With no macros defined, the preprocessor's output for plain
// text is the text itself (with a final newline): every line is copied as it is. Large
// scenes are mostly plain, and their text is looked at in spans of a MiB on the build's
// threads (tetra: 25 MB, 6 ms on one thread, before anything else can run). Words here are
// runs of identifier characters starting with a letter or '_' not preceded by an
// identifier character, which include every identifier of Tokenize's and some letters of
// pp-numbers (`1.e5`): seeing more words only sends more texts to the full preprocessor,
// which decides exactly. The NUL that ends a std::string's characters is Special, so it
// ends every run of plain characters without a bounds check.
bool IsPlainText(const std::string& text) {
    const char* p = text.c_str();
    const size_t n = text.size();
    constexpr size_t kSpan = size_t{1} << 20;
    if (n < 4 * kSpan || !BuildLoopInstalled()) return IsPlainSpan(p, n, 0, n);
    std::vector<char> plain((n + kSpan - 1) / kSpan, 0);
    RunBuildLoopInChunks(n, kSpan, [&](size_t from, size_t to) {
        plain[from / kSpan] = IsPlainSpan(p, n, from, to);
    });
    return std::all_of(plain.begin(), plain.end(), [](char c) { return c != 0; });
}

// Replaces each comment by a blank followed by the newlines it contained, so every line
// keeps its number. Throws NeedsCpp on what cpp would treat specially outside comments:
// `//`, backslashes, apostrophes, control characters, and a '#' right after a comment that
// spans lines (whether that is a directive depends on where the comment started). Quoted
// text is copied as is (only an include line may have it; Tokenize rejects it elsewhere).
// An unterminated comment is left in place for the lexer to report with its location.
// Works in place (a comment's replacement is shorter than the comment), returning `text`.
std::string StripComments(std::string text) {
    size_t out = 0;  // text[0, out) is the result so far; out <= i
    // Moves text[from, to) to the result.
    const auto keep = [&](size_t from, size_t to) {
        if (out != from) std::copy(text.begin() + from, text.begin() + to, text.begin() + out);
        out += to - from;
    };
    for (size_t i = 0; i < text.size();) {
        const char c = text[i];
        const char next = i + 1 < text.size() ? text[i + 1] : '\0';
        if (c == '/' && next == '*') {
            const size_t end = text.find("*/", i + 2);
            if (end == std::string::npos) {
                keep(i, text.size());
                break;
            }
            const long newlines = std::count(text.begin() + i, text.begin() + end, '\n');
            text[out++] = ' ';
            std::fill_n(text.begin() + out, newlines, '\n');
            out += newlines;
            i = end + 2;
            if (newlines > 0) {
                size_t k = i;
                while (k < text.size() && IsBlank(text[k])) ++k;
                if (k < text.size() && text[k] == '#') throw NeedsCpp{};
            }
            continue;
        }
        if (c == '"') {
            const size_t end = text.find_first_of("\"\n", i + 1);
            if (end == std::string::npos || text[end] != '"') throw NeedsCpp{};
            keep(i, end + 1);
            i = end + 1;
            continue;
        }
        if ((c == '/' && next == '/') || c == '\\' || c == '\'' ||
            (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') ||
            c == 0x7f)
            throw NeedsCpp{};
        // Keeps the run of characters up to the next one that needs a look.
        size_t end = i + 1;
        while (end < text.size() && IsPlain(text[end])) ++end;
        keep(i, end);
        i = end;
    }
    text.resize(out);
    return text;
}

// The text Run emits. While it is a prefix of Run's input (every line so far passed as is),
// it is not built: Take then returns the input itself, so a scene without directives or
// macros is not copied.
class RunOutput {
  public:
    // `input` must not change until Take.
    explicit RunOutput(std::string& input) : input_(input) {}

    // Emits input[start, end) and a newline; `end` is the position of the line's newline,
    // or the input's size for a last line without one.
    void CopyLine(size_t start, size_t end) {
        if (verbatim_ && start == emitted_) {
            emitted_ = end + 1;  // past the input's end when the newline is added
            return;
        }
        Text().append(input_, start, end - start);
        text_ += '\n';
    }
    // The text emitted so far, to append to.
    std::string& Text() {
        if (verbatim_) {
            text_.reserve(input_.size());
            text_.assign(input_, 0, std::min(emitted_, input_.size()));
            if (emitted_ > input_.size()) text_ += '\n';
            verbatim_ = false;
        }
        return text_;
    }
    // The whole text (leaves the input moved from when it is that).
    std::string Take() {
        if (!verbatim_) return std::move(text_);
        if (emitted_ > input_.size()) {
            input_ += '\n';
        } else {
            input_.resize(emitted_);
        }
        return std::move(input_);
    }

  private:
    std::string& input_;
    bool verbatim_ = true;
    size_t emitted_ = 0;  // while verbatim_, the text is input_[0, emitted_) (see CopyLine)
    std::string text_;    // the text once not verbatim_
};

std::string_view TrimBlanks(std::string_view s) {
    while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
    while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
    return s;
}

PpTokens TrimBlankTokens(PpTokens t) {
    while (!t.empty() && t.back().kind == PpKind::Blank) t.pop_back();
    size_t first = 0;
    while (first < t.size() && t[first].kind == PpKind::Blank) ++first;
    t.erase(t.begin(), t.begin() + static_cast<long>(first));
    return t;
}

// Reads an identifier at the start of `s` (after blanks); empty when there is none.
std::string_view TakeIdentifier(std::string_view& s) {
    s = TrimBlanks(s);
    size_t n = 0;
    if (!s.empty() && IsIdentifierStart(s[0]))
        while (n < s.size() && IsIdentifierChar(s[n])) ++n;
    std::string_view word = s.substr(0, n);
    s.remove_prefix(n);
    if (!word.empty() && IsPredefinedByCpp(word)) throw NeedsCpp{};
    return word;
}

// The contents of the included file `path`, named on line `line` of `fileName`. A file
// that cannot be read goes to cpp (which reports it); one beyond the scene text limit is an
// error here, since cpp would read all of it (an endless device such as /dev/zero hangs it).
std::string ReadInclude(const std::string& path, const std::string& fileName, int line) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw NeedsCpp{};
    const size_t limit = static_cast<size_t>(Limits().sceneBytes);
    std::string contents;
    char block[65536];
    while (file.read(block, sizeof block) || file.gcount() > 0) {
        contents.append(block, static_cast<size_t>(file.gcount()));
        if (contents.size() > limit) {
            Report(Severity::Abort, {fileName, line}, "Included file %s exceeds %zu bytes",
                   path.c_str(), limit);
        }
    }
    if (file.bad()) throw NeedsCpp{};
    return contents;
}

class Preprocessor {
  public:
    explicit Preprocessor(const std::vector<CommandLineMacro>& predefined) {
        for (const CommandLineMacro& m : predefined) Define(m.name + " " + m.body);
    }

    // Preprocesses one file's text; its includes are read recursively.
    std::string Run(std::string text, const std::string& fileName, int depth);

  private:
    // Processes `#define` given the rest of its line.
    void Define(std::string_view rest);
    // Expands the macros in `in` (macros named in `disabled` are being expanded already).
    PpTokens Expand(const PpTokens& in, std::vector<std::string>& disabled, int depth);
    // Bounds the work on runaway input (macros that double at every level): such input
    // goes to cpp. The bound, in tokens produced, is far above what scenes use.
    void CountWork(size_t units) {
        work_ += units;
        if (work_ > kMaxWork) throw NeedsCpp{};
    }
    static constexpr size_t kMaxWork = size_t{1} << 22;

    std::map<std::string, Macro, std::less<>> macros_;
    size_t work_ = 0;
};

void Preprocessor::Define(std::string_view rest) {
    const std::string name(TakeIdentifier(rest));
    if (name.empty()) throw NeedsCpp{};
    Macro m;
    if (!rest.empty() && rest[0] == '(') {
        m.functionLike = true;
        rest.remove_prefix(1);
        for (bool first = true;; first = false) {
            std::string_view param = TakeIdentifier(rest);
            rest = TrimBlanks(rest);
            if (param.empty()) {
                if (!(first && !rest.empty() && rest[0] == ')')) throw NeedsCpp{};  // `...` too
            } else {
                if (std::find(m.params.begin(), m.params.end(), param) != m.params.end())
                    throw NeedsCpp{};
                m.params.emplace_back(param);
            }
            if (rest.empty()) throw NeedsCpp{};
            const char c = rest[0];
            rest.remove_prefix(1);
            if (c == ')') break;
            if (c != ',') throw NeedsCpp{};
        }
    } else if (!rest.empty() && !IsBlank(rest[0])) {
        throw NeedsCpp{};  // cpp warns about a missing blank after the name
    }
    m.body = TrimBlankTokens(Tokenize(TrimBlanks(rest)));
    for (const PpToken& t : m.body)
        if (t.text == "#") throw NeedsCpp{};  // stringizing and pasting
    auto it = macros_.find(name);
    if (it != macros_.end()) {
        if (!(it->second == m)) throw NeedsCpp{};  // cpp warns about a redefinition
        return;
    }
    macros_.emplace(name, std::move(m));
}

PpTokens Preprocessor::Expand(const PpTokens& in, std::vector<std::string>& disabled, int depth) {
    if (depth > kMaxDepth) throw NeedsCpp{};
    PpTokens out;
    for (size_t i = 0; i < in.size(); ++i) {
        const auto it = in[i].kind == PpKind::Identifier ? macros_.find(in[i].text) : macros_.end();
        if (it == macros_.end()) {
            out.push_back(in[i]);
            continue;
        }
        // A macro cpp would leave unexpanded (inside its own expansion, or a function-like
        // one without arguments) could expand later in ways not followed here.
        if (std::find(disabled.begin(), disabled.end(), it->first) != disabled.end())
            throw NeedsCpp{};
        const Macro& macro = it->second;
        PpTokens replacement;
        size_t last = i;  // the invocation's last token
        long newlines = 0;
        if (!macro.functionLike) {
            replacement = macro.body;
        } else {
            size_t j = i + 1;
            for (; j < in.size() && (in[j].kind == PpKind::Blank || in[j].kind == PpKind::Newline); ++j)
                newlines += in[j].kind == PpKind::Newline;
            if (j == in.size() && depth == 0) throw Incomplete{};
            if (j == in.size() || in[j].text != "(") throw NeedsCpp{};
            std::vector<PpTokens> args(1);
            int nesting = 1;
            for (++j; j < in.size(); ++j) {
                const PpToken& t = in[j];
                if (t.kind == PpKind::Newline) {
                    ++newlines;
                    args.back().push_back({PpKind::Blank, " "});
                    continue;
                }
                if (t.text == "(") ++nesting;
                if (t.text == ")" && --nesting == 0) break;
                if (t.text == "," && nesting == 1) {
                    args.emplace_back();
                    continue;
                }
                args.back().push_back(t);
            }
            if (j == in.size()) {
                if (depth == 0) throw Incomplete{};
                throw NeedsCpp{};
            }
            last = j;
            for (PpTokens& a : args) a = TrimBlankTokens(std::move(a));
            const bool noArguments = macro.params.empty() && args.size() == 1 && args[0].empty();
            if (!noArguments && args.size() != macro.params.size()) throw NeedsCpp{};
            // Arguments are expanded on their own first (none is an operand of # or ##).
            for (PpTokens& a : args) a = Expand(a, disabled, depth + 1);
            for (size_t b = 0; b < macro.body.size(); ++b) {
                const PpToken& t = macro.body[b];
                const auto p = t.kind == PpKind::Identifier
                                   ? std::find(macro.params.begin(), macro.params.end(), t.text)
                                   : macro.params.end();
                if (p == macro.params.end()) {
                    replacement.push_back(t);
                    continue;
                }
                if ((b > 0 && !IsSeparator(macro.body[b - 1])) ||
                    (b + 1 < macro.body.size() && !IsSeparator(macro.body[b + 1])))
                    throw NeedsCpp{};
                const PpTokens& arg = args[static_cast<size_t>(p - macro.params.begin())];
                replacement.insert(replacement.end(), arg.begin(), arg.end());
            }
        }
        if ((i > 0 && !IsSeparator(in[i - 1])) || (last + 1 < in.size() && !IsSeparator(in[last + 1])))
            throw NeedsCpp{};
        disabled.push_back(it->first);
        PpTokens result = Expand(replacement, disabled, depth + 1);
        disabled.pop_back();
        out.push_back({PpKind::Blank, " "});
        out.insert(out.end(), result.begin(), result.end());
        out.push_back({PpKind::Blank, " "});
        // An invocation written over several lines: the lines after it keep their numbers.
        for (long n = 0; n < newlines; ++n) out.push_back({PpKind::Newline, "\n"});
        CountWork(result.size());
        i = last;
    }
    return out;
}

std::string Preprocessor::Run(std::string text, const std::string& fileName, int depth) {
    if (depth > kMaxDepth) throw NeedsCpp{};
    std::string clean = StripComments(std::move(text));
    // Conditional groups: a line is processed when every enclosing group is taken.
    struct Group {
        bool enclosingActive;
        bool condition;
        bool inElse = false;
        bool Active() const { return enclosingActive && (inElse ? !condition : condition); }
    };
    std::vector<Group> groups;
    auto active = [&] { return groups.empty() || groups.back().Active(); };

    RunOutput output(clean);
    PpTokens pending;  // text lines whose macros are not expanded yet
    // Expands and emits the pending lines; at a directive or the end of the file
    // (`final`) an invocation still open goes to cpp, otherwise it waits for more lines.
    auto flush = [&](bool final) {
        if (pending.empty()) return;
        std::string& out = output.Text();
        std::vector<std::string> disabled;
        const size_t before = out.size();
        try {
            for (const PpToken& t : Expand(pending, disabled, 0)) out += t.text;
        } catch (const Incomplete&) {
            if (final) throw NeedsCpp{};
            return;
        }
        pending.clear();
        CountWork(out.size() - before);
    };
    int lineNumber = 0;
    for (size_t start = 0; start < clean.size();) {
        size_t end = clean.find('\n', start);
        const bool lastLine = end == std::string::npos;
        if (lastLine) end = clean.size();
        std::string_view line(clean.data() + start, end - start);
        const size_t lineStart = start;
        start = end + 1;
        ++lineNumber;

        std::string_view rest = TrimBlanks(line);
        if (rest.empty() || rest[0] != '#') {
            if (active() && pending.empty() && !MentionsMacro(line, macros_)) {
                output.CopyLine(lineStart, end);
            } else if (active()) {
                PpTokens tokens = Tokenize(line);
                pending.insert(pending.end(), tokens.begin(), tokens.end());
                pending.push_back({PpKind::Newline, "\n"});
                flush(false);
            } else {
                output.Text() += '\n';
            }
            continue;
        }
        flush(true);
        std::string& out = output.Text();
        rest.remove_prefix(1);
        const std::string_view directive = TakeIdentifier(rest);
        rest = TrimBlanks(rest);
        if (directive == "ifdef" || directive == "ifndef" || directive == "if") {
            if (!active()) {
                groups.push_back({false, false});
            } else {
                if (directive == "if") throw NeedsCpp{};
                const std::string_view name = TakeIdentifier(rest);
                if (name.empty() || !TrimBlanks(rest).empty()) throw NeedsCpp{};
                const bool defined = macros_.find(name) != macros_.end();
                groups.push_back({true, directive == "ifdef" ? defined : !defined});
            }
        } else if (directive == "else" || directive == "endif") {
            if (groups.empty() || (groups.back().enclosingActive && !rest.empty())) throw NeedsCpp{};
            if (directive == "endif") {
                groups.pop_back();
            } else {
                if (groups.back().inElse) throw NeedsCpp{};
                groups.back().inElse = true;
            }
        } else if (directive == "elif") {
            if (groups.empty() || groups.back().enclosingActive) throw NeedsCpp{};
        } else if (!active()) {
            // Any other directive in a skipped group is ignored, as cpp does.
        } else if (directive == "define") {
            Define(rest);
        } else if (directive == "undef") {
            const std::string_view name = TakeIdentifier(rest);
            if (name.empty() || !TrimBlanks(rest).empty()) throw NeedsCpp{};
            if (auto it = macros_.find(name); it != macros_.end()) macros_.erase(it);
        } else if (directive == "include") {
            if (rest.size() < 3 || rest[0] != '"') throw NeedsCpp{};
            const size_t close = rest.find('"', 1);
            if (close == std::string_view::npos || !TrimBlanks(rest.substr(close + 1)).empty())
                throw NeedsCpp{};
            const std::string name(rest.substr(1, close - 1));
            const size_t slash = fileName.rfind('/');
            const std::string path = name[0] == '/' || slash == std::string::npos
                                         ? name
                                         : fileName.substr(0, slash + 1) + name;
            std::string included = Run(ReadInclude(path, fileName, lineNumber), path, depth + 1);
            if (!included.empty() && included.back() != '\n') included += '\n';
            out += "# 1 \"" + path + "\"\n" + included + "# " + std::to_string(lineNumber + 1) +
                   " \"" + fileName + "\"";
        } else if (!directive.empty() || !rest.empty()) {
            throw NeedsCpp{};  // any other directive (the null directive `#` is allowed)
        }
        if (!lastLine) out += '\n';
    }
    flush(true);
    if (!groups.empty()) throw NeedsCpp{};  // cpp reports the unterminated group
    return output.Take();
}

}  // namespace

std::optional<std::string> PreprocessBuiltin(std::string text, const std::string& fileName,
                                             const std::vector<CommandLineMacro>& predefined) {
    if (predefined.empty() && IsPlainText(text)) {
        if (!text.empty() && text.back() != '\n') text += '\n';
        return text;
    }
    try {
        Preprocessor preprocessor(predefined);
        return preprocessor.Run(std::move(text), fileName, 0);
    } catch (const NeedsCpp&) {
        return std::nullopt;
    }
}

}  // namespace rs
