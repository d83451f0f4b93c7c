// rayshade-farm-helper: the two steps of the render farm (rayshade-farm) that need the
// renderer's own code.
//
//   rayshade-farm-helper plan RAYSHADE-ARGS...
//       Reads the command line and the scene exactly as rayshade does and prints, as one
//       JSON object on standard output, what the farm splits: the screen size, the rendered
//       window, the frames, the output file, the alpha flag and the scene file. Errors
//       (usage, scene syntax, a window outside the screen) are reported as rayshade reports
//       them, once, with exit status 1 or 2.
//
//   rayshade-farm-helper merge OUT WIDTH HEIGHT THREADS (X Y TILE)...
//       Pastes the tiles (PNG or mtv files, all with the same channels) at their positions
//       into one WIDTH x HEIGHT image and writes it to OUT through a temporary file renamed
//       over OUT when complete. The tiles must cover the image exactly once; otherwise, or
//       when a tile cannot be read, nothing is written and the status is 1.
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "libcommon/error.h"
#include "libimage/image.h"
#include "libshade/command.h"
#include "libshade/parser.h"
#include "rayshade/cli.h"
#include "rayshade/renderer.h"

namespace {

std::atomic<bool> gQuiet{false};

std::string JsonString(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
            out += escaped;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out + "\"";
}

int Plan(const std::vector<std::string>& args) {
    rs::CommandLine cl;
    std::string error;
    if (!rs::ParseCommandLine(args, cl, error)) rs::Report(rs::Severity::Abort, {}, "%s", error.c_str());
    gQuiet = cl.options.quiet;  // -q: warnings are dropped, as rayshade drops them
    rs::ParseInput input;
    input.path = cl.inputFile;
    input.useCpp = cl.useCpp;
    input.cppArgs = cl.cppArgs;
    rs::Scene scene = rs::ParseScene(input, cl.options);
    if (!cl.implicit.Empty() && rs::ApplyImplicitOverrides(*scene.world, cl.implicit, error) < 0)
        rs::Report(rs::Severity::Abort, {}, "%s", error.c_str());
    const rs::RenderOptions& o = scene.options;
    if (o.frames < 1) rs::Report(rs::Severity::Abort, {}, "the number of frames must be at least 1");
    const rs::RenderWindow w = rs::ComputeWindow(o);
    std::printf("{\"xres\": %d, \"yres\": %d, \"window\": [%d, %d, %d, %d], \"startframe\": %d, "
                "\"frames\": %d, \"output\": %s, \"alpha\": %s, \"resume\": %s, \"scene\": %s}\n",
                o.xres, o.yres, w.minX, w.maxX, w.minY, w.maxY, o.startFrame, o.frames,
                JsonString(o.outFile).c_str(), cl.alpha ? "true" : "false", cl.resume ? "true" : "false", JsonString(cl.inputFile).c_str());
    return 0;
}

struct Placed {
    int x, y;
    rs::Image image;
};

int Merge(const std::vector<std::string>& args) {
    if (args.size() < 4 || (args.size() - 4) % 3 != 0)
        rs::Report(rs::Severity::Abort, {}, "merge: usage: merge OUT WIDTH HEIGHT THREADS (X Y TILE)...");
    const std::string& out = args[0];
    const int width = std::atoi(args[1].c_str()), height = std::atoi(args[2].c_str());
    const int threads = std::max(1, std::atoi(args[3].c_str()));
    if (width < 1 || height < 1) rs::Report(rs::Severity::Abort, {}, "merge: bad image size %s x %s", args[1].c_str(), args[2].c_str());
    std::vector<Placed> tiles;
    long area = 0;
    for (size_t i = 4; i < args.size(); i += 3) {
        std::string error;
        std::optional<rs::Image> image = rs::ReadImage(args[i + 2], error);
        if (!image) rs::Report(rs::Severity::Abort, {}, "merge: %s", error.c_str());
        Placed p{std::atoi(args[i].c_str()), std::atoi(args[i + 1].c_str()), std::move(*image)};
        if (p.x < 0 || p.y < 0 || p.x + p.image.width > width || p.y + p.image.height > height)
            rs::Report(rs::Severity::Abort, {}, "merge: tile '%s' (%dx%d at %d,%d) lies outside the %dx%d image",
                       args[i + 2].c_str(), p.image.width, p.image.height, p.x, p.y, width, height);
        if (!tiles.empty() && p.image.channels != tiles.front().image.channels)
            rs::Report(rs::Severity::Abort, {}, "merge: tile '%s' has %d channels, the first tile %d",
                       args[i + 2].c_str(), p.image.channels, tiles.front().image.channels);
        for (const Placed& q : tiles) {
            const bool apart = p.x + p.image.width <= q.x || q.x + q.image.width <= p.x ||
                               p.y + p.image.height <= q.y || q.y + q.image.height <= p.y;
            if (!apart) rs::Report(rs::Severity::Abort, {}, "merge: tile '%s' overlaps another tile", args[i + 2].c_str());
        }
        area += static_cast<long>(p.image.width) * p.image.height;
        tiles.push_back(std::move(p));
    }
    if (area != static_cast<long>(width) * height)
        rs::Report(rs::Severity::Abort, {}, "merge: the tiles cover %ld of the image's %ld pixels", area,
                   static_cast<long>(width) * height);
    rs::Image image;
    image.width = width;
    image.height = height;
    image.channels = tiles.front().image.channels;
    image.pixels.resize(static_cast<size_t>(width) * height * image.channels);
    for (const Placed& p : tiles) {
        const size_t rowBytes = static_cast<size_t>(p.image.width) * image.channels;
        for (int y = 0; y < p.image.height; ++y)
            std::copy(p.image.Row(y), p.image.Row(y) + rowBytes, image.Row(p.y + y) + static_cast<size_t>(p.x) * image.channels);
    }
    std::string error;
    if (!rs::WriteImage(out, image, error, threads)) rs::Report(rs::Severity::Abort, {}, "merge: %s", error.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return rs::RunCommand("rayshade-farm", gQuiet, [&] {
        std::vector<std::string> args(argv + 1, argv + argc);
        const std::string mode = args.empty() ? "" : args.front();
        if (!args.empty()) args.erase(args.begin());
        if (mode == "plan") return Plan(args);
        if (mode == "merge") return Merge(args);
        rs::Report(rs::Severity::Abort, {}, "usage: rayshade-farm-helper plan RAYSHADE-ARGS... | merge OUT WIDTH HEIGHT THREADS (X Y TILE)...");
        return 1;
    });
}
