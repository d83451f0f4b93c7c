#include "rayshade/cli.h"

#include <cerrno>
#include <cstdlib>

#include "libcommon/limits.h"

namespace rs {

namespace {

class ArgCursor {
  public:
    ArgCursor(const std::vector<std::string>& args, std::string& error) : args_(args), error_(error) {}

    bool Done() const { return next_ >= args_.size(); }
    const std::string& Take() { return args_[next_++]; }

    bool Word(const char* flag, std::string& out) {
        if (Done()) return Fail(std::string("option ") + flag + " needs an argument");
        out = Take();
        return true;
    }
    bool Real(const char* flag, double& out) {
        std::string w;
        if (!Word(flag, w)) return false;
        char* end = nullptr;
        errno = 0;
        out = std::strtod(w.c_str(), &end);
        if (w.empty() || *end != '\0' || errno == ERANGE)
            return Fail(std::string("option ") + flag + ": '" + w + "' is not a number");
        return true;
    }
    bool Int(const char* flag, int& out) {
        std::string w;
        if (!Word(flag, w)) return false;
        char* end = nullptr;
        errno = 0;
        long v = std::strtol(w.c_str(), &end, 10);
        if (w.empty() || *end != '\0' || errno == ERANGE || v < -1000000000L || v > 1000000000L)
            return Fail(std::string("option ") + flag + ": '" + w + "' is not an integer");
        out = static_cast<int>(v);
        return true;
    }
    bool Fail(const std::string& message) {
        error_ = message;
        return false;
    }

