// The implicit block's sub-language (implicit_syntax.h, implicit_block.h): every error and
// warning names the file and line of the statement at fault, through the real scene parser.
#include "libobj/implicit/implicit_syntax.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "libcommon/error.h"
#include "libobj/implicit/implicit_block.h"
#include "libshade/parser.h"
#include "token_reader.h"

namespace rs {
namespace {

// The diagnostics of parsing `text` as "t.ray", each as "file:line: message" without the
// usage line; `fatal` tells whether parsing failed.
struct Parsed {
    std::vector<std::string> messages;
    bool fatal = false;
};

Parsed ParseDiagnostics(const std::string& text) {
    Parsed out;
    ErrorSink previous = SetErrorSink([&out](const Diagnostic& d) {
        std::string message = d.message;
        if (size_t usage = message.find(" (usage: "); usage != std::string::npos) {
            message.resize(usage);
        }
        out.messages.push_back(d.location.file + ":" + std::to_string(d.location.line) + ": " +
                               message);
    });
    try {
        ParseSceneText(text, "t.ray", RenderOptions());
    } catch (const FatalError&) {
        out.fatal = true;
    }
    SetErrorSink(previous);
    return out;
}

// The one fatal message of a scene that must fail.
std::string FatalMessage(const std::string& text) {
    Parsed p = ParseDiagnostics(text);
    EXPECT_TRUE(p.fatal) << text;
    return p.messages.empty() ? std::string() : p.messages.back();
}

TEST(ImplicitSyntax, UnknownStatementFailsAtItsLineWithASuggestion) {
    EXPECT_EQ(FatalMessage("implicit\n  point a 0 0 0\n  point b 1 0 0\n  blnd a b\nend\n"),
              "t.ray:4: 'blnd' is not a statement of the implicit block (did you mean "
              "'blend'?)");
    EXPECT_EQ(FatalMessage("implicit\n  point a 0 0 0\n  sphere 1 0 0 0\nend\n"),
              "t.ray:3: 'sphere' is not a statement of the implicit block (point, segment, "
              "polyline, circle, triangle, box, cylinder, threshold, tolerance, octree, "
              "method, field, blend, contact, propagation, end)");
    EXPECT_EQ(FatalMessage("implicit\n  threshold 1\n  weight 2\n  point a 0 0 0\nend\n"),
              "t.ray:3: 'weight' must follow a skeleton's numbers (or its 'field')");
}

TEST(ImplicitSyntax, UnknownNamesFailAtTheStatementNamingThem) {
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n point b 1 0 0\n blend a c\nend\n"),
              "t.ray:4: blend names unknown skeleton 'c'");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n point b 1 0 0\n blend b : a c\nend\n"),
              "t.ray:4: blend names unknown skeleton 'c'");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n\n contact a c\nend\n"),
              "t.ray:4: contact names unknown skeleton 'c'");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n point b 3 0 0\n contact a b\n"
                           " propagation c 0.2\nend\n"),
              "t.ray:5: propagation names unknown skeleton 'c'");
}

TEST(ImplicitSyntax, ContactErrorsFailAtTheContact) {
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n point b 1 0 0\n blend a b\n"
                           " contact b a\nend\n"),
              "t.ray:5: skeletons 'b' and 'a' both blend (line 4) and are in contact");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n contact a a\nend\n"),
              "t.ray:3: contact needs two different skeletons, not 'a' twice");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n point b 1 0 0\n contact a b\n"
                           " propagation a -1\nend\n"),
              "t.ray:5: propagation width must be >= 0");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n point b 1 0 0\n contact a b\n"
                           " propagation a 1 2\nend\n"),
              "t.ray:5: propagation height must be in [0, 1]");
}

TEST(ImplicitSyntax, BadKernelFailsAtItsFieldStatement) {
    // k(R − e) = 4 · 1 > 3: the block-level field on line 2 is at fault, not the skeleton.
    EXPECT_EQ(FatalMessage("implicit\n field quadratic 1 4 2\n point arm 0 0 0\nend\n"),
              "t.ray:2: skeleton 'arm': stiffness·(radius − thickness) = 4 exceeds 3, so the "
              "field would turn negative outside the thickness; lower the stiffness to at "
              "most 3 or the radius to at most 1.75");
    // A skeleton's own field, on the line after its numbers.
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n point b 1 0 0\n"
                           "   field blob -1 2\nend\n"),
              "t.ray:4: skeleton 'b': blob field needs strength > 0 and radius > 0 (got -1, 2)");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n field\nend\n"),
              "t.ray:3: expected linear, quadratic or blob after 'field'");
}

