#include "libshade/builtin_preprocessor.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "libcommon/error.h"
#include "libcommon/parallel_build.h"
#include "libshade/lexer.h"
#include "libshade/preprocess.h"

namespace rs {
namespace {

namespace fs = std::filesystem;

// The tokens the parser would read from `text`, with kinds, spellings and locations; the
// lexer's error message instead when it fails.
std::vector<std::string> Tokens(const std::string& text, const std::string& file) {
    std::vector<std::string> out;
    try {
        Lexer lexer(text, file);
        for (Token t = lexer.Next(); t.kind != TokenKind::End; t = lexer.Next())
            out.push_back(std::to_string(static_cast<int>(t.kind)) + " " + std::string(t.text) + " @" +
                          t.Location().file + ":" + std::to_string(t.Location().line));
    } catch (const FatalError& e) {
        out.push_back(std::string("error: ") + e.what());
    }
    return out;
}

std::string ReadFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A scratch directory for scene files and their includes.
class Scratch {
  public:
    Scratch() {
        char name[] = "/tmp/rs_builtin_cpp_XXXXXX";
        dir_ = mkdtemp(name);
    }
    ~Scratch() { fs::remove_all(dir_); }
    std::string Write(const std::string& name, const std::string& text) const {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }

  private:
    fs::path dir_;
};

std::vector<std::string> AsCppArguments(const std::vector<CommandLineMacro>& macros) {
    std::vector<std::string> defines;
    for (const CommandLineMacro& m : macros) defines.push_back(m.name + "=" + m.body);
    return defines;
}

// Expects the built-in preprocessor to accept the file and to give the lexer exactly
// what the system cpp's output gives it.
void ExpectSameAsCpp(const std::string& path, const std::vector<CommandLineMacro>& macros = {}) {
    const std::optional<std::string> builtin = PreprocessBuiltin(ReadFile(path), path, macros);
    ASSERT_TRUE(builtin.has_value()) << path << " fell back to cpp";
    // -I/ keeps ReadSceneSource from taking the built-in path: this is the real cpp.
    const std::string cpp = ReadSceneSource(path, true, "-I/", AsCppArguments(macros)).text;
    EXPECT_EQ(Tokens(*builtin, path), Tokens(cpp, path)) << path << "\n--- built-in:\n"
                                                         << *builtin << "\n--- cpp:\n" << cpp;
}

TEST(BuiltinPreprocessor, MatchesCppOnMacrosConditionalsAndIncludes) {
    Scratch dir;
    const char* texts[] = {
        "#define EXPAND(x)\tscale x x x\nsphere 1 0 0 0 EXPAND(0.7)\n",
        "#define F(a, b) translate a b 0\nF(1,\n  2) sphere\nnext 3\n",
        "#define A 1\n#define B A A\n#define G(x) B x\nG(A) G((1 + A)) G( (A,A) ) end\n",
        "#ifdef NOPE\nbad -tokens\n#ifdef X\n#else\n#endif\n#if whatever\n#elif\n#endif\n#else\n"
        "good\n#endif\n#ifndef NOPE\nyes\n#endif\n",
        "#define E() 5\nE() E ( ) x\n#undef E\nE\n",
        "/* a\n b */ x /* c */ y\n  # /* the null directive */\nz\n",
        "#define X 1\r\nX\r\n",
        "a\nb",
        "/* unix linux __FILE__ // \" ' */ a-b.c x/y 1e-5 .5 2unix\n",
        "#define LACUNARITY\t2.\n#define OCTAVES 6\ntexture fbm 0 1 .3 LACUNARITY OCTAVES -.2\n",
        "#define P /usr/u/img/x.rle\nimage P map planar\n(P)\n",
        "#define S(r) sphere r 0 0 0\n#define T S(1) S(2)\nT T\n",
        "#define F(x) scale x\nplain line\nF\n(2) F (\n3\n) after\nplain 2\n",
        // Plain texts (no directive, comment or quote), one ending without a newline, and
        // words cpp predefines inside pp-numbers (`1.linux`: only the full preprocessor
        // tells them from words).
        "polygon txt001\n-1 -0.5 2.55836e-17 1.e5 2unix x_1 a-b.c\r\n\tcone 0 0 0",
        "sphere s1 1 0 0 0\n1.linux 2._x\n",
    };
    int n = 0;
    for (const char* text : texts) ExpectSameAsCpp(dir.Write(std::to_string(n++) + ".ray", text));

    dir.Write("inc.ray", "sphere R 0 0 0\n#undef R\n#define R 3\n#include \"sub/inner.ray\"\n");
    dir.Write("sub/inner.ray", "");  // (directory created below)
    fs::create_directories(fs::path(dir.Write("probe", "")).parent_path() / "sub");
    dir.Write("sub/inner.ray", "inner R\n#include \"leaf.ray\"\n");
    dir.Write("sub/leaf.ray", "leaf line1\nleaf line2");
    ExpectSameAsCpp(dir.Write("main.ray", "#define R 2\n#include \"inc.ray\"\nafter R\n"));

    ExpectSameAsCpp(dir.Write("d.ray", "texture image IMAGEFILE map planar FLAG\n"),
                    {{"IMAGEFILE", "testtex.img"}, {"FLAG", "1"}});
    ExpectSameAsCpp(dir.Write("f.ray", "F(2) G\n"), {{"F(x)", "scale x x x"}, {"G", ""}});
}

TEST(BuiltinPreprocessor, MatchesCppOnEveryShippedScene) {
    // The shared scenes (ashtray with the IMAGEFILE its tests pass) and our examples.
    int scenes = 0;
    for (const char* dir : {RAYSHADE_SCENES_DIR, RAYSHADE_EXAMPLES_DIR})
        for (const auto& entry : fs::recursive_directory_iterator(dir)) {
            if (entry.path().extension() != ".ray" || entry.path().stem().extension() == ".def")
                continue;
            ++scenes;
            if (entry.path().filename() == "ashtray.ray")
                ExpectSameAsCpp(entry.path().string(), {{"IMAGEFILE", "testtex.img"}});
            ExpectSameAsCpp(entry.path().string());
        }
    EXPECT_GT(scenes, 15);
}

TEST(BuiltinPreprocessor, LeavesEverythingElseToCpp) {
    Scratch dir;
    const char* texts[] = {
        "#if 1\n#endif\n", "#define S(x) #x\n", "#define P(a, b) a ## b\n", "#define V(...) x\n",
        "#pragma once\n", "#line 5\n", "#error no\n", "a // c\n", "\"q\"\n", "a 'b\n",
        "x \\\n y\n", "unix\n", "__LINE__\n", "_X\n", "#define X 1\n#define X 2\n",
        "#define X 1\na-X\n", "#define X 1\nX.5\n", "#define X 1\nX/y\n", "#define F(x) x\nF\n",
        "#define F(x) x\nF(1, 2)\n", "#ifdef X\n", "#endif\n", "#else\n",
        "#ifdef X\n#else\n#else\n#endif\n", "#include \"missing.ray\"\n", "#include <stdio.h>\n",
        "#define F(x) a-x\nF(1)\n", "#define X X\nX\n", "a\fb\n", "/* x\n */ #define Y\n",
        "#define F(x) x\nF(1\n#define Z\n)\n", "#ifdef X junk\n#endif\n", "#define X(a, a) a\n",
        "#define X(a,) a\n", "#define X+1\n", "#foo\n", "#ifdef __GNUC__\n#endif\n",
        "#define D 1\n#define G(x) x\n#define H G\nH(D)\n"};
    for (const char* text : texts)
        EXPECT_FALSE(PreprocessBuiltin(text, dir.Write("t.ray", text), {}).has_value()) << text;
    EXPECT_FALSE(PreprocessBuiltin("a\n", "t.ray", {{"_RESERVED", "1"}}).has_value());
}

TEST(BuiltinPreprocessor, FindsWhatNeedsCppAtEveryOffsetOfALongNumberRun) {
    // Runs of numbers are scanned sixteen bytes at a time: a character or word that needs
    // cpp is found wherever it falls in such a run, at every offset from its start.
    const std::string numbers = "-0.992188 1 -1.5 0.25\n3 -4.125 7 8.5 ";
    std::string run;
    while (run.size() < 80) run += numbers;
    for (const std::string needsCpp : {"\\", "\"", "unix", "_X", "'"}) {
        for (size_t k = 0; k <= 64; ++k) {
            const std::string text = run.substr(0, k) + " " + needsCpp + " " + run.substr(k) + "\n";
            EXPECT_FALSE(PreprocessBuiltin(text, "t.ray", {}).has_value()) << needsCpp << " at " << k;
        }
    }
    for (size_t k = 0; k <= 64; ++k) {
        // A comment is seen too (and removed by the full built-in path)...
        const std::string commented = run.substr(0, k) + "/* c */" + run.substr(k) + "\n";
        const std::optional<std::string> stripped = PreprocessBuiltin(commented, "t.ray", {});
        ASSERT_TRUE(stripped.has_value()) << k;
        EXPECT_EQ(stripped->find("/*"), std::string::npos) << k;
        // ...and without any of these the text is plain and comes back as it is.
        const std::string plain = run.substr(0, k) + " sphere " + run.substr(k) + "\n";
        EXPECT_EQ(PreprocessBuiltin(plain, "t.ray", {}), std::optional<std::string>(plain)) << k;
    }
}

TEST(BuiltinPreprocessor, FindsWhatNeedsCppAcrossTheSpansOfALargeText) {
    // Texts of 4 MiB and more are looked at in spans of 1 MiB on the build's threads (here
    // handed out backwards): a character or a predefined word that needs cpp is found
    // wherever it falls, also across a span's edge, and a plain text stays plain.
    const std::string numbers = "-0.992188 1 -1.5 0.25\n3 -4.125 7 8.5 ";
    std::string big;
    while (big.size() < (size_t{5} << 20)) big += numbers;
    big += '\n';
    const ParallelLoop backwards = [](long count, const std::function<void(long)>& body) {
        for (long i = count - 1; i >= 0; --i) body(i);
    };
    const ParallelBuildScope scope(&backwards);
    EXPECT_TRUE(PreprocessBuiltin(big, "t.ray", {}) == std::optional<std::string>(big));  // (no 5 MB diff)
    for (const std::string needsCpp : {"\\", "unix"}) {
        for (const size_t edge : {size_t{1} << 20, size_t{3} << 20, big.size() - 6}) {
            for (size_t back = 0; back <= 4; ++back) {
                std::string text = big;
                // " unix " over the numbers: a word of its own.
                text.replace(edge - back - 1, needsCpp.size() + 2, " " + needsCpp + " ");
                EXPECT_FALSE(PreprocessBuiltin(text, "t.ray", {}).has_value())
                    << needsCpp << " at " << edge << " - " << back;
            }
        }
    }
}

TEST(BuiltinPreprocessor, RunawayExpansionGoesToCpp) {
    // Each level doubles: 2^40 tokens. Stopped by the work bound, not by running out of
    // memory.
    std::ostringstream text;
    for (int i = 0; i < 40; ++i) text << "#define M" << i + 1 << " M" << i << " M" << i << "\n";
    text << "#define M0 x\nM40\n";
    EXPECT_FALSE(PreprocessBuiltin(text.str(), "t.ray", {}).has_value());
}

TEST(BuiltinPreprocessor, UnterminatedCommentIsLeftForTheLexer) {
    const std::optional<std::string> out = PreprocessBuiltin("a\n/* b\n", "t.ray", {});
    ASSERT_TRUE(out.has_value());
    const std::vector<std::string> tokens = Tokens(*out, "t.ray");
    EXPECT_EQ(tokens.back(), "error: t.ray:2: Unterminated comment");
}

TEST(BuiltinPreprocessor, OurPredefinedNamesCoverThisCpp) {
    // Every macro this system's cpp predefines is reserved (leading '_') or listed.
    FILE* pipe = popen("cpp -dM < /dev/null", "r");
    ASSERT_NE(pipe, nullptr);
    std::string out;
    char buf[4096];
    for (size_t n; (n = fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
    ASSERT_EQ(pclose(pipe), 0);
    std::istringstream lines(out);
    int macros = 0;
    for (std::string directive, name, rest; lines >> directive >> name && std::getline(lines, rest);) {
        ASSERT_EQ(directive, "#define");
        name = name.substr(0, name.find('('));
        ++macros;
        bool known = name[0] == '_';
        for (std::string_view listed : kCppPredefinedNames) known = known || name == listed;
        EXPECT_TRUE(known) << name << " is predefined by cpp but not in kCppPredefinedNames";
    }
    EXPECT_GT(macros, 50);
}

}  // namespace
}  // namespace rs
