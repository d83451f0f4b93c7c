// `rayshade -h` against docs/options.md: the same groups in the same order, the same
// options (as the tables write them, e.g. "-R x y") in each, and every option letter the
// parser accepts listed, so the help and the reference cannot drift apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "rayshade/cli.h"

namespace rs {
namespace {

using Groups = std::vector<std::pair<std::string, std::vector<std::string>>>;

// The "### Title" subsections of "## The options" holding a table, and the first cell of
// each table row ("| `-R x y` | ..."), with markdown's "\|" unescaped.
Groups DocumentedGroups() {
    std::ifstream in(RAYSHADE_SOURCE_DIR "/docs/options.md");
    EXPECT_TRUE(in) << "cannot read docs/options.md";
    Groups groups;
    bool inOptions = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("## ", 0) == 0) inOptions = line == "## The options";
        if (!inOptions) continue;
        if (line.rfind("### ", 0) == 0) groups.push_back({line.substr(4), {}});
        if (line.rfind("| `-", 0) == 0 && !groups.empty()) {
            const size_t end = line.find('`', 3);
            std::string option = line.substr(3, end - 3);
            for (size_t at; (at = option.find("\\|")) != std::string::npos;) option.erase(at, 1);
            groups.back().second.push_back(option);
        }
    }
    // Subsections without a table (the details after the tables) are not groups.
    std::erase_if(groups, [](const auto& group) { return group.second.empty(); });
    return groups;
}

// The help's group lines ("Title:" or "Title (remark):") and option lines ("  -R x y  ...":
// the synopsis ends at two spaces).
Groups HelpGroups() {
    std::istringstream in(UsageText());
    Groups groups;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("usage:", 0) == 0 || line.empty()) continue;
        if (line[0] != ' ') {
            EXPECT_EQ(line.back(), ':') << line;
            groups.push_back({line.substr(0, std::min(line.find(" ("), line.size() - 1)), {}});
        } else if (line.rfind("  -", 0) == 0 && !groups.empty()) {
            groups.back().second.push_back(line.substr(2, line.find("  ", 2) - 2));
        }
    }
    return groups;
}

TEST(Help, ListsTheDocumentedGroupsAndOptionsInOrder) {
    const Groups documented = DocumentedGroups(), help = HelpGroups();
    ASSERT_FALSE(documented.empty());
    ASSERT_EQ(help.size(), documented.size());
    for (size_t g = 0; g < help.size(); ++g) {
        EXPECT_EQ(help[g].first, documented[g].first);
        EXPECT_EQ(help[g].second, documented[g].second) << "group " << documented[g].first;
    }
}

TEST(Help, ListsEveryOptionTheParserAccepts) {
    std::set<char> listed;
    for (const auto& group : HelpGroups())
        for (const std::string& option : group.second) listed.insert(option[1]);
    std::set<char> accepted;
    for (char c = 'A'; c <= 'z'; ++c) {
        if (!std::isalpha(static_cast<unsigned char>(c))) continue;
        CommandLine cl;
        std::string error;
        // Options that need arguments fail for want of one, unknown ones as unknown.
        if (ParseCommandLine({std::string("-") + c}, cl, error) || error.rfind("unknown option", 0) != 0)
            accepted.insert(c);
    }
    EXPECT_EQ(listed, accepted);
}

TEST(Help, ArgumentCountsComeFromTheTable) {
    EXPECT_EQ(OptionArgumentCount('R'), 2);
    EXPECT_EQ(OptionArgumentCount('W'), 4);
    EXPECT_EQ(OptionArgumentCount('n'), 0);
    EXPECT_EQ(OptionArgumentCount('H'), 1);
    EXPECT_EQ(OptionArgumentCount('Z'), -1);
}

}  // namespace
}  // namespace rs