TEST(ImplicitSyntax, BadSkeletonsAndSettingsFailAtTheirLine) {
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n circle c 0 0 0 0 0 0 1\nend\n"),
              "t.ray:3: skeleton 'c': circle needs a radius > 0 and a non-zero normal");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n cylinder c -1 0 0 0 0 0 1\nend\n"),
              "t.ray:3: skeleton 'c': cylinder radius must be >= 0");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n\n point a 1 0 0\nend\n"),
              "t.ray:4: skeleton name 'a' used twice");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n polyline p 1 0 0 0\nend\n"),
              "t.ray:3: polyline 'p' needs at least 2 points");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n threshold 0\nend\n"),
              "t.ray:3: implicit threshold must be > 0");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n tolerance -1\nend\n"),
              "t.ray:3: implicit tolerance must be > 0");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n octree 17\nend\n"),
              "t.ray:3: octree depth must be in [0, 16]");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n method march 0\nend\n"),
              "t.ray:3: the march step must be > 0");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n method fast\nend\n"),
              "t.ray:3: expected a method after 'method': patches, kb89, march, sphere, "
              "segment, polynomial, exact, auto");
    // polynomial serves blob points and segments only: the method statement is at fault.
    const std::string polynomial =
        FatalMessage("implicit\n point a 0 0 0\n\n method polynomial\nend\n");
    EXPECT_EQ(polynomial.rfind("t.ray:4: ", 0), 0u) << polynomial;
}

TEST(ImplicitSyntax, KeywordsOfTheSceneLanguageNameSkeletons) {
    // `body`, `sphere` and `light` are scene keywords; inside the block they are names.
    Parsed ok = ParseDiagnostics(
        "implicit\n point body 0 0 0\n point sphere 1.5 0 0\n point light 0 1.5 0\n"
        " blend body : sphere light\n contact sphere light\nend\n");
    EXPECT_FALSE(ok.fatal);
    EXPECT_TRUE(ok.messages.empty()) << ok.messages.front();
    // The block's own statement words are reserved.
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n point blend 1 0 0\nend\n"),
              "t.ray:3: expected a skeleton name, found 'blend', a reserved word of the "
              "implicit block");
    EXPECT_EQ(FatalMessage("implicit\n point a 0 0 0\n contact a end\n"),
              "t.ray:3: expected a second skeleton name, found 'end', a reserved word of the "
              "implicit block");
}

TEST(ImplicitSyntax, StatementsWithoutEffectWarnAtTheirLine) {
    Parsed twice = ParseDiagnostics("implicit\n threshold 1\n point a 0 0 0\n threshold 0.5\n"
                                    "end\n");
    EXPECT_FALSE(twice.fatal);
    ASSERT_EQ(twice.messages.size(), 1u);
    EXPECT_EQ(twice.messages[0],
              "t.ray:4: 'threshold' given again (first at line 2): this one applies");
    // After a skeleton's numbers a `field` is that skeleton's own; after another statement
    // it is the default of the skeletons that follow, here none.
    Parsed unused = ParseDiagnostics("implicit\n point a 0 0 0\n point b 1 0 0\n blend a b\n"
                                     " field blob 1 2\nend\n");
    ASSERT_EQ(unused.messages.size(), 1u);
    EXPECT_EQ(unused.messages[0],
              "t.ray:5: this 'field' applies to no skeleton (a block's 'field' is the kernel "
              "of the skeletons declared after it)");
    Parsed replaced = ParseDiagnostics("implicit\n field blob 1 2\n field blob 1 3\n"
                                       " point a 0 0 0\nend\n");
    ASSERT_EQ(replaced.messages.size(), 1u);
    EXPECT_EQ(replaced.messages[0].rfind("t.ray:2: this 'field' applies to no skeleton", 0),
              0u);
    Parsed lonely = ParseDiagnostics("implicit\n point a 0 0 0\n point b 3 0 0\n"
                                     " propagation a 0.2\nend\n");
    ASSERT_EQ(lonely.messages.size(), 1u);
    EXPECT_EQ(lonely.messages[0], "t.ray:4: propagation of 'a', which is in no contact");
    Parsed ignored = ParseDiagnostics("implicit\n method kb89\n point a 0 0 0\n"
                                      " point b 1 0 0\n blend a b\nend\n");
    ASSERT_EQ(ignored.messages.size(), 1u);
    EXPECT_EQ(ignored.messages[0],
              "t.ray:5: 'blend' is ignored with 'method kb89' (one field, everything blends)");
}

// The blend graph of a block, as term index pairs (read with the token reader).
std::vector<std::pair<int, int>> BlendPairs(const std::string& block) {
    TokenReader reader(block);
    BuiltImplicitBlock built = BuildImplicitBlock(ReadImplicitBlock(reader), reader);
    EXPECT_TRUE(reader.AtEnd());
    return built.options.blendPairs;
}

TEST(ImplicitSyntax, BlendListBlendsEveryPairAndHubFormEachWithTheHub) {
    const std::string skeletons = "point a 0 0 0 point b 1 0 0 point c 2 0 0 point d 3 0 0 ";
    using Pairs = std::vector<std::pair<int, int>>;
    EXPECT_EQ(BlendPairs(skeletons + "blend a b c end"), (Pairs{{0, 1}, {0, 2}, {1, 2}}));
    EXPECT_EQ(BlendPairs(skeletons + "blend b : a c d end"), (Pairs{{1, 0}, {1, 2}, {1, 3}}));
    EXPECT_EQ(BlendPairs(skeletons + "blend a : b blend c d end"), (Pairs{{0, 1}, {2, 3}}));
    TokenReader self(skeletons + "blend a : b a end");
    EXPECT_THROW(BuildImplicitBlock(ReadImplicitBlock(self), self), FatalError);
    TokenReader empty(skeletons + "blend a : end");
    EXPECT_THROW(ReadImplicitBlock(empty), FatalError);
}

