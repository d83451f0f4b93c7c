#include "libobj/implicit/implicit_syntax.h"

#include <algorithm>
#include <climits>
#include <limits>
#include <string_view>

#include "libcommon/error.h"
#include "libcommon/limits.h"

namespace rs {

const char kImplicitUsage[] =
    "implicit [surface] {threshold T | tolerance auto|Eps | octree auto|MaxDepth [Dratio] | "
    "method Name [Step] | field linear|quadratic e k R | field blob s R | "
    "point|segment|polyline|circle|triangle|box|cylinder Name numbers... [weight W] "
    "[field ...] | blend Name Name... | blend Hub : Name... | contact NameA NameB | "
    "propagation Name Width [Height]} end";

size_t DeclaredNumbers::Add(AnimatedValue v) {
    const size_t index = values_.size();
    values_.push_back(v.value);
    if (v.IsAnimated()) {
        slot_.resize(index + 1, -1);
        slot_[index] = static_cast<int32_t>(animated_.size());
        animated_.push_back(std::move(v));
    }
    return index;
}

const AnimatedValue* DeclaredNumbers::Animated(size_t index) const {
    if (index >= slot_.size() || slot_[index] < 0) return nullptr;
    return &animated_[slot_[index]];
}

std::pair<double, double> DeclaredNumbers::Range(size_t index, double t0, double t1) const {
    const AnimatedValue* v = Animated(index);
    if (!v) return {values_[index], values_[index]};
    if (!v->range) {
        const double inf = std::numeric_limits<double>::infinity();
        return {-inf, inf};
    }
    return v->range(t0, t1);
}

namespace {

struct SkeletonSyntax {
    SkeletonKind kind;
    const char* keyword;
    int arity;  // count of numbers; -1 for polyline, whose point count comes first
    const char* syntax;
};

constexpr SkeletonSyntax kSkeletonSyntax[] = {
    {SkeletonKind::Point, "point", 3, "point Name X Y Z"},
    {SkeletonKind::Segment, "segment", 6, "segment Name X1 Y1 Z1 X2 Y2 Z2"},
    {SkeletonKind::Polyline, "polyline", -1, "polyline Name N X1 Y1 Z1 ... XN YN ZN"},
    {SkeletonKind::Circle, "circle", 7, "circle Name Radius X Y Z Nx Ny Nz"},
    {SkeletonKind::Triangle, "triangle", 9, "triangle Name X1 Y1 Z1 X2 Y2 Z2 X3 Y3 Z3"},
    {SkeletonKind::Box, "box", 6, "box Name Xlo Ylo Zlo Xhi Yhi Zhi"},
    {SkeletonKind::Cylinder, "cylinder", 7, "cylinder Name Radius X1 Y1 Z1 X2 Y2 Z2"}};

struct KernelSyntax {
    KernelKind kind;
    const char* keyword;
    int paramCount;
    const char* syntax;
};

constexpr KernelSyntax kKernelSyntax[] = {
    {KernelKind::GascuelLinear, "linear", 3, "field linear e k R"},
    {KernelKind::GascuelQuadratic, "quadratic", 3, "field quadratic e k R"},
    {KernelKind::Blob, "blob", 2, "field blob s R"}};

// The other words the reader accepts after a statement word (the method names come from
// the method registry).
constexpr const char kWeight[] = "weight";
constexpr const char kAuto[] = "auto";
constexpr const char kHubSeparator[] = ":";
const ImplicitKeyword kModifierWords[] = {
    {kWeight, "after a skeleton's numbers: weight W"},
    {kAuto, "tolerance auto, octree auto"},
    {kHubSeparator, "blend Hub : Name [Name...]"},
};

class BlockReader;
using StatementRead = void (BlockReader::*)(const SourceLocation& where);

// A statement word, its argument list as the reference page writes it, and its reader
// (null for the skeleton kinds, read through kSkeletonSyntax, and for `end`).
struct StatementSyntax {
    const char* word;
    const char* syntax;
    StatementRead read;
};

// Reads one block into a description, statement by statement; each statement reader gets
// the location of its keyword.
class BlockReader {
  public:
    BlockReader(ArgReader& args, ImplicitDescription& d) : args_(args), d_(d) {}

    void ReadAll();

    void ReadThreshold(const SourceLocation& where);
    void ReadTolerance(const SourceLocation& where);
    void ReadOctree(const SourceLocation& where);
    void ReadMethod(const SourceLocation& where);
    void ReadField(const SourceLocation& where);
    void ReadBlend(const SourceLocation& where);
    void ReadContact(const SourceLocation& where);
    void ReadPropagation(const SourceLocation& where);

