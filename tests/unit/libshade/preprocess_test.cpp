#include "libshade/preprocess.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "libcommon/error.h"
#include "libshade/lexer.h"

namespace rs {
namespace {

class TempFile {
  public:
    explicit TempFile(const std::string& text) {
        char name[] = "/tmp/rs_pre_XXXXXX";
        int fd = mkstemp(name);
        path_ = name;
        close(fd);
        std::ofstream(path_) << text;
    }
    ~TempFile() { std::remove(path_.c_str()); }
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

TEST(Preprocess, RawReadKeepsText) {
    TempFile f("#define X 1\nX\n");
    SourceText s = ReadSceneSource(f.path(), false, "", {});
    EXPECT_EQ(s.text, "#define X 1\nX\n");
    EXPECT_EQ(s.fileName, f.path());
}

TEST(Preprocess, CppExpandsMacrosAndEmitsLineMarkers) {
    TempFile f("#define EXPAND(x) scale x x x\n/* c */\nEXPAND(2)\n#ifdef FOO\nfoo FOO\n#endif\n");
    SourceText s = ReadSceneSource(f.path(), true, "-DFOO=bar", {"BAZ"});
    EXPECT_NE(s.text.find("scale 2 2 2"), std::string::npos) << s.text;
    EXPECT_NE(s.text.find("foo bar"), std::string::npos) << s.text;
    EXPECT_NE(s.text.find("# 1 \"" + f.path() + "\""), std::string::npos) << s.text;
    EXPECT_EQ(s.text.find("/* c */"), std::string::npos);
}

TEST(Preprocess, CppFailureCarriesItsMessage) {
    TempFile f("#include \"does-not-exist.ray\"\n");
    try {
        ReadSceneSource(f.path(), true, "", {});
        FAIL() << "no error";
    } catch (const FatalError& e) {
        std::string what = e.what();
        EXPECT_NE(what.find("The C preprocessor failed"), std::string::npos) << what;
        EXPECT_NE(what.find("does-not-exist.ray"), std::string::npos) << what;
    }
}

TEST(Preprocess, MissingFileIsAnError) {
    EXPECT_THROW(ReadSceneSource("/nonexistent/scene.ray", false, "", {}), FatalError);
    EXPECT_THROW(ReadSceneSource("/nonexistent/scene.ray", true, "", {}), FatalError);
}

TEST(Preprocess, ArgumentsAreNotInterpretedByAShell) {
    TempFile f("X\n");
    // With a shell this would run `touch`; as one argv word cpp merely defines a macro.
    SourceText s = ReadSceneSource(f.path(), true, "-DX=1;touch${IFS}/tmp/rs_pwned", {});
    EXPECT_NE(s.text.find("1;touch${IFS}/tmp/rs_pwned"), std::string::npos) << s.text;
    EXPECT_NE(access("/tmp/rs_pwned", F_OK), 0);
}

// The tokens of `text` with their kinds, spellings and locations, as the parser sees them.
std::vector<std::string> Tokens(const std::string& text, const std::string& file) {
    Lexer lexer(text, file);
    std::vector<std::string> out;
    for (Token t = lexer.Next(); t.kind != TokenKind::End; t = lexer.Next())
        out.push_back(std::to_string(static_cast<int>(t.kind)) + " " + t.text + " @" +
                      t.location.file + ":" + std::to_string(t.location.line));
    return out;
}

// The text cpp makes of the file at `path` (cpp's own output, forced by a harmless -D).
std::string ThroughCpp(const std::string& path) {
    return ReadSceneSource(path, true, "-DRS_FORCE_CPP", {}).text;
}

TEST(Preprocess, PassThroughIsRecognised) {
    EXPECT_TRUE(CppWouldOnlyStripComments("sphere 1 0 0 0 /* # not a directive */\n"));
    EXPECT_TRUE(CppWouldOnlyStripComments("eyep 0 -4 0\r\nlight 1 point 1e5 2 3\n"));
    EXPECT_TRUE(CppWouldOnlyStripComments("name a-b.c x.y /* unterminated"));
    EXPECT_TRUE(CppWouldOnlyStripComments("a # b\n"));  // '#' inside a line: no directive
    EXPECT_TRUE(CppWouldOnlyStripComments("linuxbox unix2 my_unix\n"));  // other identifiers
}

TEST(Preprocess, AnythingCppActsOnIsNotPassThrough) {
    using namespace std::string_literals;
    for (const std::string& text :
         {"#define X 1\n"s, "  #include \"f\"\n"s, "\t# 3 \"f\"\n"s, "/* c */ #if 0\n"s,
          "a\n/* x\n y */ #endif\n"s, "scale \\\n 2\n"s, "x // comment\n"s,
          "image \"f.png\"\n"s, "a 'b\n"s, "light 1 point linux 0 0\n"s, "unix\n"s,
          "__FILE__\n"s, "_X\n"s, "a-unix\n"s, "2linux\n"s, "a\fb\n"s, "nul\0x"s})
        EXPECT_FALSE(CppWouldOnlyStripComments(text)) << text;
}

TEST(Preprocess, OurPredefinedNamesCoverThisCpp) {
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

TEST(Preprocess, PassThroughFilesSkipCppAndLexAsCppOutput) {
    TempFile f("/* header\n comment */\nsphere 1 0 0 0\n\n  plane 0 0 1 0 0 -1 /* x */ end\n");
    SourceText direct = ReadSceneSource(f.path(), true, "", {});
    EXPECT_EQ(direct.text.find("# 1"), std::string::npos) << "cpp ran: " << direct.text;
    EXPECT_EQ(Tokens(direct.text, direct.fileName), Tokens(ThroughCpp(f.path()), f.path()));
}

TEST(Preprocess, ShippedScenesLexTheSameWithAndWithoutCpp) {
    // Every scene the fast path accepts must give the parser exactly what cpp would.
    std::vector<std::filesystem::path> scenes;
    for (const char* dir : {RAYSHADE_SCENES_DIR, RAYSHADE_EXAMPLES_DIR})
        for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
            if (entry.path().extension() == ".ray") scenes.push_back(entry.path());
    ASSERT_GT(scenes.size(), 10u);
    int passThrough = 0;
    for (const auto& scene : scenes) {
        std::ifstream in(scene);
        std::stringstream raw;
        raw << in.rdbuf();
        if (!CppWouldOnlyStripComments(raw.str())) continue;
        ++passThrough;
        EXPECT_EQ(Tokens(raw.str(), scene.string()), Tokens(ThroughCpp(scene.string()), scene.string()))
            << scene;
    }
    EXPECT_GT(passThrough, 5);
}

}  // namespace
}  // namespace rs
