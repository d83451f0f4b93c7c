// rayshade: renders a Rayshade 4.0 scene file to PNG (or the original's mtv format).
#include <sys/resource.h>
#include <signal.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "libcommon/error.h"
#include "libcommon/limits.h"
#include "libcommon/parallel_build.h"
#include "libcommon/stats.h"
#include "libimage/image.h"
#include "liblight/directional_light.h"
#include "libshade/command.h"
#include "libshade/expression.h"
#include "libshade/parser.h"
#include "rayshade/checkpoint.h"
#include "rayshade/cli.h"
#include "rayshade/renderer.h"
#include "rayshade/report.h"

namespace {

using rs::Severity;

std::atomic<bool> gQuiet{false};
std::FILE* gStats = stderr;
// The scene once the last frame is written, left to the process's end (see Run). A global
// root (volatile, so the store is kept), through which leak checkers find all it holds.
const rs::Scene* volatile gSceneLeftToExit = nullptr;

// "4.2s", "12s", "3m05s", "1h02m": a duration for the progress lines.
std::string Duration(double seconds) {
    const long s = std::lround(std::max(0.0, seconds));
    char text[32];
    if (seconds < 9.95)
        std::snprintf(text, sizeof text, "%.1fs", std::max(0.0, seconds));
    else if (s < 60)
        std::snprintf(text, sizeof text, "%lds", s);
    else if (s < 3600)
        std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, s / 60 % 60);
    return text;
}

// Progress on stderr: a live bar on a terminal, a plain line every 10% otherwise, with the
// time left extrapolated from the time so far (the renderer reports a fraction of the
// estimated work, which grows roughly in proportion to time: rayshade/progress_estimate.h).
class Progress {
  public:
    Progress(bool quiet, int frame)
        : quiet_(quiet), tty_(isatty(STDERR_FILENO)), frame_(frame),
          start_(std::chrono::steady_clock::now()) {}
    void operator()(long done, long total) {
        if (quiet_ || total <= 0) return;
        const bool finished = done >= total;
        const int percent = static_cast<int>(100 * done / total);
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        const double fraction = static_cast<double>(done) / static_cast<double>(total);
        // No estimate from the first percent or the first half second: too little to go on.
        const bool estimate = fraction >= 0.01 && elapsed >= 0.5;
        const double left = estimate ? elapsed * (1 - fraction) / fraction : 0;
        if (tty_) {
            // Redrawn at each percent, and each second for the time left.
            if (percent == last_ && !finished && elapsed < lastDraw_ + 1) return;
            last_ = percent;
            lastDraw_ = elapsed;
            const int bar = percent / 4;
            const std::string tail = finished ? "in " + Duration(elapsed)
                                     : estimate ? Duration(left) + " left"
                                                : std::string();
            std::fprintf(stderr, "\rframe %d [%.*s%*s] %3d%% %-12s", frame_, bar,
                         "#########################", 25 - bar, "", percent, tail.c_str());
            if (finished) std::fputc('\n', stderr);
            std::fflush(stderr);
        } else if (percent / 10 != last_ / 10 || (finished && last_ != 100)) {
            last_ = percent;
            if (finished)
                std::fprintf(stderr, "frame %d: 100%% done in %s\n", frame_, Duration(elapsed).c_str());
            else if (estimate)
                std::fprintf(stderr, "frame %d: %d%% done, %s elapsed, about %s left\n", frame_, percent,
                             Duration(elapsed).c_str(), Duration(left).c_str());
            else
                std::fprintf(stderr, "frame %d: %d%% done\n", frame_, percent);
        }
    }

  private:
    bool quiet_, tty_;
    int frame_;
    std::chrono::steady_clock::time_point start_;
    int last_ = -1;
    double lastDraw_ = 0;
};

// The first SIGINT or SIGTERM asks the render to stop after the work items in progress
// and save its state; a second one ends the process at once, unsaved (one work item can
// take long, e.g. a pixel whose ray builds a large implicit octree).
void OnInterrupt(int signalNumber) {
    if (rs::StopRequested()) {
        signal(signalNumber, SIG_DFL);
        raise(signalNumber);
        return;
    }
    rs::RequestStop();
}

// Seconds between partial-state saves: RAYSHADE_CHECKPOINT_SECONDS, default 10.
double CheckpointSeconds() {
    const char* v = std::getenv("RAYSHADE_CHECKPOINT_SECONDS");
    double s = v ? std::atof(v) : 10;
    return s > 0 ? s : 10;
}

double CpuSeconds(bool user) {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    const timeval& tv = user ? ru.ru_utime : ru.ru_stime;
    return static_cast<double>(tv.tv_sec) + static_cast<double>(tv.tv_usec) * 1e-6;
}