  private:
    StatementPlace Place(const SourceLocation& where);
    // Warns when setting `word` was already given (the last one applies).
    void NoteSetting(const char* word, const SourceLocation& where);
    KernelSpec ReadKernel(const SourceLocation& where);
    void ReadSkeleton(const SkeletonSyntax& syntax, const SourceLocation& where);
    int ReadNumberCount(const SkeletonSyntax& syntax, const std::string& name,
                        const SourceLocation& where);
    // A skeleton name: any word but the block's statement words (an error at `where`, the
    // statement's location).
    std::string ReadSkeletonName(const char* role, const SourceLocation& where);
    // Why the next token starts no statement (consuming it when it is a word).
    std::string UnknownStatement();
    void WarnUnusedField();

    ArgReader& args_;
    ImplicitDescription& d_;
    size_t defaultKernel_ = 0;
    SourceLocation defaultKernelWhere_;
    bool defaultKernelUsed_ = true;
    std::vector<std::pair<const char*, int>> settingLines_;  // setting word, its line
};

const StatementSyntax kStatements[] = {
    {"threshold", "threshold T", &BlockReader::ReadThreshold},
    {"tolerance", "tolerance auto|Eps", &BlockReader::ReadTolerance},
    {"octree", "octree auto|MaxDepth [Dratio]", &BlockReader::ReadOctree},
    {"method", "method Name [Step]", &BlockReader::ReadMethod},
    {"field", "field linear|quadratic e k R  |  field blob s R", &BlockReader::ReadField},
    {"blend", "blend Name Name [Name...]  |  blend Hub : Name [Name...]",
     &BlockReader::ReadBlend},
    {"contact", "contact NameA NameB  |  contact auto", &BlockReader::ReadContact},
    {"propagation", "propagation Name Width [Height]", &BlockReader::ReadPropagation},
    {"end", "end", nullptr},
};

// The edit distance between two words (for "did you mean").
size_t EditDistance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1,
                               diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

}  // namespace

const std::vector<ImplicitKeyword>& ImplicitBlockKeywords() {
    static const std::vector<ImplicitKeyword> words = [] {
        std::vector<ImplicitKeyword> out;
        for (const StatementSyntax& s : kStatements) out.push_back({s.word, s.syntax});
        for (const SkeletonSyntax& s : kSkeletonSyntax) out.push_back({s.keyword, s.syntax});
        for (const KernelSyntax& k : kKernelSyntax) out.push_back({k.keyword, k.syntax});
        for (const ImplicitKeyword& k : kModifierWords) out.push_back(k);
        for (const MethodEntry& m : MethodRegistry()) out.push_back({m.name, "method"});
        return out;
    }();
    return words;
}

bool IsImplicitStatementWord(const std::string& word) {
    for (const StatementSyntax& s : kStatements)
        if (word == s.word) return true;
    for (const SkeletonSyntax& s : kSkeletonSyntax)
        if (word == s.keyword) return true;
    return false;
}

namespace {

StatementPlace BlockReader::Place(const SourceLocation& where) {
    size_t index = d_.files.size();  // a block's statements are nearly always in one file
    while (index > 0 && d_.files[index - 1] != where.file) --index;
    if (index == 0) {
        d_.files.push_back(where.file);
        index = d_.files.size();
    }
    return {static_cast<uint32_t>(index - 1), where.line};
}

void BlockReader::NoteSetting(const char* word, const SourceLocation& where) {
    for (const auto& [w, line] : settingLines_) {
        if (std::string_view(w) == word) {
            args_.WarnAtLocation(
                where, StringPrintf("'%s' given again (first at line %d): this one applies",
                                    word, line));
            return;
        }
    }
    settingLines_.emplace_back(word, where.line);
}

void BlockReader::ReadThreshold(const SourceLocation& where) {
    NoteSetting("threshold", where);
    d_.settings.threshold = args_.ReadNumber();
    if (!(d_.settings.threshold > 0)) args_.FailAtLocation(where, "implicit threshold must be > 0");
}

void BlockReader::ReadTolerance(const SourceLocation& where) {
    NoteSetting("tolerance", where);
    d_.settings.autoTolerance = args_.Accept(kAuto);
    if (d_.settings.autoTolerance) return;
    d_.settings.tolerance = args_.ReadNumber();
    if (!(d_.settings.tolerance > 0)) args_.FailAtLocation(where, "implicit tolerance must be > 0");
}

void BlockReader::ReadOctree(const SourceLocation& where) {
    NoteSetting("octree", where);
    d_.settings.autoDepth = args_.Accept(kAuto);
    if (!d_.settings.autoDepth) {
        d_.settings.maxDepth = args_.ReadInt();
        if (d_.settings.maxDepth < 0 || d_.settings.maxDepth > 16) {
            args_.FailAtLocation(where, "octree depth must be in [0, 16]");
        }
    }
    if (args_.PeekNumber()) d_.settings.dRatio = args_.ReadNumber();
}

void BlockReader::ReadMethod(const SourceLocation& where) {
    NoteSetting("method", where);
    // Accept() rather than a name: method words such as `sphere` are keywords of the
    // scene language.
    const MethodEntry* chosen = nullptr;
    for (const MethodEntry& entry : MethodRegistry()) {
        if (args_.Accept(entry.name)) {
            chosen = &entry;
            break;
        }
    }
    if (!chosen) {
        args_.FailAtLocation(where, "expected a method after 'method': " + ImplicitMethodNames());
    }
    d_.settings.method = chosen->method;
    d_.settings.methodPlace = Place(where);
    if (d_.settings.method == ImplicitMethod::March && args_.PeekNumber()) {
        d_.settings.marchStep = args_.ReadNumber();
        if (!(d_.settings.marchStep > 0)) args_.FailAtLocation(where, "the march step must be > 0");
    }
}

KernelSpec BlockReader::ReadKernel(const SourceLocation& where) {
    KernelSpec k;
    k.place = Place(where);
    const KernelSyntax* syntax = nullptr;
    for (const KernelSyntax& candidate : kKernelSyntax) {
        if (args_.Accept(candidate.keyword)) {
            syntax = &candidate;
            break;
        }
    }
    if (!syntax) args_.FailAtLocation(where, "expected linear, quadratic or blob after 'field'");
    k.kind = syntax->kind;
    k.paramCount = syntax->paramCount;
    for (int i = 0; i < k.paramCount; ++i) {
        k.params[i] = d_.numbers.Add(args_.ReadAnimatedNumber());
    }
    return k;
}

// A block-level `field` is the kernel of the skeletons after it, until the next one.
void BlockReader::ReadField(const SourceLocation& where) {
    WarnUnusedField();
    d_.kernels.push_back(ReadKernel(where));
    defaultKernel_ = d_.kernels.size() - 1;
    defaultKernelWhere_ = where;
    defaultKernelUsed_ = false;
}

void BlockReader::WarnUnusedField() {
    if (defaultKernelUsed_) return;
    args_.WarnAtLocation(defaultKernelWhere_,
                 "this 'field' applies to no skeleton (a block's 'field' is the kernel of the "
                 "skeletons declared after it)");
}

std::string BlockReader::ReadSkeletonName(const char* role, const SourceLocation& where) {
    std::string name = args_.ReadWord();
    if (IsImplicitStatementWord(name)) {
        args_.FailAtLocation(where, StringPrintf("expected %s, found '%s', a reserved word of "
                                                "the implicit block",
                                                role, name.c_str()));
    }
    return name;
}

void BlockReader::ReadBlend(const SourceLocation& where) {
    BlendSpec blend;
    blend.place = Place(where);
    std::string first = ReadSkeletonName("a skeleton name", where);
    if (args_.Accept(kHubSeparator)) {
        blend.hub = std::move(first);
    } else {
        blend.names.push_back(std::move(first));
    }
    // An open-ended list: it stops at the next statement word (or a number, an error then).
    do {
        blend.names.push_back(ReadSkeletonName("a skeleton name", where));
    } while (args_.PeekWord() && !args_.Peek(kHubSeparator) &&
             std::none_of(std::begin(kStatements), std::end(kStatements),
                          [&](const StatementSyntax& s) { return args_.Peek(s.word); }) &&
             std::none_of(std::begin(kSkeletonSyntax), std::end(kSkeletonSyntax),
                          [&](const SkeletonSyntax& s) { return args_.Peek(s.keyword); }));
    d_.blends.push_back(std::move(blend));
}

void BlockReader::ReadContact(const SourceLocation& where) {
    if (args_.Accept("auto")) {
        d_.settings.autoContacts = true;
        return;
    }
    ContactSpec contact;
    contact.place = Place(where);
    contact.a = ReadSkeletonName("a skeleton name", where);
    contact.b = ReadSkeletonName("a second skeleton name", where);
    d_.contacts.push_back(std::move(contact));
}

void BlockReader::ReadPropagation(const SourceLocation& where) {
    PropagationSpec p;
    p.place = Place(where);
    p.name = ReadSkeletonName("a skeleton name", where);
    p.width = args_.ReadNumber();
    if (!(p.width >= 0)) args_.FailAtLocation(where, "propagation width must be >= 0");
    if (args_.PeekNumber()) {
        p.height = args_.ReadNumber();
        if (!(p.height >= 0 && p.height <= 1)) {
            args_.FailAtLocation(where, "propagation height must be in [0, 1]");
        }
    }
    d_.propagations.push_back(std::move(p));
}

int BlockReader::ReadNumberCount(const SkeletonSyntax& syntax, const std::string& name,
                                 const SourceLocation& where) {
    if (syntax.arity >= 0) return syntax.arity;
    const int points = args_.ReadInt();
    if (points < 2) args_.FailAtLocation(where, "polyline '" + name + "' needs at least 2 points");
    // Each point is three numbers of the input, so a count beyond what any input holds
    // only overflows 3·points (Limits().polylinePoints, raised with -L polylinePoints=N,
    // never beyond what 3·points in an int allows).
    const long maxPoints = std::min<long>(Limits().polylinePoints, INT_MAX / 3);
    if (points > maxPoints) {
        args_.FailAtLocation(where, StringPrintf("polyline '%s' has more than %ld points",
                                                 name.c_str(), maxPoints));
    }
    return 3 * points;
}

void BlockReader::ReadSkeleton(const SkeletonSyntax& syntax, const SourceLocation& where) {
    SkeletonSpec e;
    e.kind = syntax.kind;
    e.place = Place(where);
    if (const std::string name = ReadSkeletonName("a skeleton name", where);
        !d_.names.Insert(name)) {
        args_.FailAtLocation(where, "skeleton name '" + name + "' used twice");
    }
    const std::string& name = d_.names.Name(d_.skeletons.size());
    const int count = ReadNumberCount(syntax, name, where);
    e.firstNumber = d_.numbers.Size();
    e.numberCount = static_cast<size_t>(count);
    for (int i = 0; i < count; ++i) d_.numbers.Add(args_.ReadAnimatedNumber());
    e.weight = 0;  // the constant 1 (ReadAll stores it first)
    e.kernel = defaultKernel_;
    defaultKernelUsed_ = true;
    for (;;) {
        if (args_.Accept(kWeight)) {
            e.weight = d_.numbers.Add(args_.ReadAnimatedNumber());
        } else if (args_.Peek("field")) {
            const SourceLocation modifier = args_.NextLocation();  // only when there is one
            args_.Accept("field");
            d_.kernels.push_back(ReadKernel(modifier));
            e.kernel = d_.kernels.size() - 1;
        } else {
            break;
        }
    }
    d_.skeletons.push_back(std::move(e));
}

std::string BlockReader::UnknownStatement() {
    std::string list;
    for (const SkeletonSyntax& s : kSkeletonSyntax) list += std::string(s.keyword) + ", ";
    for (const StatementSyntax& s : kStatements) list += std::string(s.word) + ", ";
    list.resize(list.size() - 2);
    if (!args_.PeekWord()) return "expected a statement of the implicit block (" + list + ")";
    const std::string word = args_.ReadWord();
    if (word == kWeight) return "'weight' must follow a skeleton's numbers (or its 'field')";
    std::string nearest;
    size_t best = 3;  // suggest only words within two edits
    for (const ImplicitKeyword& k : ImplicitBlockKeywords()) {
        const size_t distance = EditDistance(word, k.word);
        if (distance < best && IsImplicitStatementWord(k.word)) {
            best = distance;
            nearest = k.word;
        }
    }
    return "'" + word + "' is not a statement of the implicit block" +
           (nearest.empty() ? " (" + list + ")" : " (did you mean '" + nearest + "'?)");
}

void BlockReader::ReadAll() {
    const size_t one = d_.numbers.Add({1, {}, {}});  // index 0: the default weight
    // `field quadratic 1 1 2` (m = k(R − e) = 1) until a `field` statement.
    d_.kernels.push_back({KernelKind::GascuelQuadratic, {one, one, d_.numbers.Add({2, {}, {}})},
                          3, {}});
    for (;;) {
        const SourceLocation where = args_.NextLocation();
        if (args_.Accept("end")) break;
        const StatementSyntax* statement = nullptr;
        for (const StatementSyntax& s : kStatements) {
            if (s.read && args_.Accept(s.word)) {
                statement = &s;
                break;
            }
        }
        if (statement) {
            (this->*statement->read)(where);
            continue;
        }
        const SkeletonSyntax* skeleton = nullptr;
        for (const SkeletonSyntax& s : kSkeletonSyntax) {
            if (args_.Accept(s.keyword)) {
                skeleton = &s;
                break;
            }
        }
        if (!skeleton) args_.FailAtLocation(where, UnknownStatement());
        ReadSkeleton(*skeleton, where);
    }
    WarnUnusedField();
}

}  // namespace

ImplicitDescription ReadImplicitBlock(ArgReader& args) {
    ImplicitDescription d;
    BlockReader(args, d).ReadAll();
    return d;
}

}  // namespace rs
