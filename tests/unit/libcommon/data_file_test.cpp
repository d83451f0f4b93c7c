#include "libcommon/data_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace rs {
namespace {

namespace fs = std::filesystem;

// A scratch tree: <root>/scenes/scene.ray and <root>/scenes/beside.dat, with the working
// directory moved to <root>/work for the test and restored after.
class DataFileTest : public ::testing::Test {
  protected:
    void SetUp() override {
        root_ = fs::temp_directory_path() / ("rs_data_file_" + std::to_string(getpid()));
        fs::create_directories(root_ / "scenes");
        fs::create_directories(root_ / "work");
        Touch(root_ / "scenes" / "scene.ray");
        Touch(root_ / "scenes" / "beside.dat");
        previous_ = fs::current_path();
        fs::current_path(root_ / "work");
    }
    void TearDown() override {
        fs::current_path(previous_);
        fs::remove_all(root_);
    }
    static void Touch(const fs::path& p) { std::ofstream(p) << "x"; }
    std::string Scene() const { return (root_ / "scenes" / "scene.ray").string(); }

    fs::path root_, previous_;
};

TEST_F(DataFileTest, FoundBesideTheSceneWhenNotInTheWorkingDirectory) {
    EXPECT_EQ(ResolveDataFile("beside.dat", Scene()), (root_ / "scenes" / "beside.dat").string());
}

TEST_F(DataFileTest, TheWorkingDirectoryComesFirst) {
    Touch(root_ / "work" / "beside.dat");
    EXPECT_EQ(ResolveDataFile("beside.dat", Scene()), "beside.dat");
}

TEST_F(DataFileTest, RelativeSceneDirectoryAndSubdirectories) {
    fs::create_directories(root_ / "scenes" / "maps");
    Touch(root_ / "scenes" / "maps" / "a.map");
    EXPECT_EQ(ResolveDataFile("maps/a.map", "../scenes/scene.ray"), "../scenes/maps/a.map");
}

TEST_F(DataFileTest, NotFoundAnywhereKeepsTheNameAsWritten) {
    EXPECT_EQ(ResolveDataFile("missing.dat", Scene()), "missing.dat");
    // A scene without a directory part lives in the working directory: nothing else to try.
    EXPECT_EQ(ResolveDataFile("beside.dat", "scene.ray"), "beside.dat");
    EXPECT_EQ(ResolveDataFile("beside.dat", ""), "beside.dat");  // standard input
}

TEST_F(DataFileTest, AbsoluteNamesAreNotResolved) {
    EXPECT_EQ(ResolveDataFile("/nonexistent/beside.dat", Scene()), "/nonexistent/beside.dat");
}

}  // namespace
}  // namespace rs