TEST(ImplicitSyntax, DescriptionKeepsStatementsInOrderWithTheirLines) {
    TokenReader reader("threshold 0.5 tolerance 1e-6 octree 5 3 method march 0.1 "
                       "field blob 1 2 point a 0 0 0 weight 2 segment b 0 0 0 1 1 1 "
                       "field linear 0.5 1 1.5 contact a b propagation b 0.1 end");
    ImplicitDescription d = ReadImplicitBlock(reader);
    EXPECT_EQ(d.settings.threshold, 0.5);
    EXPECT_FALSE(d.settings.autoTolerance);
    EXPECT_EQ(d.settings.tolerance, 1e-6);
    EXPECT_FALSE(d.settings.autoDepth);
    EXPECT_EQ(d.settings.maxDepth, 5);
    EXPECT_EQ(d.settings.dRatio, 3);
    EXPECT_EQ(d.settings.method, ImplicitMethod::March);
    EXPECT_EQ(d.settings.marchStep, 0.1);
    ASSERT_EQ(d.skeletons.size(), 2u);
    EXPECT_EQ(d.names.Name(1), "b");
    EXPECT_EQ(d.skeletons[1].kind, SkeletonKind::Segment);
    EXPECT_EQ(d.numbers.At(d.skeletons[0].weight, 0), 2);
    EXPECT_EQ(d.kernels[d.skeletons[0].kernel].kind, KernelKind::Blob);
    EXPECT_EQ(d.kernels[d.skeletons[1].kernel].kind, KernelKind::GascuelLinear);
    ASSERT_EQ(d.contacts.size(), 1u);
    ASSERT_EQ(d.propagations.size(), 1u);
    EXPECT_EQ(d.propagations[0].height, 0.5);  // the default
}

// The reference page (docs/implicit-reference.md) cannot drift from the parser: every
// example block of it parses without a diagnostic, and every word the block's reader
// accepts appears in its code.
std::string ReferencePage() {
    std::ifstream in(RAYSHADE_REFERENCE_PAGE);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_FALSE(text.str().empty()) << RAYSHADE_REFERENCE_PAGE;
    return text.str();
}

// The ```ray blocks of a Markdown page.
std::vector<std::string> RayBlocks(const std::string& page) {
    std::vector<std::string> blocks;
    std::istringstream lines(page);
    std::string line, block;
    bool inside = false;
    while (std::getline(lines, line)) {
        if (!inside && line == "```ray") {
            inside = true;
            block.clear();
        } else if (inside && line == "```") {
            inside = false;
            blocks.push_back(block);
        } else if (inside) {
            block += line + "\n";
        }
    }
    return blocks;
}

// The words of the page's code: inline `spans`, fenced blocks and indented lines, split at
// white space and at the brackets and bars of syntax summaries.
std::set<std::string> CodeWords(const std::string& page) {
    std::string code;
    std::istringstream lines(page);
    std::string line;
    bool fenced = false;
    while (std::getline(lines, line)) {
        if (line.rfind("```", 0) == 0) {
            fenced = !fenced;
            continue;
        }
        if (fenced || line.rfind("    ", 0) == 0) {
            code += line + "\n";
            continue;
        }
        for (size_t open = line.find('`'); open != std::string::npos;) {
            const size_t close = line.find('`', open + 1);
            if (close == std::string::npos) break;
            code += line.substr(open + 1, close - open - 1) + "\n";
            open = line.find('`', close + 1);
        }
    }
    for (char& c : code) {
        if (std::strchr("[]{}()|,", c)) c = ' ';
    }
    std::set<std::string> words;
    std::istringstream split(code);
    for (std::string w; split >> w;) words.insert(w);
    return words;
}

TEST(ImplicitReference, EveryExampleOfThePageParsesCleanly) {
    const std::vector<std::string> blocks = RayBlocks(ReferencePage());
    EXPECT_GE(blocks.size(), 12u);  // one per statement at least
    for (const std::string& block : blocks) {
        Parsed p = ParseDiagnostics(block);
        EXPECT_FALSE(p.fatal) << block;
        EXPECT_TRUE(p.messages.empty()) << block << p.messages.front();
    }
}

TEST(ImplicitReference, EveryKeywordOfTheParserIsDocumented) {
    const std::set<std::string> documented = CodeWords(ReferencePage());
    ASSERT_FALSE(ImplicitBlockKeywords().empty());
    for (const ImplicitKeyword& k : ImplicitBlockKeywords()) {
        EXPECT_TRUE(documented.count(k.word)) << "'" << k.word << "' (" << k.syntax
                                              << ") is accepted but not documented";
    }
    // The checker itself: a word absent from the page is reported.
    EXPECT_FALSE(documented.count("gaussian"));
}

}  // namespace
}  // namespace rs
