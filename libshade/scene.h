// Everything a parsed scene file describes, handed from the parser to the renderer.
// Defaults are the original program's (spec §3.2, §3.16).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "libcommon/error.h"
#include "libcommon/vector.h"
#include "liblight/light.h"
#include "libobj/object.h"

namespace rs {

struct Camera {
    Vec3 eye{0, -10, 0};
    Vec3 lookAt{0, 0, 0};
    Vec3 up{0, 0, 1};
    double hfov = 45;      // degrees
    double vfov = -1;      // degrees; < 0: derived as hfov·yres/xres (spec §3.2)
    double aperture = 0;   // radius of the square lens; 0 = pinhole
    double focalDist = -1; // < 0: |lookAt − eye|
    double eyeSep = -1;    // < 0: unset (stereo then impossible)
    // The last of the eyep, lookp and up statements (unknown when the scene has none): a
    // degenerate view is reported there.
    SourceLocation viewStatement;
};

enum class FilterKind { Box, Gauss };

// An atmospheric effect (spec §3.8); parsed now, applied by the renderer.
struct AtmosphereEffect {
    enum class Kind { Fog, Mist, FogDeck } kind = Kind::Fog;
    Color color;
    Color thinness;
    double zero = 0, scale = 1;                 // mist
    double altitude = 0, offset = 0;            // fogdeck
    Vec3 deckScale{1, 1, 1};
    double chaoScale = 0;
    int octaves = 0;
};

// Render options. Each field that the command line can also set has a `...Set` flag: once
// the CLI sets it, the scene keyword is ignored (spec §3.1).
struct RenderOptions {
    int xres = 512, yres = 512;
    bool resolutionSet = false;
    int window[4] = {0, -1, 0, -1};  // x0 x1 y0 y1; x1 < 0: whole screen
    bool windowSet = false;
    double crop[4] = {0, 1, 0, 1};   // l r b t
    bool cropSet = false;

    int samples = 3;
    bool samplesSet = false;
    bool jitter = true;
    bool jitterSet = false;
    FilterKind filter = FilterKind::Box;
    double filterWidth = -1;  // < 0: 1 for box, 1.8 for gauss
    Color contrast{0.2, 0.15, 0.3};
    bool contrastSet = false;
    Color cutoff{0.002, 0.002, 0.002};
    bool cutoffSet = false;
    int maxDepth = 5;
    bool maxDepthSet = false;
    Color background;
    bool shadowTransparency = true;  // toggled by `shadowtransp` and -o
    bool noShadows = false;          // -n
    bool shadowCache = true;         // toggled by -s (changes only statistics and time)
    bool flipNormals = false;        // -f, read by triangles/polygons at creation
    double gamma = 1;                // -G

    std::string outFile;
    bool outFileSet = false;
    bool verbose = false;
    bool quiet = false;
    int reportFreq = 10;
    bool reportFreqSet = false;
    std::string statsFile;
    bool statsFileSet = false;

    int frames = 1;
    bool framesSet = false;
    int startFrame = 0;  // -A
    double startTime = 0;
    double frameLength = 1;
    double shutter = 0;

    int eyeSepSide = 0;   // -l: −1, -r: +1, 0: mono
    bool eyeSepSet = false;
    int threads = 0;      // 0: all cores
};

struct Scene {
    Camera camera;
    RenderOptions options;
    // Lights in order of definition (the renderer evaluates them in reverse, as the
    // original stores them).
    std::vector<std::shared_ptr<const Light>> lights;
    Color ambientLight{1, 1, 1};
    double atmosphereIndex = 1;
    std::vector<AtmosphereEffect> atmosphere;
    // The World: an implicit list of every top-level instance.
    std::shared_ptr<Object> world;
    // Objects defined with `name`, in order of definition (for the verbose report).
    std::vector<std::shared_ptr<Object>> namedObjects;
    // Primitives the parser read in parallel runs (parser.cpp; for the verbose report).
    std::size_t parallelParsedObjects = 0;
};

}  // namespace rs
