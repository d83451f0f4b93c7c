#include "libshade/lexer.h"

#include <array>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <mutex>
#include <unordered_set>

namespace rs {

namespace {

// The keywords spelt in more than one way (spec §1.3).
struct Synonym {
    std::string_view word;
    std::string_view keyword;  // its canonical spelling
};
constexpr Synonym kSynonyms[] = {{"polygon", "poly"},       {"reflective", "reflect"},
                                 {"transparent", "transp"}, {"translucency", "translu"},
                                 {"resolution", "screen"},  {"samples", "sample"}};

// Spec §1.3: every keyword in its canonical spelling, plus `implicit`, our Implicit Patches
// primitive (libray/libobj/implicit/README.md), and `patches`, its debug texture
// (libray/libtext/patches_texture.h). Synonyms (kSynonyms) map to the spelling the grammar
// uses; `samples` (the quick reference's spelling) is accepted for `sample`.
constexpr std::string_view kKeywords[] = {
    "ambient",     "aperture",    "applysurf",    "area",      "atmosphere", "background",
    "blob",        "blotch",      "body",         "box",       "bump",       "checker",
    "cloud",       "component",   "cone",         "contrast",  "crop",       "cursurf",
    "cutoff",      "cylinder",    "cylindrical",  "define",    "diffuse",    "difference",
    "directional", "disc",        "end",          "extended",  "extinct",    "eyep",
    "eyesep",      "fbm",         "fbmbump",      "filter",    "focaldist",  "fog",
    "fogdeck",     "fov",         "framelength",  "frames",    "gauss",      "gloss",
    "grid",        "heightfield", "image",        "implicit",  "index",      "intersect",
    "jitter",      "patches",
    "light",       "list",        "lookp",        "map",       "marble",     "maxdepth",
    "mist",        "mount",       "name",         "nojitter",  "noshadow",   "object",
    "outfile",     "planar",      "plane",        "point",     "poly",       "print",
    "quiet",       "range",       "reflect",      "report",    "rotate",     "sample",
    "scale",       "screen",      "shadowtransp", "shutter",   "sky",        "smooth",
    "specpow",     "specular",    "sphere",       "spherical", "spot",       "starttime",
    "stripe",      "surface",     "textsurf",     "texture",   "tile",       "torus",
    "transform",   "translate",   "translu",      "transp",    "triangle",   "triangleuv",
    "union",       "up",          "uv",           "verbose",   "window",     "windy",
    "wood"};

constexpr bool kKeywordsFitTheIndex = [] {  // lower-case and shorter than 16 characters
    for (std::string_view k : kKeywords)
        if (k.empty() || k.size() >= 16 || k[0] < 'a' || k[0] > 'z') return false;
    for (const Synonym& s : kSynonyms)
        if (s.word.empty() || s.word.size() >= 16 || s.word[0] < 'a' || s.word[0] > 'z') return false;
    return true;
}();
static_assert(kKeywordsFitTheIndex);

// The keywords and synonyms (as Synonym: spelling, canonical keyword) grouped by first
// letter and length, so that a lookup (one per name a scene spells) compares a word with
// the few spellings of its group and hashes nothing.
class KeywordIndex {
  public:
    KeywordIndex() {
        std::vector<Synonym> all;
        for (std::string_view k : kKeywords) all.push_back({k, k});
        for (const Synonym& s : kSynonyms) all.push_back(s);
        for (const Synonym& s : all) ++groups_[Group(s.word)].count;  // every word has a group
        uint16_t start = 0;
        for (Range& g : groups_) {
            g.start = start;
            start = static_cast<uint16_t>(start + g.count);
        }
        entries_.resize(all.size());
        std::array<uint16_t, kGroups> filled{};
        for (const Synonym& s : all) {
            const size_t g = Group(s.word);
            entries_[groups_[g].start + filled[g]++] = s;
        }
    }

