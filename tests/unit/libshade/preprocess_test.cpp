#include "libshade/preprocess.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "libcommon/error.h"

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
    SourceText s = ReadSceneSource(f.path(), true, "-I. -DFOO=bar", {"BAZ"});  // -I: cpp
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
    // (-I keeps the built-in preprocessor out: this is about starting cpp.)
    SourceText s = ReadSceneSource(f.path(), true, "-I. -DX=1;touch${IFS}/tmp/rs_pwned", {});
    EXPECT_NE(s.text.find("1;touch${IFS}/tmp/rs_pwned"), std::string::npos) << s.text;
    EXPECT_NE(access("/tmp/rs_pwned", F_OK), 0);
}

TEST(Preprocess, FilesInTheBuiltinSubsetSkipCpp) {
    TempFile f("#define R 2\n/* c */\nsphere R 0 0 0\n");
    SourceText s = ReadSceneSource(f.path(), true, "-DUNUSED=1", {"ALSO"});
    EXPECT_EQ(s.text.find("# 1"), std::string::npos) << "cpp ran: " << s.text;
    EXPECT_NE(s.text.find("sphere  2  0 0 0"), std::string::npos) << s.text;
}

TEST(Preprocess, OtherCppArgumentsUseCpp) {
    TempFile f("sphere 1 0 0 0\n");
    SourceText s = ReadSceneSource(f.path(), true, "-I/tmp", {});
    EXPECT_NE(s.text.find("# 1 \"" + f.path() + "\""), std::string::npos) << s.text;
}

}  // namespace
}  // namespace rs