  private:
    const std::vector<std::string>& args_;
    std::string& error_;
    size_t next_ = 0;
};

// Reads the value of an implicit override option (-M, -I, -K, -J, -B, -H) into cl.implicit.
bool Implicit(ArgCursor& in, const char* flag, ImplicitOverrideKind kind, CommandLine& cl) {
    std::string value, error;
    if (!in.Word(flag, value)) return false;
    if (!ParseImplicitOverride(kind, value, cl.implicit, error)) {
        return in.Fail(std::string(flag) + ": " + error);
    }
    return true;
}

}  // namespace

const char* UsageText() {
    return "usage: rayshade [options] [file.ray]\n"
           "  -A frame      first frame to render        -N frames    number of frames\n"
           "  -a            toggle alpha channel (RGBA PNG output)\n"
           "  -C r g b      ray cutoff thresholds        -D depth     maximum ray depth\n"
           "  -E sep        eye separation               -l / -r      left / right stereo view\n"
           "  -F freq       report every freq lines      -f           flip triangle/polygon normals\n"
           "  -G gamma      output gamma                 -g           toggle gaussian filter\n"
           "  -h            this help                    -j           toggle jittered sampling\n"
           "  -n            toggle shadows off           -O file      output file (.png or .mtv)\n"
           "  -o            toggle transparent shadows   -P args      arguments for cpp\n"
           "  -p            preview (no shadows, depth 0, 1 sample)\n"
           "  -q            quiet                        -R x y       resolution\n"
           "  -S n          samples per side (1-16)      -s           toggle shadow caching\n"
           "  -T r g b      contrast thresholds          -t threads   worker threads (default: all cores)\n"
           "  -u            toggle the C preprocessor    -V file      verbose report to file\n"
           "  -v            verbose report               -W x0 x1 y0 y1  sub-window (pixels)\n"
           "  -X l r b t    crop window (fractions)\n"
           "  -L name=value raise a resource limit (docs/robustness.md): resolutionSide,\n"
           "                resolutionPixels, samplesPerSide, rayDepth, sceneBytes, gridVoxels,\n"
           "                gridEntries, polylinePoints, octreeBytes\n"
           "  Implicit objects (every one, whatever its scene says):\n"
           "  -M method     auto, patches, kb89, march, sphere, segment, polynomial, exact\n"
           "  -I eps        root tolerance               -K depth     octree maximum depth\n"
           "  -J dratio     Dratio (patches)             -B step      march step\n"
           "  -H name=on|off  octree heuristic or search test: range, patch, 1, 1bis, 3, 3bis,\n"
           "                4, 5, 0bis, t1, 2bis, t3\n";
}

bool ParseCommandLine(const std::vector<std::string>& args, CommandLine& cl, std::string& error) {
    ArgCursor in(args, error);
    RenderOptions& o = cl.options;
    while (!in.Done()) {
        const std::string arg = in.Take();
        if (arg.size() < 2 || arg[0] != '-') {
            if (!cl.inputFile.empty()) return in.Fail("more than one input file given");
            cl.inputFile = arg;
            continue;
        }
        if (arg.size() != 2) return in.Fail("unknown option '" + arg + "'");
        const char* flag = arg.c_str();
        switch (arg[1]) {
            case 'A': if (!in.Int(flag, o.startFrame)) return false; break;
            case 'B': if (!Implicit(in, flag, ImplicitOverrideKind::Step, cl)) return false; break;
            case 'a': cl.alpha = !cl.alpha; break;
            case 'C':
                if (!in.Real(flag, o.cutoff.r) || !in.Real(flag, o.cutoff.g) || !in.Real(flag, o.cutoff.b))
                    return false;
                o.cutoffSet = true;
                break;
            case 'c': cl.resume = true; break;
            case 'D':
                if (!in.Int(flag, o.maxDepth)) return false;
                o.maxDepthSet = true;
                break;
            case 'E':
                if (!in.Real(flag, cl.eyeSep)) return false;
                o.eyeSepSet = true;
                break;
            case 'e': break;  // exponential RLE output: no RLE writer, nothing to do
            case 'F':
                if (!in.Int(flag, o.reportFreq)) return false;
                if (o.reportFreq < 1) o.reportFreq = 1;
                o.reportFreqSet = true;
                break;
            case 'f': o.flipNormals = !o.flipNormals; break;
            case 'G': if (!in.Real(flag, o.gamma)) return false; break;
            case 'g': o.filter = o.filter == FilterKind::Box ? FilterKind::Gauss : FilterKind::Box; break;
            case 'H': if (!Implicit(in, flag, ImplicitOverrideKind::Switch, cl)) return false; break;
            case 'h': cl.help = true; break;
            case 'I': if (!Implicit(in, flag, ImplicitOverrideKind::Tolerance, cl)) return false; break;
            case 'J': if (!Implicit(in, flag, ImplicitOverrideKind::DRatio, cl)) return false; break;
            case 'K': if (!Implicit(in, flag, ImplicitOverrideKind::Depth, cl)) return false; break;
            case 'j':
                o.jitter = !o.jitter;
                o.jitterSet = true;
                break;
            case 'l': o.eyeSepSide = -1; break;
            case 'L': {
                std::string assignment;
                if (!in.Word(flag, assignment)) return false;
                std::string limitError;
                if (!SetLimit(assignment, limitError)) return in.Fail(limitError);
                break;
            }
            case 'r': o.eyeSepSide = 1; break;
            case 'M': if (!Implicit(in, flag, ImplicitOverrideKind::Method, cl)) return false; break;
            case 'm': break;  // sample map in the RLE alpha channel: no RLE writer
            case 'N':
                if (!in.Int(flag, o.frames)) return false;
                if (o.frames < 1) return in.Fail("-N: the number of frames must be at least 1");
                o.framesSet = true;
                break;
            case 'n': o.noShadows = !o.noShadows; break;
            case 'O':
                if (!in.Word(flag, o.outFile)) return false;
                o.outFileSet = true;
                break;
            case 'o': o.shadowTransparency = !o.shadowTransparency; break;
            case 'P': if (!in.Word(flag, cl.cppArgs)) return false; break;
            case 'p':
                o.noShadows = true;
                o.maxDepth = 0;
                o.samples = 1;
                o.jitter = true;
                o.maxDepthSet = o.samplesSet = o.jitterSet = true;
                break;
            case 'q': o.quiet = true; break;
            case 'R':
                if (!in.Int(flag, o.xres) || !in.Int(flag, o.yres)) return false;
                o.resolutionSet = true;
                break;
            case 'S':
                if (!in.Int(flag, o.samples)) return false;
                if (o.samples < 1) o.samples = 1;
                o.samplesSet = true;
                break;
            case 's': break;  // shadow caching changes only statistics; we do not cache
            case 'T':
                if (!in.Real(flag, o.contrast.r) || !in.Real(flag, o.contrast.g) ||
                    !in.Real(flag, o.contrast.b))
                    return false;
                o.contrastSet = true;
                break;
            case 't':
                if (!in.Int(flag, o.threads)) return false;
                if (o.threads < 1) return in.Fail("-t: the number of threads must be at least 1");
                break;
            case 'u': cl.useCpp = !cl.useCpp; break;
            case 'V':
                if (!in.Word(flag, o.statsFile)) return false;
                if (!o.statsFile.empty() && o.statsFile[0] == '-')
                    return in.Fail("-V needs a file name, not '" + o.statsFile + "'");
                o.statsFileSet = true;
                o.verbose = true;
                break;
            case 'v': o.verbose = true; break;
            case 'W':
                for (int i = 0; i < 4; ++i)
                    if (!in.Int(flag, o.window[i])) return false;
                o.windowSet = true;
                break;
            case 'X':
                for (int i = 0; i < 4; ++i)
                    if (!in.Real(flag, o.crop[i])) return false;
                o.cropSet = true;
                break;
            default: return in.Fail("unknown option '" + arg + "'");
        }
    }
    return true;
}

}  // namespace rs