// Name of frame `frame`'s image when several frames go to files: "<stem>_fNNN<ext>"
// (at least three digits), e.g. coin_f007.png.
std::string FrameFileName(const std::string& name, int frame) {
    std::string::size_type dot = name.find_last_of('.');
    std::string::size_type slash = name.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) dot = name.size();
    char digits[32];
    std::snprintf(digits, sizeof digits, "_f%03d", frame);
    return name.substr(0, dot) + digits + name.substr(dot);
}

// Resource limits (libcommon/limits.h, docs/robustness.md; raised with -L name=value); the
// scene file's keywords were checked with their locations, these checks catch the command
// line's values.
void ValidateOptions(rs::RenderOptions& o) {
    const rs::ResourceLimits& limits = rs::Limits();
    if (o.xres < 1 || o.yres < 1 || o.xres > limits.resolutionSide || o.yres > limits.resolutionSide ||
        static_cast<long>(o.xres) * o.yres > limits.resolutionPixels)
        rs::Report(Severity::Abort, {}, "resolution %dx%d is outside 1..%ld per side and %ld pixels",
                   o.xres, o.yres, limits.resolutionSide, limits.resolutionPixels);
    if (o.samples < 1 || o.samples > limits.samplesPerSide)
        rs::Report(Severity::Abort, {}, "sample count %d is outside 1..%ld", o.samples, limits.samplesPerSide);
    if (o.frames < 1) rs::Report(Severity::Abort, {}, "the number of frames must be at least 1");
    if (o.maxDepth > limits.rayDepth) {
        rs::Report(Severity::Warn, {}, "maximum ray depth %d exceeds the limit; using %ld", o.maxDepth,
                   limits.rayDepth);
        o.maxDepth = static_cast<int>(limits.rayDepth);
    }
}