    // The canonical spelling of keyword `word`, or an empty view.
    std::string_view Find(std::string_view word) const {
        if (word.empty() || word.size() >= kLengths || word[0] < 'a' || word[0] > 'z') return {};
        const Range& g = groups_[Group(word)];
        for (uint16_t i = g.start; i < g.start + g.count; ++i)
            if (entries_[i].word == word) return entries_[i].keyword;
        return {};
    }

  private:
    static constexpr size_t kLengths = 16;  // longer words are no keywords
    static constexpr size_t kGroups = 26 * kLengths;
    // `word` starts with a lower-case letter and is shorter than kLengths.
    static size_t Group(std::string_view word) {
        return static_cast<size_t>(word[0] - 'a') * kLengths + word.size();
    }
    struct Range {
        uint16_t start = 0, count = 0;
    };
    std::array<Range, kGroups> groups_{};
    std::vector<Synonym> entries_;  // by group
};

// The canonical spelling of keyword `word`, or an empty view.
std::string_view FindKeyword(std::string_view word) {
    static const KeywordIndex index;
    return index.Find(word);
}

bool IsLetter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsNameChar(char c) { return IsLetter(c) || IsDigit(c) || c == '.' || c == '_' || c == '-'; }
bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
char At(const std::string& s, size_t i) { return i < s.size() ? s[i] : '\0'; }

// Input quoted in a message: at most 60 bytes, then "..." (a 1 MB name or number must not
// become a 1 MB message).
std::string Abbreviate(const std::string& s) {
    constexpr size_t kMaxQuoted = 60;
    if (s.size() <= kMaxQuoted) return s;
    return s.substr(0, kMaxQuoted) + "...";
}

}  // namespace

std::string CanonicalKeyword(const std::string& word) { return std::string(FindKeyword(word)); }

bool SpellsKeyword(std::string_view word, std::string_view keyword) {
    if (word == keyword) return true;
    for (const Synonym& s : kSynonyms) {
        if (word == s.word) return keyword == s.keyword;
    }
    return false;
}

std::string Token::Describe() const {
    switch (kind) {
        case TokenKind::End:
            return "end of input";
        case TokenKind::Char: {
            unsigned char c = static_cast<unsigned char>(text[0]);
            if (c < 32 || c >= 127) return StringPrintf("character 0x%02x", c);
            break;
        }
        default:
            break;
    }
    std::string quoted = "'";  // built by appending: gcc 12's -Wrestrict misreads
    quoted += Abbreviate(std::string(text));  // "'" + std::string&& here
    quoted += '\'';
    return quoted;
}

Lexer::Lexer(std::string text, std::string fileName, int firstLine)
    : text_(std::move(text)), file_(InternFileName(fileName)), line_(firstLine) {}

const std::string* InternFileName(const std::string& name) {
    static std::mutex mutex;
    static std::unordered_set<std::string> names;  // elements never move
    std::lock_guard<std::mutex> lock(mutex);
    return &*names.insert(name).first;
}

void Lexer::Fail(const char* format, const std::string& arg) const {
    const std::string message = StringPrintf(format, Abbreviate(arg).c_str());
    Report(Severity::Abort, SourceLocation{*file_, line_}, "%s", message.c_str());
    throw FatalError(Severity::Abort, message);  // not reached: Report throws for Abort
}

void Lexer::SkipSpaceAndCommentsSlowly() {
    // Locals, and the NUL after the text ends every run (most of a large scene's characters
    // between tokens are single blanks and newlines).
    const char* text = text_.c_str();
    const size_t size = text_.size();
    while (true) {
        size_t p = pos_;
        while (IsBlank(text[p])) ++p;
        if (text[p] == '\n') {
            ++line_;
            pos_ = p + 1;
            atLineStart_ = true;
            continue;
        }
        pos_ = p;
        if (p >= size) return;
        const char c = text[p];
        if (c == '/' && text[p + 1] == '*') {
            int startLine = line_;
            size_t end = text_.find("*/", pos_ + 2);
            if (end == std::string::npos) {
                line_ = startLine;
                Fail("%s", "Unterminated comment");
            }
            for (size_t i = pos_; i < end; ++i)
                if (text_[i] == '\n') ++line_;
            pos_ = end + 2;
        } else if (c == '#' && atLineStart_) {
            ReadLineMarker();
        } else {
            return;
        }
    }
}

// `# n "file" flags...`, `# n`, `#line n "file"`: sets the number of the NEXT line to n.
void Lexer::ReadLineMarker() {
    size_t eol = text_.find('\n', pos_);
    if (eol == std::string::npos) eol = text_.size();
    std::string line = text_.substr(pos_, eol - pos_);
    size_t i = 1;
    auto skipBlanks = [&] {
        while (i < line.size() && IsBlank(line[i])) ++i;
    };
    skipBlanks();
    if (line.compare(i, 4, "line") == 0) {
        i += 4;
        skipBlanks();
    }
    size_t digitsStart = i;
    while (i < line.size() && IsDigit(line[i])) ++i;
    if (i == digitsStart || i - digitsStart > 9) Fail("Unknown '#' control: %s", line);
    int number = std::atoi(line.substr(digitsStart, i - digitsStart).c_str());
    skipBlanks();
    std::string file = *file_;
    if (i < line.size() && line[i] == '"') {
        size_t close = line.find('"', i + 1);
        if (close == std::string::npos) Fail("Unknown '#' control: %s", line);
        file = line.substr(i + 1, close - i - 1);
        if (file.empty() || file == "<stdin>") file = "stdin";  // gcc names stdin "<stdin>"
        i = close + 1;
        // gcc appends flags (1 = enter include, 2 = return, 3 = system header, 4 = extern C).
        while (i < line.size() && (IsBlank(line[i]) || IsDigit(line[i]))) ++i;
    }
    if (i != line.size()) Fail("Unknown '#' control: %s", line);
    pos_ = eol < text_.size() ? eol + 1 : eol;
    if (file != *file_) file_ = InternFileName(file);
    line_ = number;
    atLineStart_ = true;
}

// Longest match of the filename pattern (spec §1.2): an optional `/` or `//`, then any
// number of components (`.`, `..` or a name) each followed by `/`, then a final name.
// A bare name is the degenerate case. Returns 0 when nothing matches.
size_t Lexer::MatchFilename(size_t start) const {
    size_t p = start;
    if (At(text_, p) == '/') {
        ++p;
        if (At(text_, p) == '/') ++p;
    }
    size_t best = 0;
    while (true) {
        char c = At(text_, p);
        if (IsLetter(c)) {
            size_t q = p + 1;
            while (IsNameChar(At(text_, q))) ++q;
            best = q - start;
            if (At(text_, q) != '/') break;
            p = q + 1;
        } else if (c == '.') {
            size_t q = At(text_, p + 1) == '.' ? p + 2 : p + 1;
            if (At(text_, q) != '/') break;
            p = q + 1;
        } else {
            break;
        }
    }
    return best;
}

Token Lexer::Next() {
    Token tok;
    Next(tok);
    return tok;
}

void Lexer::Next(Token& tok) {
    SkipSpaceAndComments();
    tok.kind = TokenKind::End;
    tok.text = {};
    tok.keyword = {};
    tok.number = 0;
    tok.file = file_;
    tok.line = line_;
    if (pos_ >= text_.size()) return;
    atLineStart_ = false;

    char c = text_[pos_];
    if ((IsDigit(c) || c == '.') && ReadNumber(tok)) return;
    if (IsLetter(c) || c == '/' || c == '.') {
        if (size_t n = MatchFilename(pos_); n > 0) {
            tok.text = std::string_view(text_).substr(pos_, n);
            pos_ += n;
            if (n > kMaxNameLength)
                Fail(StringPrintf("Name longer than %zu characters: %%s", kMaxNameLength).c_str(),
                     std::string(tok.text));
            if (tok.text.find('/') != std::string_view::npos) {
                tok.kind = TokenKind::Filename;
            } else if (std::string_view k = FindKeyword(tok.text); !k.empty()) {
                tok.kind = TokenKind::Keyword;
                tok.keyword = k;
            } else {
                tok.kind = TokenKind::Name;
            }
            return;
        }
    }
    tok.kind = TokenKind::Char;
    tok.text = std::string_view(text_).substr(pos_, 1);
    ++pos_;
}

bool Lexer::NextLiteral(double& value) {
    SkipSpaceAndComments();
    const char c = At(text_, pos_);
    if (c != '-' && c != '+') return ReadNumberValue(value);
    const Position sign = Save();
    ++pos_;
    atLineStart_ = false;
    SkipSpaceAndComments();
    if (ReadNumberValue(value)) {
        if (c == '-') value = -value;
        return true;
    }
    Restore(sign);
    return false;
}

bool Lexer::StartsExpression() {
    SkipSpaceAndComments();
    const char c = At(text_, pos_);
    if (c == '(') return true;
    if (c != '-' && c != '+') return AtNumber();
    const Position sign = Save();
    ++pos_;
    atLineStart_ = false;
    SkipSpaceAndComments();
    const bool number = AtNumber();
    Restore(sign);
    return number;
}

bool Lexer::ReadNumberValue(double& value) {
    const char c = At(text_, pos_);
    Token number;
    if (!(IsDigit(c) || c == '.') || !ReadNumber(number)) return false;
    atLineStart_ = false;
    value = number.number;
    return true;
}

namespace {

// Appends the run of decimal digits at `p` to `m` (m·10^k + the k digits' value, wrapping
// modulo 2^64) and returns the end of the run. Reads no byte at or past `limit` other than
// the NUL there, which ends the run. Eight bytes at a time while eight remain before
// `limit`: their values less '0' are digits exactly up to the first byte that is not one
// (a borrow only moves to later bytes), and the leading digits, moved to the high end as
// if led by zeros, are combined by pairs, fours and eights in three multiplications (on
// little-endian machines; elsewhere one byte at a time).
inline __attribute__((always_inline)) const char* ScanDigits(const char* p, const char* limit,
                                                             uint64_t& m) {
    static constexpr uint64_t kPowersOfTen[] = {1,      10,      100,      1000,     10000,
                                                100000, 1000000, 10000000, 100000000};
    constexpr uint64_t kOnes = 0x0101010101010101;
    while (std::endian::native == std::endian::little && limit - p >= 8) {
        uint64_t chunk;
        std::memcpy(&chunk, p, 8);
        const uint64_t values = chunk - '0' * kOnes;  // little-endian: byte i is p[i] - '0'
        // High bit of byte i: p[i] is no digit (its value is above 9), for bytes up to the
        // first such one.
        const uint64_t notDigit = ((values + 0x76 * kOnes) | values) & (0x80 * kOnes);
        const int count = notDigit == 0 ? 8 : std::countr_zero(notDigit) / 8;
        if (count > 0) {
            uint64_t v = values << (8 * (8 - count));  // the digits, led by 8 - count zeros
            v = v * 10 + (v >> 8);  // byte 2i (i < 4): the value of digits 2i, 2i + 1
            v = ((v & 0x000000FF000000FF) * (100 + (uint64_t{1000000} << 32)) +
                 ((v >> 16) & 0x000000FF000000FF) * (1 + (uint64_t{10000} << 32))) >>
                32;
            m = m * kPowersOfTen[count] + v;
        }
        p += count;
        if (count < 8) return p;
    }
    for (; IsDigit(*p); ++p) m = m * 10 + static_cast<uint64_t>(*p - '0');
    return p;
}

// The number at `s` (D+ | D+ . D* [E] | D* . D+ [E] | D+ E with E = [eE][+-]?D+): returns
// its length, 0 when none starts there. The text must end with a NUL at `limit` (which ends
// any number).
// Reads its value on the way by Clinger's fast path: when the digits make an integer
// m <= 2^53 and the power of ten 10^e has |e| <= 22, both are exact doubles and one
// multiplication or division rounds m·10^e correctly, as from_chars does; `exact` says
// whether `value` was set so.
size_t ScanNumber(const char* s, const char* limit, double& value, bool& exact) {
    constexpr uint64_t kMaxExact = uint64_t{1} << 53;
    static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                              1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                              1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char* p = s;
    uint64_t m = 0;  // the digits (wrapping when more than 19, then unused)
    for (; IsDigit(*p); ++p) m = m * 10 + static_cast<uint64_t>(*p - '0');  // mostly one digit
    const long intDigits = p - s;
    long fracDigits = 0;
    if (*p == '.') {
        const char* q = ScanDigits(p + 1, limit, m);
        fracDigits = q - p - 1;
        p = q;
    }
    if (intDigits == 0 && fracDigits == 0) return 0;
    long exponent = -fracDigits;
    if (*p == 'e' || *p == 'E') {
        const char* q = p + 1;
        const bool negative = *q == '-';
        if (*q == '+' || *q == '-') ++q;
        if (IsDigit(*q)) {
            long e = 0;
            for (; IsDigit(*q); ++q)
                if (e < 100000) e = e * 10 + (*q - '0');
            exponent += negative ? -e : e;
            p = q;
        }
    }
    exact = intDigits + fracDigits <= 19 && m <= kMaxExact && (m == 0 || (exponent >= -22 && exponent <= 22));
    if (exact) {
        const double mantissa = static_cast<double>(m);
        value = m == 0         ? 0
                : exponent < 0 ? mantissa / kPowersOfTen[-exponent]
                               : mantissa * kPowersOfTen[exponent];
    }
    return static_cast<size_t>(p - s);
}

}  // namespace

bool Lexer::AtNumber() const {
    // ScanNumber's grammar: a digit, or a point and a digit.
    const char c = At(text_, pos_);
    return IsDigit(c) || (c == '.' && IsDigit(At(text_, pos_ + 1)));
}

bool Lexer::ReadNumber(Token& tok) {
    const char* begin = text_.c_str() + pos_;
    bool exact = false;
    const size_t n = ScanNumber(begin, text_.c_str() + text_.size(), tok.number, exact);
    if (n == 0) return false;
    const char* end = begin + n;
    tok.kind = TokenKind::Number;
    tok.text = std::string_view(begin, n);
    pos_ += n;
    if (exact) return true;
    // from_chars and strtod both round correctly; strtod settles what from_chars leaves
    // (out of range: infinity, zero or a subnormal, as before).
    const std::string spelling(tok.text);
    if (auto [stop, error] = std::from_chars(begin, end, tok.number); error != std::errc() || stop != end)
        tok.number = std::strtod(spelling.c_str(), nullptr);
    if (!std::isfinite(tok.number)) Fail("Number out of range: %s", spelling);
    return true;
}

TokenStream::TokenStream(std::string text, std::string fileName, int firstLine)
    : lexer_(std::move(text), std::move(fileName), firstLine), ring_(kInitialRing) {}

void TokenStream::Push() {
    if (count_ == ring_.size()) {
        std::vector<Token> grown(2 * ring_.size());
        for (size_t i = 0; i < count_; ++i) grown[i] = std::move(ring_[(head_ + i) & (ring_.size() - 1)]);
        ring_ = std::move(grown);
        head_ = 0;
    }
    lexer_.Next(ring_[(head_ + count_) & (ring_.size() - 1)]);
    ++count_;
}

}  // namespace rs
