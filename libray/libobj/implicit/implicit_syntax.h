// The `implicit ... end` block's sub-language (docs/implicit-reference.md is its reference):
// reads a block into a plain description, its skeletons, kernels, blend graph, contacts,
// propagations and settings, each statement with the place it was written, and nothing
// built yet (no field, no patch). implicit_block.h turns a description into the object's
// terms and options, reporting what is wrong at the statement at fault.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libcommon/large_buffer.h"
#include "libcommon/name_index.h"
#include "libobj/implicit/implicit_options.h"
#include "libobj/implicit/kernel.h"
#include "libobj/implicit/lg_octree.h"
#include "libobj/implicit/method_registry.h"

namespace rs {

// The usage line of the whole block, appended to its error messages: every statement.
extern const char kImplicitUsage[];

// One keyword of the block and what it introduces, for the reference page's test and the
// help: `syntax` is the statement's argument list as the reference writes it.
struct ImplicitKeyword {
    const char* word;
    const char* syntax;
};
// Every word the block's reader accepts in statement position or after a statement word
// (statements, skeleton kinds, per-skeleton modifiers, kernel and method names, `auto`).
const std::vector<ImplicitKeyword>& ImplicitBlockKeywords();
// Whether `word` begins a statement of the block (or ends it), so a parser can tell it from
// an optional surface name after `implicit`. These words are reserved inside the block: they
// cannot name a skeleton.
bool IsImplicitStatementWord(const std::string& word);

// Where a statement was written: an index into ImplicitDescription::files and a line,
// 8 bytes per skeleton where a SourceLocation would copy the file name.
struct StatementPlace {
    uint32_t file = 0;
    int32_t line = 0;
};

// The numbers of a block, indexed in reading order: a plain value each, and the expression
// of those that are time-varying (usually none).
class DeclaredNumbers {
  public:
    size_t Size() const { return values_.size(); }
    // Stores `v` at index Size() and returns that index.
    size_t Add(AnimatedValue v);
    bool IsAnimated(size_t index) const { return Animated(index) != nullptr; }
    double At(size_t index, double time) const {
        const AnimatedValue* v = Animated(index);
        return v ? v->At(time) : values_[index];
    }
    // An interval holding At(index, t) for every t in [t0, t1] (AnimatedValue::range;
    // infinite ends when the value cannot be bounded).
    std::pair<double, double> Range(size_t index, double t0, double t1) const;

  private:
    const AnimatedValue* Animated(size_t index) const;

    std::vector<double, LargeBufferAllocator<double>> values_;
    std::vector<AnimatedValue> animated_;
    // The slot in animated_ of each number up to the last animated one (−1: static): an
    // O(1) lookup for the per-ray evaluation of moving skeletons; empty in static scenes.
    std::vector<int32_t> slot_;
};

// A `field` statement: the kernel and the indices of its parameters in DeclaredNumbers
// (thickness, stiffness, radius; blob: strength, radius, paramCount 2).
struct KernelSpec {
    KernelKind kind = KernelKind::GascuelQuadratic;
    size_t params[3] = {};
    int paramCount = 3;
    StatementPlace place;  // line 0: the implicit default `field quadratic 1 1 2`
};

enum class SkeletonKind : uint8_t { Point, Segment, Polyline, Circle, Triangle, Box, Cylinder };

// One skeleton statement with its `weight` and `field` modifiers; its numbers (in syntax
// order), weight and kernel are indices into the description's tables.
struct SkeletonSpec {
    SkeletonKind kind = SkeletonKind::Point;
    size_t firstNumber = 0, numberCount = 0;
    size_t weight = 0;
    size_t kernel = 0;  // index in ImplicitDescription::kernels
    StatementPlace place;
};

// `blend a b c ...` (every pair of the list blends) or `blend hub : a b c ...` (each listed
// skeleton blends with the hub, not with each other).
struct BlendSpec {
    std::string hub;  // empty for the list form
    std::vector<std::string> names;
    StatementPlace place;
};

struct ContactSpec {
    std::string a, b;
    StatementPlace place;
};

struct PropagationSpec {
    std::string name;
    double width = 0, height = 0.5;
    StatementPlace place;
};

// The block's settings as written, the defaults (ImplicitOptions and the settings it holds:
// the one table of them) for those omitted; `auto` is kept as such, for the builder to
// resolve.
struct BlockSettings {
    double threshold = ImplicitOptions().threshold;
    bool autoTolerance = RootSearchSettings().autoTolerance;
    double tolerance = RootSearchSettings().tolerance;  // `tolerance Eps`, when not auto
    bool autoDepth = ImplicitOptions().autoDepth;
    int maxDepth = OctreeHeuristics().maxDepth;  // `octree MaxDepth`, when not auto
    double dRatio = OctreeHeuristics().dRatio;
    ImplicitMethod method = ImplicitOptions().method;
    double marchStep = ImplicitOptions().marchStep;  // <= 0: the method's default
    bool autoContacts = ImplicitOptions().autoContacts;  // `contact auto`
    StatementPlace methodPlace;  // the `method` statement (line 0: none)
};

struct ImplicitDescription {
    std::vector<std::string> files;  // the file names StatementPlace::file indexes
    BlockSettings settings;
    NameIndex names;  // names.Name(i) names skeletons[i]
    DeclaredNumbers numbers;
    std::vector<KernelSpec> kernels;  // kernels[0] is the implicit default
    std::vector<SkeletonSpec, LargeBufferAllocator<SkeletonSpec>> skeletons;
    std::vector<BlendSpec> blends;
    std::vector<ContactSpec> contacts;
    std::vector<PropagationSpec> propagations;

    SourceLocation Where(StatementPlace place) const {
        return {files.empty() ? std::string() : files[place.file], place.line};
    }
};

// Reads the statements after `implicit [surface]` up to and including `end`. Fails at the
// statement at fault (unknown word with a suggestion, bad arguments, a name used twice, a
// reserved word as a name); warns at the statement about statements without effect (a
// setting given twice, a `field` no skeleton follows).
ImplicitDescription ReadImplicitBlock(ArgReader& args);

}  // namespace rs