int Run(int argc, char** argv) {
    rs::CommandLine cl;
    std::string error;
    if (!rs::ParseCommandLine(std::vector<std::string>(argv + 1, argv + argc), cl, error)) {
        std::fprintf(stderr, "rayshade: %s\n%s", error.c_str(), rs::UsageText());
        return 1;
    }
    if (cl.help) {
        std::fputs(rs::UsageText(), stderr);
        return 0;
    }
    gQuiet = cl.options.quiet;
    if (cl.options.statsFileSet) {
        gStats = std::fopen(cl.options.statsFile.c_str(), "w");
        if (!gStats) {
            gStats = stderr;
            rs::Report(Severity::Abort, {}, "cannot open statistics file '%s': %s",
                       cl.options.statsFile.c_str(), std::strerror(errno));
        }
    }
    if (cl.options.verbose) std::fprintf(gStats, "rayshade 4.0 (C++ re-creation), patch level 6\nReading input file...\n");

    auto start = std::chrono::steady_clock::now();
    // The render's threads, started once (the thread count is the command line's: scenes
    // cannot set it): the parser's runs of primitives and each frame's acceleration builds
    // run on them (RunBuildLoop), then each frame's pixels.
    const int threads = rs::Renderer::ThreadCount(cl.options);
    rs::WorkerPool workers(threads);
    const rs::ParallelLoop buildLoop = [&workers](long count, const std::function<void(long)>& body) {
        workers.Run(count, body, false);
    };
    rs::LazyRenderFingerprint fingerprint(std::vector<std::string>(argv + 1, argv + argc), cl.inputFile);
    rs::ParseInput input;
    input.path = cl.inputFile;
    input.useCpp = cl.useCpp;
    input.cppArgs = cl.cppArgs;
    rs::Scene scene = [&] {
        // (On one thread the parser's runs would only add their speculation's cost.)
        const rs::ParallelBuildScope parallelParse(threads > 1 ? &buildLoop : nullptr);
        return rs::ParseScene(input, cl.options);
    }();
    if (!cl.implicit.Empty() &&
        rs::ApplyImplicitOverrides(*scene.world, cl.implicit, error) < 0)
        rs::Report(Severity::Abort, {}, "%s", error.c_str());
    rs::RenderOptions& o = scene.options;
    gQuiet = o.quiet;
    if (o.eyeSepSet) scene.camera.eyeSep = cl.eyeSep;
    ValidateOptions(o);
    if (o.maxDepth < 0) o.maxDepth = 0;
    bool anyLight = false;
    for (const auto& l : scene.lights) anyLight = anyLight || l != nullptr;
    if (!anyLight)
        scene.lights.push_back(std::make_shared<rs::DirectionalLight>(rs::Color(1), rs::Vec3{1, -1, 1}));

    const bool toStdout = o.outFile.empty();
    if (toStdout && isatty(STDOUT_FILENO))
        rs::Report(Severity::Abort, {}, "no output file: give one with -O file.png (or redirect standard output for mtv)");

    // Continued rendering: the partial state names the frame in progress; earlier frames
    // were written before the interruption.
    const std::string partialPath = toStdout ? std::string() : rs::PartialStatePath(o.outFile);
    rs::FrameState resumed;
    int firstFrame = o.startFrame;
    if (cl.resume) {
        if (toStdout) rs::Report(Severity::Abort, {}, "-c needs an output file (-O or outfile)");
        if (!rs::LoadFrameState(partialPath, fingerprint.Get(), resumed, error))
            rs::Report(Severity::Abort, {}, "%s", error.c_str());
        if (resumed.frame < o.startFrame || resumed.frame >= o.startFrame + o.frames)
            rs::Report(Severity::Abort, {}, "partial state '%s' is for frame %d, outside this render",
                       partialPath.c_str(), resumed.frame);
        firstFrame = resumed.frame;
    }
    signal(SIGINT, OnInterrupt);
    signal(SIGTERM, OnInterrupt);
    const double checkpointSeconds = CheckpointSeconds();
    rs::CheckpointFn checkpoint;
    if (!toStdout) {
        checkpoint = [&](const rs::FrameState& state, bool) {
            std::string saveError;
            if (!rs::SaveFrameState(partialPath, fingerprint.Get(), state, saveError))
                rs::Report(Severity::Warn, {}, "%s", saveError.c_str());
        };
    }

    rs::RunTimes times;
    for (int f = firstFrame; f < o.startFrame + o.frames; ++f) {
        double frameTime = o.startTime + f * o.frameLength;
        rs::SetCurrentFrame(f);
        {
            const rs::ParallelBuildScope parallelBuilds(&buildLoop);
            scene.world->PrepareFrame(frameTime, o.shutter);
        }
        if (o.verbose) {
            if (f == firstFrame) {
                for (const auto& named : scene.namedObjects) {
                    named->PrepareFrame(frameTime, o.shutter);  // also those never instanced
                    rs::WriteObjectSummary(gStats, *named);
                }
                rs::WriteOptionsSummary(gStats, scene, threads);
            }
            rs::WriteObjectSummary(gStats, *scene.world);
        }
        if (f == firstFrame) {
            times.preprocessSeconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (!o.quiet) std::fprintf(gStats, "Preprocessing time:\t%.2f sec\nStarting trace.\n", times.preprocessSeconds);
        }
        auto renderStart = std::chrono::steady_clock::now();
        Progress progress(o.quiet, f);
        rs::Renderer renderer(scene, [&](long done, long total) { progress(done, total); }, workers);
        bool resuming = cl.resume && f == resumed.frame;
        rs::Image image;
        try {
            image = renderer.RenderFrame(f, frameTime, cl.alpha && !toStdout,
                                         resuming ? &resumed : nullptr, checkpoint, checkpointSeconds);
        } catch (const rs::RenderStopped&) {
            if (toStdout)
                rs::Report(Severity::Abort, {}, "interrupted");
            rs::Report(Severity::Abort, {}, "interrupted; the partial state is in '%s': run the same command with -c to continue",
                       partialPath.c_str());
        }
        times.renderWallSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - renderStart).count();
        if (toStdout) {
            std::vector<uint8_t> bytes = rs::EncodeMtv(image);
            if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0)
                rs::Report(Severity::Abort, {}, "cannot write the image to standard output");
        } else {
            std::string name = o.frames > 1 ? FrameFileName(o.outFile, f) : o.outFile;
            if (!rs::WriteImage(name, image, error, threads))
                rs::Report(Severity::Abort, {}, "%s", error.c_str());
            std::remove(partialPath.c_str());  // the frame is complete
        }
    }
    times.cpuUserSeconds = CpuSeconds(true);
    times.cpuSystemSeconds = CpuSeconds(false);
    if (o.verbose) rs::WriteStatistics(gStats, times);
    if (gStats != stderr) std::fclose(gStats);
    // The scene is left to the process's end, which returns its memory at once: freeing a
    // large scene's million nodes one by one took about 5% of tetra's setup time, on one
    // thread after the image was written.
    gSceneLeftToExit = new rs::Scene(std::move(scene));
    return 0;
}

}  // namespace

// The setup of a large scene allocates and frees buffers of megabytes in turn (the
// hierarchy's and grid's build arrays, the children's boxes). glibc's defaults hand each
// such buffer back to the kernel when it is freed (mmap above a threshold, trimming the
// heap's top), so the next one is fresh memory whose every page faults on first touch: on
// this kind of VM, about 3 µs a page. Keeping freed memory in the heap for reuse removes
// 9,000 of tetra's 48,000 faults and 0.03 s of its 0.40 s setup; the peak grows by 1%.
void KeepFreedMemoryForReuse() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest; bigger blocks are still mapped
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

int main(int argc, char** argv) {
    KeepFreedMemoryForReuse();
    return rs::RunCommand("rayshade", gQuiet, [&] { return Run(argc, argv); });
}
