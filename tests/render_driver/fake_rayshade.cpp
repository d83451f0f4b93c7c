// Stands in for rayshade when testing cmake/run_render_test.cmake. Called as
//     fake_rayshade -q [options] -O output.png input-image
// it "renders" by copying the input image to the output, after the options:
//     --expect-cwd DIR   fail unless the working directory is DIR
//     --expect ARG TEXT  fail unless ARG equals TEXT (checks arguments arrive intact)
//     --brighten N       add N to every channel value (clamped to 255)
//     --fail             exit with status 3 without writing anything
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "libimage/image.h"

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.size() < 3 || args[0] != "-q" || args[args.size() - 3] != "-O") {
        std::fprintf(stderr, "fake_rayshade: expected -q [options] -O output input\n");
        return 2;
    }
    int brighten = 0;
    for (size_t i = 1; i + 3 < args.size(); ++i) {
        if (args[i] == "--fail") return 3;
        if (args[i] == "--brighten") {
            brighten = std::stoi(args[++i]);
        } else if (args[i] == "--expect-cwd") {
            const auto cwd = std::filesystem::current_path();
            if (std::filesystem::weakly_canonical(args[++i]) != cwd) {
                std::fprintf(stderr, "fake_rayshade: working directory is %s\n", cwd.c_str());
                return 2;
            }
        } else if (args[i] == "--expect") {
            if (args[i + 1] != args[i + 2]) {
                std::fprintf(stderr, "fake_rayshade: \"%s\" is not \"%s\"\n",
                             args[i + 1].c_str(), args[i + 2].c_str());
                return 2;
            }
            i += 2;
        } else {
            std::fprintf(stderr, "fake_rayshade: unknown option %s\n", args[i].c_str());
            return 2;
        }
    }
    std::string error;
    auto image = rs::ReadImage(args.back(), error);
    if (!image) {
        std::fprintf(stderr, "fake_rayshade: %s\n", error.c_str());
        return 2;
    }
    for (auto& v : image->pixels) v = static_cast<uint8_t>(std::min(255, v + brighten));
    if (!rs::WriteImage(args[args.size() - 2], *image, error)) {
        std::fprintf(stderr, "fake_rayshade: %s\n", error.c_str());
        return 2;
    }
    return 0;
}
