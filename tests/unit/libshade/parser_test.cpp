#include "libshade/parser.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <random>

#include "libcommon/error.h"
#include "libshade/expression.h"
#include "libsurf/surface.h"
#include "libtext/texture.h"

namespace rs {
namespace {

// Collects diagnostics for the lifetime of the object.
class CaptureDiagnostics {
  public:
    CaptureDiagnostics() {
        previous_ = SetErrorSink([this](const Diagnostic& d) { diagnostics.push_back(d); });
    }
    ~CaptureDiagnostics() { SetErrorSink(previous_); }
    bool Has(Severity s, const std::string& text) const {
        for (const Diagnostic& d : diagnostics)
            if (d.severity == s && d.message.find(text) != std::string::npos) return true;
        return false;
    }
    std::vector<Diagnostic> diagnostics;

  private:
    ErrorSink previous_;
};

Scene Parse(const std::string& text, const RenderOptions& options = RenderOptions()) {
    return ParseSceneText(text, "t.ray", options);
}

// The fatal error's text ("file:line: message"), or "" when parsing succeeds.
std::string ParseError(const std::string& text, const RenderOptions& options = RenderOptions()) {
    CaptureDiagnostics quiet;
    try {
        Parse(text, options);
    } catch (const FatalError& e) {
        return e.what();
    }
    return "";
}

const std::vector<std::shared_ptr<Object>>& Top(const Scene& s) {
    return s.world->aggregate()->Children();
}

const char* kBall = "sphere 1 0 0 0\n";

TEST(Parser, CameraAndOptions) {
    Scene s =
        Parse(std::string(kBall) +
              "eyep 1 2 3 lookp 4 5 6 up 0 1 0 fov 30 20 aperture 0.5 focaldist 7\n"
              "eyesep 0.25 screen 320 240 window 1 2 3 4 crop 0 .5 0 .5\n"
              "samples 4 nojitter filter gauss 2 contrast .1 .2 .3 cutoff .01\n"
              "maxdepth 7 background 0.5 0.25 1 outfile out.ppm report verbose quiet 3 st.txt\n"
              "frames 5 starttime -1 framelength 2 shutter 0.5\n");
    EXPECT_EQ(s.camera.eye.x, 1);
    EXPECT_EQ(s.camera.eye.z, 3);
    EXPECT_EQ(s.camera.lookAt.y, 5);
    EXPECT_EQ(s.camera.up.y, 1);
    EXPECT_EQ(s.camera.hfov, 30);
    EXPECT_EQ(s.camera.vfov, 20);
    EXPECT_EQ(s.camera.aperture, 0.5);
    EXPECT_EQ(s.camera.focalDist, 7);
    EXPECT_EQ(s.camera.eyeSep, 0.25);
    const RenderOptions& o = s.options;
    EXPECT_EQ(o.xres, 320);
    EXPECT_EQ(o.yres, 240);
    EXPECT_EQ(o.window[3], 4);
    EXPECT_EQ(o.crop[1], 0.5);
    EXPECT_EQ(o.samples, 4);
    EXPECT_FALSE(o.jitter);
    EXPECT_EQ(o.filter, FilterKind::Gauss);
    EXPECT_EQ(o.filterWidth, 2);
    EXPECT_EQ(o.contrast, Color(.1, .2, .3));
    EXPECT_EQ(o.cutoff, Color(.01));
    EXPECT_EQ(o.maxDepth, 7);
    EXPECT_EQ(o.background, Color(0.5, 0.25, 1));
    EXPECT_EQ(o.outFile, "out.ppm");
    EXPECT_TRUE(o.verbose);
    EXPECT_TRUE(o.quiet);
    EXPECT_EQ(o.reportFreq, 3);
    EXPECT_EQ(o.statsFile, "st.txt");
    EXPECT_EQ(o.frames, 5);
    EXPECT_EQ(o.startTime, -1);
    EXPECT_EQ(o.frameLength, 2);
    EXPECT_EQ(o.shutter, 0.5);
}

TEST(Parser, CommandLineSettingsWinOverKeywords) {
    RenderOptions cli;
    cli.xres = cli.yres = 64;
    cli.resolutionSet = true;
    cli.samples = 1;
    cli.samplesSet = true;
    cli.jitter = true;
    cli.jitterSet = true;
    cli.maxDepth = 0;
    cli.maxDepthSet = true;
    cli.outFile = "cli.ppm";
    cli.outFileSet = true;
    cli.frames = 2;
    cli.framesSet = true;
    cli.contrastSet = cli.cutoffSet = cli.windowSet = cli.cropSet = true;
    cli.reportFreq = 9;
    cli.reportFreqSet = true;
    cli.statsFileSet = true;
    cli.eyeSepSet = true;
    CaptureDiagnostics diags;
    Scene s =
        Parse(std::string(kBall) +
                  "screen 320 240 sample 5 nojitter maxdepth 3 outfile x.ppm frames 9\n"
                  "contrast .5 .5 .5 cutoff .5 window 1 2 3 4 crop 0 .5 0 .5 report 2 st.txt\n"
                  "eyesep 3\n",
              cli);
    EXPECT_EQ(s.options.xres, 64);
    EXPECT_EQ(s.options.samples, 1);
    EXPECT_TRUE(s.options.jitter);
    EXPECT_EQ(s.options.maxDepth, 0);
    EXPECT_EQ(s.options.outFile, "cli.ppm");
    EXPECT_EQ(s.options.frames, 2);
    EXPECT_EQ(s.options.contrast, Color(0.2, 0.15, 0.3));
    EXPECT_EQ(s.options.cutoff, Color(0.002));
    EXPECT_EQ(s.options.window[1], -1);
    EXPECT_EQ(s.options.crop[1], 1);
    EXPECT_EQ(s.options.reportFreq, 9);
    EXPECT_EQ(s.options.statsFile, "");
    EXPECT_EQ(s.camera.eyeSep, -1);
    EXPECT_TRUE(diags.Has(Severity::Warn, "Ignoring output file name"));
}

TEST(Parser, TogglesActAfterTheCommandLine) {
    RenderOptions cli;
    cli.shadowTransparency = false;  // -o
    Scene s = Parse(std::string(kBall) + "shadowtransp filter box", cli);
    EXPECT_TRUE(s.options.shadowTransparency);  // -o and shadowtransp cancel out
    EXPECT_EQ(s.options.filter, FilterKind::Box);
    EXPECT_EQ(s.options.filterWidth, -1);
    EXPECT_FALSE(Parse(std::string(kBall) + "shadowtransp").options.shadowTransparency);
}

TEST(Parser, Lights) {
    Scene s = Parse(std::string(kBall) +
                    "light 0.5 ambient\nlight 1 0.5 0.25 point 1 2 3\n"
                    "light 1 directional 0 0 1 noshadow\nlight .2 spot 0 0 5 0 0 0 2 10 20\n"
                    "light 1 extended 0.5 0 0 9 light 1 area 0 0 0 1 0 0 2 0 1 0 2\n");
    EXPECT_EQ(s.ambientLight, Color(0.5));
    ASSERT_GE(s.lights.size(), 5u);
    EXPECT_EQ(s.lights[0]->intensity, Color(1, 0.5, 0.25));
    EXPECT_FALSE(s.lights[0]->noshadow);
    EXPECT_TRUE(s.lights[1]->noshadow);
    EXPECT_EQ(s.lights[2]->intensity, Color(0.2));
}

TEST(Parser, Atmosphere) {
    Scene s = Parse(std::string(kBall) +
                    "atmosphere 1.33 fog .5 .5 .5 1 2 3 mist 1 1 1 4 4 4 0.5 2\n"
                    "atmosphere fogdeck 1 2 3 3 3 0.5 4 1 1 1 9 9 9\n");
    EXPECT_DOUBLE_EQ(s.atmosphereIndex, 1.33);
    ASSERT_EQ(s.atmosphere.size(), 1u);  // the second statement replaced the first list
    EXPECT_EQ(s.atmosphere[0].kind, AtmosphereEffect::Kind::FogDeck);
    EXPECT_EQ(s.atmosphere[0].octaves, 4);
    EXPECT_EQ(s.atmosphere[0].thinness, Color(9));
}

TEST(Parser, NamedSurfacesAndModifiedCopies) {
    Scene s = Parse(
        "surface red diffuse 1 0 0\n"
        "sphere red 1 0 0 0\n"
        "sphere red specpow 3 1 0 0 0\n"
        "sphere ambient .5 .5 .5 1 0 0 0\n"
        "sphere 1 0 0 0\n");
    const auto& top = Top(s);
    ASSERT_EQ(top.size(), 4u);
    EXPECT_EQ(top[0]->surface->diffuse, Color(1, 0, 0));
    EXPECT_EQ(top[1]->surface->diffuse, Color(1, 0, 0));
    EXPECT_EQ(top[1]->surface->specpow, 3);
    EXPECT_EQ(top[0]->surface->specpow, 15);  // the named surface is unchanged
    EXPECT_EQ(top[2]->surface->ambient, Color(0.5));
    EXPECT_EQ(top[2]->surface->diffuse, Color(0));  // fresh surface
    EXPECT_EQ(top[3]->surface, nullptr);            // nothing bound: inherits / default
}

TEST(Parser, ApplysurfScopes) {
    Scene s = Parse(
        "sphere 1 0 0 0\n"
        "applysurf diffuse 1 0 0\n"
        "sphere 1 0 0 0\n"
        "list\n"
        "  sphere 1 0 0 0\n"
        "  applysurf diffuse 0 1 0\n"
        "  sphere 1 0 0 0\n"
        "  sphere cursurf specpow 2 1 0 0 0\n"
        "end\n"
        "sphere cursurf 1 0 0 0\n");
    const auto& top = Top(s);
    ASSERT_EQ(top.size(), 4u);
    EXPECT_EQ(top[0]->surface, nullptr);  // before applysurf
    EXPECT_EQ(top[1]->surface->diffuse, Color(1, 0, 0));
    const auto& list = *top[2];
    EXPECT_EQ(list.surface->diffuse, Color(1, 0, 0));  // the enclosing scope's default
    const auto& kids = list.aggregate()->Children();
    ASSERT_EQ(kids.size(), 3u);
    EXPECT_EQ(kids[0]->surface, nullptr);  // a new scope starts empty
    EXPECT_EQ(kids[1]->surface->diffuse, Color(0, 1, 0));
    EXPECT_EQ(kids[2]->surface->diffuse, Color(0, 1, 0));
    EXPECT_EQ(kids[2]->surface->specpow, 2);
    EXPECT_EQ(top[3]->surface->diffuse, Color(1, 0, 0));  // the inner applysurf has ended
}

TEST(Parser, CursurfWithoutDefaultIsTheDefaultSurface) {
    Scene s = Parse("sphere cursurf 1 0 0 0 sphere cursurf reflect 1 1 0 0 0");
    EXPECT_EQ(Top(s)[0]->surface->diffuse, Surface::Default().diffuse);
    EXPECT_EQ(Top(s)[1]->surface->specpow, Surface::Default().specpow);
    EXPECT_EQ(Top(s)[1]->surface->reflect, 1);
}

TEST(Parser, DefinitionsInsideAggregatesAreGlobal) {
    Scene s = Parse(
        "list surface inner diffuse 0 0 1 name ball sphere 1 0 0 0 box 0 0 0 1 1 1 end\n"
        "sphere inner 1 0 0 0 object ball\n");
    ASSERT_EQ(Top(s).size(), 3u);
    EXPECT_EQ(Top(s)[1]->surface->diffuse, Color(0, 0, 1));
    EXPECT_EQ(Top(s)[2]->kind(), Object::Kind::Instance);
}

TEST(Parser, SurfaceRedefinitionWarnsAndShadows) {
    CaptureDiagnostics diags;
    Scene s = Parse("surface a diffuse 1 1 1\nsurface a diffuse 0 0 1\nsphere a 1 0 0 0");
    EXPECT_TRUE(diags.Has(Severity::Warn, "Redefinition of surface 'a'"));
    EXPECT_EQ(Top(s)[0]->surface->diffuse, Color(0, 0, 1));
}

TEST(Parser, NamedObjectsAndInstances) {
    Scene s = Parse(
        "surface shiny specpow 50\n"
        "name ball sphere 1 0 0 0 translate 1 0 0\n"
        "object ball translate 0 2 0\n"
        "object shiny ball\n"
        "name shiny sphere 2 0 0 0\n"  // object and surface names are separate
        "object shiny\n");
    const auto& top = Top(s);
    ASSERT_EQ(top.size(), 3u);
    EXPECT_EQ(top[0]->kind(), Object::Kind::Instance);
    EXPECT_EQ(top[0]->instanceOf(), top[1]->instanceOf());
    EXPECT_EQ(top[0]->instanceOf()->name, "ball");
    EXPECT_EQ(top[0]->surface, nullptr);
    EXPECT_EQ(top[1]->surface->specpow, 50);
    EXPECT_EQ(top[2]->instanceOf()->name, "shiny");
    // The stored transform acts first, then the instance's own.
    Vec3 p = top[0]->parentFromObject.At(0).ApplyPoint(
        top[0]->instanceOf()->parentFromObject.At(0).ApplyPoint({0, 0, 0}));
    EXPECT_DOUBLE_EQ(p.x, 1);
    EXPECT_DOUBLE_EQ(p.y, 2);
}

TEST(Parser, TransformsApplyInWrittenOrder) {
    Scene s = Parse(
        "sphere 1 0 0 0 translate 1 0 0 rotate 0 0 1 90 scale 2 2 2\n"
        "sphere 1 0 0 0 transform 0 1 0 -1 0 0 0 0 1 5 6 7\n");
    Vec3 p = Top(s)[0]->parentFromObject.Static().ApplyPoint({0, 0, 0});
    EXPECT_NEAR(p.x, 0, 1e-12);  // (1,0,0) → rotate → (0,1,0) → scale → (0,2,0)
    EXPECT_NEAR(p.y, 2, 1e-12);
    Vec3 q = Top(s)[1]->parentFromObject.Static().ApplyPoint({1, 0, 0});
    EXPECT_NEAR(q.x, 5, 1e-12);  // x ↦ (0,1,0), plus translation
    EXPECT_NEAR(q.y, 7, 1e-12);
    EXPECT_NEAR(q.z, 7, 1e-12);
}

TEST(Parser, AnimatedTransforms) {
    Scene s = Parse(
        "define spin (linear(0, 0, 10, 90))\n"
        "define k 2\n"
        "sphere 1 0 0 0 translate 1 0 0 rotate 0 0 1 (spin) translate (k) 0 (frame)\n");
    const Object& ball = *Top(s)[0];
    ASSERT_TRUE(ball.parentFromObject.IsAnimated());
    Vec3 at0 = ball.parentFromObject.At(0).ApplyPoint({0, 0, 0});
    EXPECT_NEAR(at0.x, 3, 1e-12);
    Vec3 at10 = ball.parentFromObject.At(10).ApplyPoint({0, 0, 0});
    EXPECT_NEAR(at10.x, 2, 1e-12);
    EXPECT_NEAR(at10.y, 1, 1e-12);
    SetCurrentFrame(4);
    EXPECT_NEAR(ball.parentFromObject.At(10).ApplyPoint({0, 0, 0}).z, 4, 1e-12);
    SetCurrentFrame(0);
}

TEST(Parser, TextureTransformsMayBeAnimated) {
    Scene s = Parse(
        "sphere 1 0 0 0 texture bump 1 scale 2 2 2 rotate 0 0 1 (linear(0, 0, 1, 90))\n"
        "texture wood translate 1 0 0\n");
    const Object& ball = *Top(s)[0];
    ASSERT_EQ(ball.Textures().size(), 2u);
    EXPECT_TRUE(ball.Textures()[0]->transform.IsAnimated());
    Vec3 p = ball.Textures()[0]->transform.At(1).ApplyPoint({1, 0, 0});
    EXPECT_NEAR(p.x, 0, 1e-12);
    EXPECT_NEAR(p.y, 2, 1e-12);
    EXPECT_FALSE(ball.Textures()[1]->transform.IsAnimated());
    EXPECT_FALSE(ball.parentFromObject.IsAnimated());
    EXPECT_NE(ParseError("sphere 1 0 0 0 texture bump (time)").find("Illegal expression use"),
              std::string::npos);
}

TEST(Parser, IllegalTimeVaryingUse) {
    EXPECT_EQ(ParseError("sphere (time) 0 0 0"),
              "t.ray:1: Illegal expression use: only transformation parameters may vary with time "
              "(usage: sphere [surface] radius cx cy cz)");
    EXPECT_NE(ParseError("define t (frame)\nsphere 1 0 0 0\nscreen (t) 10")
                  .find("t.ray:3: Illegal expression use"),
              std::string::npos);
    EXPECT_NE(ParseError("sphere 1 0 0 0\nlight (time) point 0 0 0")
                  .find("t.ray:2: Illegal expression use"),
              std::string::npos);
    EXPECT_NE(
        ParseError("sphere diffuse (time) 0 0 1 0 0 0").find("t.ray:1: Illegal expression use"),
        std::string::npos);
}

TEST(Parser, DefineErrors) {
    EXPECT_EQ(ParseError("define x 1\ndefine x 2\n"), "t.ray:2: 'x' is already defined");
    EXPECT_EQ(ParseError("define pi 3\n"), "t.ray:1: 'pi' is already defined");
    EXPECT_EQ(ParseError("define linear 3\n"), "t.ray:1: 'linear' is already defined");
    EXPECT_EQ(ParseError("sphere (r) 0 0 0\n"),
              "t.ray:1: Undefined variable 'r' (usage: sphere [surface] radius cx cy cz)");
}

TEST(Parser, DefinedValuesAreUsable) {
    Scene s = Parse("define r 2\ndefine d (r * 2)\nsphere 1 0 0 0 translate (d) (r) 0\n");
    Vec3 p = Top(s)[0]->parentFromObject.Static().ApplyPoint({0, 0, 0});
    EXPECT_DOUBLE_EQ(p.x, 4);
    EXPECT_DOUBLE_EQ(p.y, 2);
}

TEST(Parser, ErrorsCarryFileAndLine) {
    struct Case {
        const char* text;
        const char* expected;
    } cases[] = {
        {"sphere 1 0 0 0\nfoo", "t.ray:2: Unexpected 'foo'"},
        {"sphere 1 0 0\n", "t.ray:2: Expected a number or '(', found end of input"},
        {"sphere 1 0 0 0\n\nobject nothing", "t.ray:3: Undefined object 'nothing'"},
        {"sphere nosuch 1 0 0 0", "t.ray:1: Undefined surface 'nosuch'"},
        {"list\nsphere 1 0 0 0\nlight 1 point 0 0 0\nend",
         "t.ray:3: 'light' is not allowed inside an aggregate"},
        {"sphere 1 0 0 0\nlist\nsphere 1 0 0 0\n", "t.ray:2: Missing 'end' for this 'list'"},
        {"sphere 1 0 0 0 scale 0 1 1", "t.ray:1: Singular matrix"},
        {"sphere 1 0 0 0\nheightfield x.hf", "t.ray:2: cannot open height field 'x.hf'"},
        {"sphere 1 0 0 0\nsample 0", "t.ray:2: The sample count must be at least 1"},
        {"sphere 1 0 0 0\nscreen 0 10", "t.ray:2: Invalid screen resolution"},
        {"sphere 1 0 0 0\nreport 0", "t.ray:2: The report frequency must be at least 1"},
        {"sphere 1 0 0 0 texture nosuch", "t.ray:1: Unknown texture type 'nosuch'"},
        {"sphere 1 0 0 0\nlight 1 nowhere 0 0 0", "t.ray:2: Expected a light type"},
        {"sphere 1 0 0 0\nfilter triangle", "t.ray:2: Expected 'box' or 'gauss'"},
        {"define a 1\nsphere 1 0 0 0 translate (a-1) 0 0", "t.ray:2: Undefined variable 'a-1'"},
        {"sphere 1 0 0 0 translate (1/0) 0 0",
         "t.ray:1: Transformation parameter is not a finite number"},
        {"sphere 1 0 0 0\nsurface glassy transp 1 index 0",
         "t.ray:2: Surface 'glassy' is transparent"},
        {"sphere 1 0 0 0\n/* open", "t.ray:2: Unterminated comment"},
        {"sphere 1 0 0 0\n#pragma x", "t.ray:2: Unknown '#' control"},
        {"sphere 1 0 0 0\nlist end end", "t.ray:2: Unexpected 'end'"},
        {"sphere 1 0 0 0\nname 3 sphere 1 0 0 0", "t.ray:2: Expected a name, found '3'"},
        {"sphere 1 0 0 0\nscreen 1e10 1", "t.ray:2: Integer out of range"},
        {"sphere 1 0 0 0 texture", "t.ray:1: Unknown texture type end of input"},
        {"", "Nothing to be rendered"},
        {"# 1 \"main.ray\"\nsphere 1 0 0 0\n# 1 \"inc.ray\" 1\n\nsphere 1 0 0",
         "inc.ray:2: Expected a number"},
    };
    for (const Case& c : cases) {
        std::string error = ParseError(c.text);
        EXPECT_EQ(error.rfind(c.expected, 0), 0u) << "input: " << c.text << "\nerror: " << error;
    }
}

TEST(Parser, EmptyAndInvalidAggregatesAreDiscarded) {
    CaptureDiagnostics diags;
    Scene s = Parse(
        "list end\nunion sphere 1 0 0 0 end\ngrid 0 1 1 sphere 1 0 0 0 end\n"
        "name empty list end\nobject empty\nsphere 1 0 0 0\n");
    EXPECT_EQ(Top(s).size(), 1u);
    EXPECT_TRUE(diags.Has(Severity::Warn, "Null object defined"));
    EXPECT_TRUE(diags.Has(Severity::Warn, "needs exactly two operands"));
    EXPECT_TRUE(diags.Has(Severity::Warn, "Grid voxel counts"));
}

TEST(Parser, NothingToBeRenderedWithOnlyDiscardedObjects) {
    EXPECT_EQ(ParseError("light 1 point 0 0 0\nlist end\n"), "Nothing to be rendered");
}

TEST(Parser, ModelNestingLimit) {
    auto nested = [](int levels) {
        std::string text;
        for (int i = 0; i < levels; ++i) text += "list ";
        text += "sphere 1 0 0 0 ";
        for (int i = 0; i < levels; ++i) text += "end ";
        return text;
    };
    EXPECT_EQ(ParseError(nested(kMaxModelDepth)), "");
    EXPECT_EQ(ParseError(nested(kMaxModelDepth + 1)).find("t.ray:1: Model nesting too deep"), 0u);
    EXPECT_EQ(ParseError(nested(100000)).find("t.ray:1: Model nesting too deep"), 0u);
    // Through named objects: each level wraps the previous one in a list.
    std::string chain = "name o0 sphere 1 0 0 0\n";
    for (int i = 1; i <= kMaxModelDepth + 1; ++i)
        chain += "name o" + std::to_string(i) + " list object o" + std::to_string(i - 1) + " end\n";
    chain += "object o" + std::to_string(kMaxModelDepth + 1) + "\n";
    EXPECT_NE(ParseError(chain).find("Model nesting too deep"), std::string::npos);
    // Instances of instances without aggregates are bounded too.
    std::string instances = "name i0 sphere 1 0 0 0\n";
    for (int i = 1; i < 200; ++i)
        instances += "name i" + std::to_string(i) + " object i" + std::to_string(i - 1) + "\n";
    EXPECT_NE(ParseError(instances + "object i199\n").find("Model nesting too deep"),
              std::string::npos);
}

TEST(Parser, ObjectWithSurfaceNameFirst) {
    Scene s = Parse("surface a diffuse 1 0 0\nname b sphere 1 0 0 0\nobject a b\nobject b\n");
    ASSERT_EQ(Top(s).size(), 2u);
    EXPECT_EQ(Top(s)[0]->surface->diffuse, Color(1, 0, 0));
    EXPECT_EQ(Top(s)[1]->surface, nullptr);
}

TEST(Parser, PolygonSynonymAndOpenEndedVertexList) {
    Scene s = Parse("polygon 0 0 0 1 0 0 1 1 0 0 1 0 poly 0 0 0 1 0 0 0 1 0\n");
    EXPECT_EQ(Top(s).size(), 2u);
}

TEST(Parser, EyepTransformsAreIgnored) {
    CaptureDiagnostics diags;
    Scene s = Parse(std::string(kBall) + "eyep 0 -5 0 rotate 0 0 1 90 translate 1 1 1\nfov 30");
    EXPECT_EQ(s.camera.eye.y, -5);
    EXPECT_EQ(s.camera.hfov, 30);
    EXPECT_TRUE(diags.Has(Severity::Advise, "ignored"));
}

TEST(Parser, PrintReportsTheValue) {
    CaptureDiagnostics diags;
    Parse(std::string(kBall) + "print (2 ^ 3)");
    EXPECT_TRUE(diags.Has(Severity::Warn, "8.000000"));
}

TEST(Parser, CarriageReturnsAreWhitespace) {
    Scene s = Parse("surface r\r\n  diffuse 1 0 0\r\nsphere r 1 0 0 0\r\n");
    EXPECT_EQ(Top(s)[0]->surface->diffuse, Color(1, 0, 0));
}

TEST(Parser, ScenesFromStandardInputAndFilesThroughCpp) {
    char name[] = "/tmp/rs_scene_XXXXXX";
    int fd = mkstemp(name);
    close(fd);
    std::ofstream(name) << "#define EXPAND(x) scale x x x\nsphere R 0 0 0 EXPAND(S)\n";
    ParseInput in;
    in.path = name;
    in.cppArgs = "-DR=2";
    in.extraDefines = {"S=3"};
    Scene s = ParseScene(in, RenderOptions());
    ASSERT_EQ(Top(s).size(), 1u);
    EXPECT_DOUBLE_EQ(Top(s)[0]->parentFromObject.Static().ApplyPoint({1, 0, 0}).x, 3);

    in.useCpp = false;
    std::string error;
    {
        CaptureDiagnostics quiet;
        try {
            ParseScene(in, RenderOptions());
        } catch (const FatalError& e) {
            error = e.what();
        }
    }
    EXPECT_EQ(error, std::string(name) + ":1: Unknown '#' control: #define EXPAND(x) scale x x x");
    std::remove(name);
}

// Random token sequences either parse or fail with a FatalError: no crash, no hang.
TEST(Parser, RandomTokenSoupFailsCleanly) {
    const char* vocab[] = {
        "sphere",     "box",       "plane",      "disc",        "cylinder", "cone",
        "torus",      "triangle",  "triangleuv", "poly",        "list",     "grid",
        "union",      "intersect", "difference", "end",         "object",   "name",
        "surface",    "applysurf", "cursurf",    "ambient",     "diffuse",  "specpow",
        "reflect",    "transp",    "index",      "translu",     "noshadow", "translate",
        "scale",      "rotate",    "transform",  "texture",     "checker",  "bump",
        "wood",       "blotch",    "stripe",     "gloss",       "map",      "uv",
        "planar",     "light",     "point",      "directional", "spot",     "area",
        "define",     "print",     "eyep",       "fov",         "screen",   "sample",
        "atmosphere", "fog",       "report",     "(",           ")",        "-",
        "+",          "*",         "/",          "%",           "^",        ",",
        "time",       "frame",     "linear",     "pi",          "sin",      "hypot",
        "a",          "b",         "1",          "0",           "2",        "0.5",
        "1e3"};
    const int n = sizeof vocab / sizeof *vocab;
    CaptureDiagnostics quiet;
    int parsed = 0;
    for (unsigned seed = 1; seed <= 3000; ++seed) {
        std::mt19937 rng(seed);
        std::string text = "sphere 1 0 0 0\n";
        for (int i = 0, len = static_cast<int>(rng() % 60); i < len; ++i) {
            text += vocab[rng() % n];
            text += rng() % 5 == 0 ? "\n" : " ";
        }
        try {
            Parse(text);
            ++parsed;
        } catch (const FatalError&) {
        } catch (...) {
            ADD_FAILURE() << "seed " << seed << ": unexpected exception for\n" << text;
        }
    }
    EXPECT_GT(parsed, 0);
}

// The example scenes of the original distribution parse completely.
class ExampleScene : public ::testing::TestWithParam<const char*> {};

TEST_P(ExampleScene, Parses) {
    const std::string dir = RAYSHADE_SCENES_DIR;
    if (access(dir.c_str(), R_OK) != 0) GTEST_SKIP() << "scene folder not available";
    char cwd[4096];
    ASSERT_NE(getcwd(cwd, sizeof cwd), nullptr);
    ASSERT_EQ(chdir(dir.c_str()), 0);  // relative colour maps and images resolve there
    ParseInput in;
    in.path = std::string(GetParam()) + ".ray";
    if (in.path == "ashtray.ray") in.cppArgs = "-DIMAGEFILE=testtex.img";
    std::string error;
    Scene s;
    {
        CaptureDiagnostics quiet;
        try {
            s = ParseScene(in, RenderOptions());
        } catch (const FatalError& e) {
            error = e.what();
        }
    }
    ASSERT_EQ(chdir(cwd), 0);
    ASSERT_EQ(error, "");
    EXPECT_GT(s.world->PrimitiveCount(), 0);
}

INSTANTIATE_TEST_SUITE_P(Rayshade, ExampleScene,
                         ::testing::Values("ashtray", "balls", "boxball", "coin", "csg", "glass",
                                           "mtv", "planet"));

TEST(ExampleScenes, CoinIsAnimated) {
    CaptureDiagnostics quiet;
    ParseInput in;
    in.path = std::string(RAYSHADE_SCENES_DIR) + "/coin.ray";
    if (access(in.path.c_str(), R_OK) != 0) GTEST_SKIP() << "scene not available";
    Scene s = ParseScene(in, RenderOptions());
    EXPECT_EQ(s.options.frames, 32);
    EXPECT_EQ(s.options.samples, 4);
    EXPECT_EQ(s.options.startTime, -1);
    EXPECT_EQ(s.options.shutter, 1);
    EXPECT_DOUBLE_EQ(s.camera.lookAt.z, 3.5);
    ASSERT_EQ(Top(s).size(), 2u);
    const Object& coin = *Top(s)[1];
    EXPECT_TRUE(coin.parentFromObject.IsAnimated());
    // At time 15 (half way) the coin is at its zenith height 7, at ground (0, 0).
    Vec3 c = coin.parentFromObject.At(15).ApplyPoint({0, 0, 0});
    EXPECT_NEAR(c.x, 0, 1e-9);
    EXPECT_NEAR(c.z, 7, 1e-9);
}

TEST(ExampleScenes, BlobSceneParses) {
    ParseInput in;
    in.path = std::string(RAYSHADE_SCENES_DIR) + "/blob.ray";
    if (access(in.path.c_str(), R_OK) != 0) GTEST_SKIP() << "scene not available";
    Scene s = ParseScene(in, RenderOptions());
    EXPECT_EQ(s.world->PrimitiveCount(), 2);  // the blob and the plane
}

}  // namespace
}  // namespace rs

namespace rs {
namespace {

TEST(Parser, ImplicitBlockWithOrWithoutSurface) {
    // A NAME after `implicit` is the surface unless it begins the block's statements.
    Scene bare = Parse("implicit\n field quadratic 0.5 1.5 1.5\n point a 0 0 0\nend\n");
    ASSERT_EQ(Top(bare).size(), 1u);
    EXPECT_EQ(Top(bare)[0]->surface, nullptr);
    Scene named = Parse("surface skin diffuse 1 0 0\nimplicit skin point a 0 0 0\nend\n");
    ASSERT_EQ(Top(named).size(), 1u);
    ASSERT_NE(Top(named)[0]->surface, nullptr);
    EXPECT_EQ(Top(named)[0]->surface->diffuse, Color(1, 0, 0));
}

}  // namespace
}  // namespace rs
