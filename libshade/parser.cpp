#include "libshade/parser.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string_view>
#include <unordered_map>

#include "libcommon/limits.h"
#include "libcommon/constants.h"
#include "libcommon/parallel_build.h"
#include "liblight/lights.h"
#include "libobj/csg.h"
#include "libobj/grid.h"
#include "libobj/list.h"
#include "libshade/arg_reader_impl.h"
#include "libshade/expression_parser.h"
#include "libshade/preprocess.h"
#include "libshade/primitive_registry.h"
#include "libtext/texture_registry.h"

namespace rs {

namespace {

// The hit path holds every node from a primitive up to the World (HitRecord::kMaxPath), so
// a node below the World may be at most this many levels deep, instances included.
constexpr int kMaxNodeDepth = HitRecord::kMaxPath - 1;

bool IsSurfaceAttribute(const Token& t) {
    if (t.kind != TokenKind::Keyword) return false;
    // Views, so that most words are rejected by their length (this runs after every object).
    static constexpr std::string_view kAttributes[] = {"ambient", "diffuse", "specular", "specpow",
                                                       "body",    "extinct", "transp",   "reflect",
                                                       "index",   "translu", "noshadow"};
    return std::any_of(std::begin(kAttributes), std::end(kAttributes),
                       [&](std::string_view a) { return t.keyword == a; });
}

// Keywords are compared as views: a literal's length is then known at compile time and most
// words are rejected by their length (these run for every object of large scenes).
bool IsAggregateKeyword(std::string_view k) {
    return k == "list" || k == "grid" || k == "union" || k == "intersect" || k == "difference";
}

// Keywords that are legal only outside aggregates (spec §2, parsing notes).
bool IsTopLevelOnly(std::string_view k) {
    static constexpr std::string_view kWords[] = {
        "eyep",       "lookp",  "up",        "fov",         "aperture",     "focaldist",
        "eyesep",     "screen", "window",    "crop",        "sample",       "filter",
        "contrast",   "cutoff", "maxdepth",  "background",  "shadowtransp", "outfile",
        "report",     "frames", "starttime", "framelength", "shutter",      "light",
        "atmosphere", "define", "print"};
    return std::any_of(std::begin(kWords), std::end(kWords), [&](std::string_view w) { return k == w; });
}

// Hashes std::string keys and std::string_view lookups alike, so that a token's spelling
// finds its entry without being copied into a string.
struct NameHash {
    using is_transparent = void;
    size_t operator()(std::string_view name) const { return std::hash<std::string_view>()(name); }
};
template <class Value>
using NameMap = std::unordered_map<std::string, Value, NameHash, std::equal_to<>>;

enum class TransformKind { Translate, Scale, Rotate, General };

// The transform for already evaluated parameters, or nothing when they are invalid.
std::optional<Transform> BuildTransform(TransformKind kind, const std::vector<double>& v) {
    switch (kind) {
        case TransformKind::Translate:
            return Transform::Translate({v[0], v[1], v[2]});
        case TransformKind::Scale:
            return Transform::Scale({v[0], v[1], v[2]});
        case TransformKind::Rotate:
            return Transform::Rotate({v[0], v[1], v[2]}, v[3]);
        case TransformKind::General: {
            Vec3 t = v.size() == 12 ? Vec3{v[9], v[10], v[11]} : Vec3{0, 0, 0};
            return Transform::General({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]},
                                      t);
        }
    }
    return std::nullopt;
}

// Depth of a node: `model` counts aggregate levels (the original's nesting limit), `total`
// counts every node on the way down to a primitive (bounded by the hit path's length).
struct NodeDepth {
    int model = 0;
    int total = 1;
};

class Parser final : public ParserServices {
  public:
    Parser(std::string text, const std::string& fileName, const RenderOptions& options)
        : tokens_(std::move(text), fileName) {
        scene_.options = options;
        scopes_.emplace_back();
    }
    // A parser of one piece of a parallel run (ParsePrimitiveRun): `piece` starts at line
    // `firstLine` of `fileName`, in the innermost scope of `from` with its surfaces and
    // symbols as they are now.
    Parser(const Parser& from, std::string piece, const std::string& fileName, int firstLine)
        : tokens_(std::move(piece), fileName, firstLine),
          symbols_(from.symbols_),
          scopes_{from.scopes_.back()},
          surfaces_(from.surfaces_) {
        scene_.options = from.scene_.options;
    }

    Scene Parse();

    TokenStream& Tokens() override { return tokens_; }
    const SymbolTable& Symbols() const override { return symbols_; }
    Surface ParseSurfaceValue(std::string_view usage) override { return *ParseSurface(usage); }
    bool FlipNormals() const override { return scene_.options.flipNormals; }

  private:
    // A reader for the arguments of keyword token `kw`.
    TokenArgReader Args(const Token& kw, const char* usage) {
        return TokenArgReader(*this, kw, usage);
    }

    void ParseTopLevelItem();
    // surface, applysurf, name or an instance; returns false when the next token starts
    // none of them. Instances are appended to `into`.
    bool ParseScopedItem(std::vector<std::shared_ptr<Object>>& into);
    bool ParseCameraItem();
    bool ParseOptionItem();
    void ParseLight();
    void ParseAtmosphere();
    void ParseDefine();
    void ParsePrint();

    bool PeekSurfaceStart();
    std::shared_ptr<const Surface> ParseSurface(std::string_view usage);
    void ParseSurfaceAttribute(TokenArgReader& args, Surface& s);
    void ParseSurfaceDefinition();

    std::shared_ptr<Object> ParseInstance();

    // Parallel runs of primitive statements (see the comment above ParsePrimitiveRun).
    struct RunPiece;
    // Parses a run of primitive statements starting at the next token in pieces on the
    // build loop's threads, appending the objects to `into`; returns false, having read
    // nothing, where a run does not pay or its first statement is not a plain primitive.
    bool ParsePrimitiveRun(std::vector<std::shared_ptr<Object>>& into);
    // The statements of this piece parser's text up to its first one that is not a plain
    // primitive or that reports anything.
    void ParsePiece(RunPiece& piece);

    // `row`: the primitive the next token names.
    std::shared_ptr<Object> ParsePrimitive(const PrimitiveEntry& row);
    std::shared_ptr<Object> ParseAggregate();
    std::shared_ptr<Object> ParseObjectReference();
    void ParseTransforms(TransformList& list);
    std::shared_ptr<Texture> ParseTexture();
    Color ReadIntensity(TokenArgReader& args);

    void SetDepth(const Object* node, NodeDepth d, const Token& at);
    NodeDepth DepthOf(const Object* node) const;

    TokenStream tokens_;
    SymbolTable symbols_;
    Scene scene_;
    // Surface defaults of the open scopes: the top level, then one per open aggregate.
    struct Scope {
        std::shared_ptr<const Surface> current;  // set by applysurf; null: none
    };
    std::vector<Scope> scopes_;
    NameMap<std::shared_ptr<const Surface>> surfaces_;
    // Named objects; a null entry is a name whose definition was discarded (already warned).
    std::unordered_map<std::string, std::shared_ptr<Object>> objects_;
    std::unordered_map<const Object*, NodeDepth> depths_;
    std::vector<std::shared_ptr<Object>> worldChildren_;
    bool advisedOpenCsgOperand_ = false;
    // No parallel run starts before this offset of the text: past the statement that
    // stopped the last run, and a piece further when that run was short (ParsePrimitiveRun).
    size_t nextRunOffset_ = 0;
};

Scene Parser::Parse() {
    while (tokens_.Peek().kind != TokenKind::End) ParseTopLevelItem();
    auto world = std::make_shared<ListAggregate>();
    for (auto& child : worldChildren_) world->AddChild(std::move(child));
    scene_.world = Object::MakeAggregate(world);
    scene_.world->name = "World";
    if (!scene_.world->HasPrimitive())
        Report(Severity::Abort, SourceLocation{}, "Nothing to be rendered");
    return std::move(scene_);
}

void Parser::ParseTopLevelItem() {
    if (ParseCameraItem() || ParseOptionItem()) return;
    const Token& t = tokens_.Peek();
    if (t.IsKeyword("light")) {
        ParseLight();
    } else if (t.IsKeyword("atmosphere")) {
        ParseAtmosphere();
    } else if (t.IsKeyword("define")) {
        ParseDefine();
    } else if (t.IsKeyword("print")) {
        ParsePrint();
    } else if (!ParseScopedItem(worldChildren_)) {
        FailAt(t.Location(), "", "Unexpected " + t.Describe());
    }
}

bool Parser::ParseScopedItem(std::vector<std::shared_ptr<Object>>& into) {
    const Token& t = tokens_.Peek();
    if (t.kind != TokenKind::Keyword) return false;
    const std::string_view k = t.keyword;
    if (k == "surface") {
        ParseSurfaceDefinition();
    } else if (k == "applysurf") {
        tokens_.Next();
        scopes_.back().current = ParseSurface("applysurf surface");
    } else if (k == "name") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "name objname object [transforms] [textures]");
        std::string name = args.ReadName();
        std::shared_ptr<Object> node = ParseInstance();
        if (node) {
            node->name = name;
            scene_.namedObjects.push_back(node);
        }
        objects_[name] = node;  // a later definition shadows an earlier one silently
    } else if (IsPrimitiveKeyword(k) || IsAggregateKeyword(k) || k == "object") {
        if (ParsePrimitiveRun(into)) return true;
        if (std::shared_ptr<Object> node = ParseInstance()) into.push_back(std::move(node));
    } else {
        return false;
    }
    return true;
}

bool Parser::ParseCameraItem() {
    const Token& t = tokens_.Peek();
    if (t.kind != TokenKind::Keyword) return false;
    const std::string_view k = t.keyword;
    Camera& cam = scene_.camera;
    RenderOptions& opt = scene_.options;
    if (k == "eyep") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "eyep x y z");
        cam.eye = args.ReadVector();
        cam.viewStatement = kw.Location();
        if (tokens_.Peek().kind == TokenKind::Keyword) {
            TransformList ignored;
            ParseTransforms(ignored);
            if (!ignored.IsIdentity()) args.Advise("Transformations of eyep are ignored");
        }
    } else if (k == "lookp") {
        Token kw = tokens_.Next();
        cam.lookAt = Args(kw, "lookp x y z").ReadVector();
        cam.viewStatement = kw.Location();
    } else if (k == "up") {
        Token kw = tokens_.Next();
        cam.up = Args(kw, "up x y z").ReadVector();
        cam.viewStatement = kw.Location();
    } else if (k == "fov") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "fov hfov [vfov]");
        cam.hfov = args.ReadNumber();
        if (args.PeekNumber()) cam.vfov = args.ReadNumber();
        if (cam.hfov <= 0 || cam.hfov >= 180)
            args.Fail("The field of view must lie in (0, 180) degrees");
    } else if (k == "aperture") {
        Token kw = tokens_.Next();
        cam.aperture = Args(kw, "aperture radius").ReadNumber();
    } else if (k == "focaldist") {
        Token kw = tokens_.Next();
        cam.focalDist = Args(kw, "focaldist distance").ReadNumber();
    } else if (k == "eyesep") {
        Token kw = tokens_.Next();
        double sep = Args(kw, "eyesep separation").ReadNumber();
        if (!opt.eyeSepSet) cam.eyeSep = sep;
    } else if (k == "screen") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "screen xres yres");
        int x = args.ReadInt(), y = args.ReadInt();
        if (x < 1 || y < 1) args.Fail("Invalid screen resolution");
        const ResourceLimits& limits = Limits();
        if (x > limits.resolutionSide || y > limits.resolutionSide ||
            static_cast<long>(x) * y > limits.resolutionPixels)
            args.Fail(StringPrintf("Screen resolution %dx%d exceeds the limits (%ld per side, %ld "
                                   "pixels)", x, y, limits.resolutionSide, limits.resolutionPixels));
        if (!opt.resolutionSet) opt.xres = x, opt.yres = y;
    } else if (k == "window") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "window xmin xmax ymin ymax");
        int w[4];
        for (int& v : w) v = args.ReadInt();
        if (!opt.windowSet) std::copy(std::begin(w), std::end(w), opt.window);
    } else if (k == "crop") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "crop left right bottom top");
        double c[4];
        for (double& v : c) v = args.ReadNumber();
        if (!opt.cropSet) std::copy(std::begin(c), std::end(c), opt.crop);
    } else {
        return false;
    }
    return true;
}

bool Parser::ParseOptionItem() {
    const Token& t = tokens_.Peek();
    if (t.kind != TokenKind::Keyword) return false;
    const std::string_view k = t.keyword;
    RenderOptions& opt = scene_.options;
    if (k == "sample") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "sample n [jitter | nojitter]");
        int n = args.ReadInt();
        if (n < 1) args.Fail("The sample count must be at least 1");
        if (n > Limits().samplesPerSide)
            args.Fail(StringPrintf("The sample count must be at most %ld", Limits().samplesPerSide));
        if (!opt.samplesSet) opt.samples = n;
        if (args.Accept("jitter")) {
            if (!opt.jitterSet) opt.jitter = true;
        } else if (args.Accept("nojitter")) {
            if (!opt.jitterSet) opt.jitter = false;
        }
    } else if (k == "filter") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "filter box|gauss [width]");
        if (args.Accept("box"))
            opt.filter = FilterKind::Box;
        else if (args.Accept("gauss"))
            opt.filter = FilterKind::Gauss;
        else
            args.FailExpected("'box' or 'gauss'");
        opt.filterWidth = -1;
        if (args.PeekNumber()) {
            opt.filterWidth = args.ReadNumber();
            if (opt.filterWidth <= 0) args.Fail("The filter width must be positive");
        }
    } else if (k == "contrast") {
        Token kw = tokens_.Next();
        Color c = Args(kw, "contrast r g b").ReadColor();
        if (!opt.contrastSet) opt.contrast = c;
    } else if (k == "cutoff") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "cutoff value | cutoff r g b");
        Color c = ReadIntensity(args);
        if (!opt.cutoffSet) opt.cutoff = c;
    } else if (k == "maxdepth") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "maxdepth n");
        int d = args.ReadInt();
        if (d > Limits().rayDepth) {
            args.Warn(StringPrintf("maxdepth %d exceeds the limit; using %ld", d, Limits().rayDepth));
            d = static_cast<int>(Limits().rayDepth);
        }
        if (!opt.maxDepthSet) opt.maxDepth = d;
    } else if (k == "background") {
        Token kw = tokens_.Next();
        opt.background = Args(kw, "background r g b").ReadColor();
    } else if (k == "shadowtransp") {
        tokens_.Next();
        opt.shadowTransparency = !opt.shadowTransparency;
    } else if (k == "outfile") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "outfile filename");
        std::string file = args.ReadFilename();
        if (opt.outFileSet)
            args.Warn("Ignoring output file name");
        else
            opt.outFile = file;
    } else if (k == "report") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "report [verbose] [quiet] [frequency] [filename]");
        if (args.Accept("verbose")) opt.verbose = true;
        if (args.Accept("quiet")) opt.quiet = true;
        if (args.PeekNumber()) {
            int freq = args.ReadInt();
            if (freq < 1) args.Fail("The report frequency must be at least 1");
            if (!opt.reportFreqSet) opt.reportFreq = freq;
        }
        if (args.PeekFilename()) {
            std::string file = args.ReadFilename();
            if (!opt.statsFileSet) opt.statsFile = file;
        }
    } else if (k == "frames") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "frames n");
        int n = args.ReadInt();
        if (n < 1) args.Fail("The number of frames must be at least 1");
        if (!opt.framesSet) opt.frames = n;
    } else if (k == "starttime") {
        Token kw = tokens_.Next();
        opt.startTime = Args(kw, "starttime time").ReadNumber();
    } else if (k == "framelength") {
        Token kw = tokens_.Next();
        opt.frameLength = Args(kw, "framelength length").ReadNumber();
    } else if (k == "shutter") {
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, "shutter length");
        opt.shutter = args.ReadNumber();
        if (opt.shutter < 0) args.Fail("The shutter length must not be negative");
    } else {
        return false;
    }
    return true;
}

Color Parser::ReadIntensity(TokenArgReader& args) {
    double v = args.ReadNumber();
    if (!args.PeekNumber()) return Color(v);
    double g = args.ReadNumber(), b = args.ReadNumber();
    return Color(v, g, b);
}

void Parser::ParseLight() {
    Token kw = tokens_.Next();
    TokenArgReader args = Args(kw,
                               "light intensity ambient | point | directional | extended | "
                               "spot | area ... [noshadow]");
    Color intensity = ReadIntensity(args);
    if (args.Accept("ambient")) {
        scene_.ambientLight = intensity;
        return;
    }
    const Token& type = tokens_.Peek();
    LightList lights;
    if (type.IsKeyword("point")) {
        Token t = tokens_.Next();
        TokenArgReader a = Args(t, "light intensity point x y z [noshadow]");
        lights = CreatePointLight(a, intensity);
    } else if (type.IsKeyword("directional")) {
        Token t = tokens_.Next();
        TokenArgReader a = Args(t, "light intensity directional x y z [noshadow]");
        lights = CreateDirectionalLight(a, intensity);
    } else if (type.IsKeyword("extended")) {
        Token t = tokens_.Next();
        TokenArgReader a = Args(t, "light intensity extended radius x y z [noshadow]");
        lights = CreateExtendedLight(a, intensity);
    } else if (type.IsKeyword("spot")) {
        Token t = tokens_.Next();
        TokenArgReader a = Args(t, "light intensity spot from to coef [inner outer] [noshadow]");
        lights = CreateSpotLight(a, intensity);
    } else if (type.IsKeyword("area")) {
        Token t = tokens_.Next();
        TokenArgReader a = Args(t, "light intensity area p1 p2 usamples p3 vsamples [noshadow]");
        lights = CreateAreaLight(a, intensity);
    } else {
        args.FailExpected("a light type (ambient, point, directional, extended, spot, area)");
    }
    bool noshadow = args.Accept("noshadow");
    for (auto& light : lights) {
        if (noshadow) light->noshadow = true;
        scene_.lights.push_back(light);
    }
}

void Parser::ParseAtmosphere() {
    Token kw = tokens_.Next();
    TokenArgReader args = Args(kw, "atmosphere [index] {fog | mist | fogdeck ...}");
    if (args.PeekNumber()) {
        // The original truncates the index to an integer (spec §6); reals are accepted here.
        double index = args.ReadNumber();
        if (index <= 0) args.Fail("The atmosphere's index of refraction must be positive");
        scene_.atmosphereIndex = index;
    }
    std::vector<AtmosphereEffect> effects;
    while (true) {
        const Token& t = tokens_.Peek();
        AtmosphereEffect e;
        if (t.IsKeyword("fog")) {
            Token k = tokens_.Next();
            TokenArgReader a = Args(k, "fog r g b thinr thing thinb");
            e.kind = AtmosphereEffect::Kind::Fog;
            e.color = a.ReadColor();
            e.thinness = a.ReadColor();
        } else if (t.IsKeyword("mist")) {
            Token k = tokens_.Next();
            TokenArgReader a = Args(k, "mist r g b thinr thing thinb zero scale");
            e.kind = AtmosphereEffect::Kind::Mist;
            e.color = a.ReadColor();
            e.thinness = a.ReadColor();
            e.zero = a.ReadNumber();
            e.scale = a.ReadNumber();
        } else if (t.IsKeyword("fogdeck")) {
            Token k = tokens_.Next();
            TokenArgReader a = Args(k,
                                    "fogdeck altitude offset sx sy sz chaoscale octaves r g b "
                                    "thinr thing thinb");
            e.kind = AtmosphereEffect::Kind::FogDeck;
            e.altitude = a.ReadNumber();
            e.offset = a.ReadNumber();
            e.deckScale = a.ReadVector();
            e.chaoScale = a.ReadNumber();
            e.octaves = a.ReadInt();
            e.color = a.ReadColor();
            e.thinness = a.ReadColor();
        } else {
            break;
        }
        effects.push_back(e);
    }
    scene_.atmosphere = std::move(effects);  // each statement replaces the previous list
}

void Parser::ParseDefine() {
    Token kw = tokens_.Next();
    TokenArgReader args = Args(kw, "define name value");
    Token name = tokens_.Peek();
    args.ReadName();
    ExprPtr value = args.ReadExpression();
    if (!symbols_.Define(std::string(name.text), value))
        FailAt(name.Location(), "", "'" + std::string(name.text) + "' is already defined");
}

void Parser::ParsePrint() {
    Token kw = tokens_.Next();
    double v = Args(kw, "print value").ReadNumber();
    Report(Severity::Warn, kw.Location(), "print: %f", v);
}

bool Parser::PeekSurfaceStart() {
    const Token& t = tokens_.Peek();
    return t.kind == TokenKind::Name || t.IsKeyword("cursurf") || IsSurfaceAttribute(t);
}

std::shared_ptr<const Surface> Parser::ParseSurface(std::string_view usage) {
    const Token& first = tokens_.Peek();  // valid until the token is consumed
    TokenArgReader args(*this, first, usage);
    Surface base;
    if (first.IsKeyword("cursurf")) {
        tokens_.Next();
        const auto& current = scopes_.back().current;
        if (!IsSurfaceAttribute(tokens_.Peek()))
            return current ? current : std::make_shared<const Surface>(Surface::Default());
        base = current ? *current : Surface::Default();
    } else if (first.kind == TokenKind::Name) {
        auto it = surfaces_.find(first.text);
        if (it == surfaces_.end())
            FailAt(first.Location(), "", "Undefined surface '" + std::string(first.text) + "'");
        tokens_.Skip();
        if (!IsSurfaceAttribute(tokens_.Peek())) return it->second;
        base = *it->second;
    } else if (IsSurfaceAttribute(first)) {
        base = Surface::Fresh();
    } else {
        args.FailExpected("a surface");
    }
    auto s = std::make_shared<Surface>(base);
    while (IsSurfaceAttribute(tokens_.Peek())) ParseSurfaceAttribute(args, *s);
    return s;
}

void Parser::ParseSurfaceAttribute(TokenArgReader& args, Surface& s) {
    Token k = tokens_.Next();
    const std::string_view a = k.keyword;
    if (a == "ambient")
        s.ambient = args.ReadColor();
    else if (a == "diffuse")
        s.diffuse = args.ReadColor();
    else if (a == "specular")
        s.specular = args.ReadColor();
    else if (a == "body")
        s.body = args.ReadColor();
    else if (a == "specpow")
        s.specpow = args.ReadNumber();
    else if (a == "extinct")
        s.extinct = args.ReadNumber();
    else if (a == "transp")
        s.transp = args.ReadNumber();
    else if (a == "reflect")
        s.reflect = args.ReadNumber();
    else if (a == "index")
        s.index = args.ReadNumber();
    else if (a == "translu") {
        s.translucency = args.ReadNumber();
        s.translucentColor = args.ReadColor();
        s.translucentPow = args.ReadNumber();
    } else if (a == "noshadow") {
        s.noshadow = true;
    }
}

void Parser::ParseSurfaceDefinition() {
    Token kw = tokens_.Next();
    const char* usage = "surface name [attributes]";
    TokenArgReader args = Args(kw, usage);
    std::string name = args.ReadName();
    std::shared_ptr<const Surface> s = PeekSurfaceStart()
                                           ? ParseSurface(usage)
                                           : std::make_shared<const Surface>(Surface::Fresh());
    // Spec §3.5: checked for named surfaces only.
    if (s->transp > kEpsilon && s->index <= 0)
        args.Fail("Surface '" + name +
                  "' is transparent but its index of refraction is not positive");
    if (surfaces_.count(name)) args.Warn("Redefinition of surface '" + name + "'");
    surfaces_[name] = s;
}

// Parallel runs of primitive statements. A large scene is mostly long runs of primitives
// (the SPD files: 10^5 to 10^6 polygons, spheres or cones in one grid), and parsing them was
// most of its setup. Where a primitive statement starts at least two pieces of text
// (kRunPieceBytes each) before the end, the text ahead is cut into pieces at lines that
// begin with a primitive keyword, and waves of up to kRunPieces pieces are parsed on the build
// loop's threads, each by a parser with a copy of this one's surfaces, symbols and default
// surface, its reports held back (HeldReports). A piece stops at its first statement that
// is not a plain primitive (a row that createsConcurrently, then transforms, no texture),
// that reports anything or fails. The pieces' objects are taken in order up to and
// including the first piece that stopped short of its end, and this parser goes on from
// where that one stopped: whatever reported is parsed again the serial way, so objects,
// their order and every diagnostic are the serial parse's. A cut that is no statement start
// (inside a comment or an implicit block) makes the piece before it stop short, so nothing
// after it is taken. Runs start only while a build loop is installed and the wave's text
// holds no line marker ('#'), so that lines count from the run's first token.

// About 6,000 triangles: a piece's fixed costs (a parser, a copy of its text, a loop index)
// are well under a percent of parsing it.
constexpr size_t kRunPieceBytes = 256 * 1024;
// Pieces per wave: a run's first wave has kRunMinPieces, each wave parsed to its end
// doubles the next up to kRunPieces, enough to keep a few threads busy. A run's end (an
// aggregate's `end`, a named object) wastes the pieces after it in its wave, so at most
// about a third of the run's parallel work when it ends in its first few waves, and the
// ramp keeps short runs between frequent stops from paying for whole waves. Runs of fewer
// than kRunMinPieces pieces do not start.
constexpr size_t kRunPieces = 8;
constexpr size_t kRunMinPieces = 2;

// Whether the word at text[p] (after blanks) spells a keyword whose row createsConcurrently;
// sets `start` to the word's offset.
bool StartsConcurrentPrimitive(const std::string& text, size_t p, size_t& start) {
    while (p < text.size() && (text[p] == ' ' || text[p] == '\t')) ++p;
    size_t end = p;
    while (end < text.size() && text[end] >= 'a' && text[end] <= 'z') ++end;
    if (end == p || end >= text.size() || (text[end] != ' ' && text[end] != '\t')) return false;
    const PrimitiveEntry* row = FindPrimitive(CanonicalKeyword(text.substr(p, end - p)));
    start = p;
    return row && row->createsConcurrently;
}

// The first offset at or after `from` where a line begins with such a keyword, or the end.
size_t NextPieceStart(const std::string& text, size_t from) {
    size_t p = from;
    while (true) {
        const void* nl = p < text.size() ? std::memchr(text.data() + p, '\n', text.size() - p) : nullptr;
        if (!nl) return text.size();
        p = static_cast<size_t>(static_cast<const char*>(nl) - text.data()) + 1;
        size_t start;
        if (StartsConcurrentPrimitive(text, p, start)) return start;
    }
}

struct Parser::RunPiece {
    size_t begin = 0, end = 0;  // offsets in the whole text
    int firstLine = 0;
    std::vector<std::shared_ptr<Object>> objects;
    bool complete = false;      // parsed to its end
    size_t stop = 0;            // else: the offset (in the piece) of the statement it stopped at
    int stopLine = 0;
};

void Parser::ParsePiece(RunPiece& piece) {
    const HeldReports held;
    try {
        while (true) {
            const Token& t = tokens_.Peek();
            if (t.kind == TokenKind::End) {
                piece.complete = true;
                return;
            }
            piece.stop = tokens_.Offset(t);
            piece.stopLine = t.line;
            const PrimitiveEntry* row =
                t.kind == TokenKind::Keyword ? FindPrimitive(t.keyword) : nullptr;
            if (!row || !row->createsConcurrently) return;
            std::shared_ptr<Object> node = ParsePrimitive(*row);
            TransformList transforms;
            ParseTransforms(transforms);
            if (!node || held.Count() > 0 || tokens_.Peek().IsKeyword("texture")) return;
            node->parentFromObject = std::move(transforms);
            piece.objects.push_back(std::move(node));
        }
    } catch (const FatalError&) {
        // Held: the statement at piece.stop is parsed again serially.
    }
}

bool Parser::ParsePrimitiveRun(std::vector<std::shared_ptr<Object>>& into) {
    if (!BuildLoopInstalled()) return false;
    const Token& first = tokens_.Peek();
    const std::string& text = tokens_.Text();
    const size_t runStart = tokens_.Offset(first);
    if (runStart < nextRunOffset_ || text.size() - runStart < kRunMinPieces * kRunPieceBytes)
        return false;
    const PrimitiveEntry* row = FindPrimitive(first.keyword);
    if (!row || !row->createsConcurrently) return false;
    const std::string& fileName = *first.file;
    size_t waveStart = runStart;
    int waveLine = first.line;
    size_t taken = 0;
    // Continues the serial parse at `offset` after the objects taken, if any.
    const auto resumeAt = [&](size_t offset, int line) {
        if (taken == 0) return false;  // the tokens are where they were
        tokens_.SeekTo(offset, line);
        scene_.parallelParsedObjects += taken;
        return true;
    };
    size_t waveSize = kRunMinPieces;  // doubled after each wave parsed to its end
    while (text.size() - waveStart >= kRunMinPieces * kRunPieceBytes) {
        std::vector<RunPiece> pieces(std::min(waveSize, (text.size() - waveStart) / kRunPieceBytes));
        waveSize = std::min(kRunPieces, 2 * waveSize);
        size_t at = waveStart;
        int line = waveLine;
        for (RunPiece& piece : pieces) {
            piece.begin = at;
            piece.end = NextPieceStart(text, at + kRunPieceBytes);
            piece.firstLine = line;
            line += static_cast<int>(std::count(text.begin() + piece.begin, text.begin() + piece.end, '\n'));
            at = piece.end;
        }
        if (const void* marker = std::memchr(text.data() + waveStart, '#', at - waveStart)) {
            nextRunOffset_ = static_cast<size_t>(static_cast<const char*>(marker) - text.data()) + 1;
            break;
        }
        RunBuildLoop(static_cast<long>(pieces.size()), [&](long i) {
            RunPiece& piece = pieces[i];
            Parser pieceParser(*this, text.substr(piece.begin, piece.end - piece.begin), fileName,
                               piece.firstLine);
            pieceParser.ParsePiece(piece);
        });
        for (RunPiece& piece : pieces) {
            taken += piece.objects.size();
            into.insert(into.end(), std::make_move_iterator(piece.objects.begin()),
                        std::make_move_iterator(piece.objects.end()));
            if (!piece.complete) {
                const size_t stop = piece.begin + piece.stop;
                // A run that ended within a piece's length leaves the next piece's length
                // to the serial parser (text of short runs); a longer one is tried again
                // right after the statement that stopped it (long runs between, say,
                // named objects).
                nextRunOffset_ = stop - runStart < kRunPieceBytes ? stop + kRunPieceBytes : stop + 1;
                return resumeAt(stop, piece.stopLine);
            }
        }
        waveStart = at;
        waveLine = line;
    }
    return resumeAt(waveStart, waveLine);
}

std::shared_ptr<Object> Parser::ParseInstance() {
    const Token& t = tokens_.Peek();
    std::shared_ptr<Object> node;
    const PrimitiveEntry* primitive = t.kind == TokenKind::Keyword ? FindPrimitive(t.keyword) : nullptr;
    if (primitive) {
        node = ParsePrimitive(*primitive);
    } else if (t.kind == TokenKind::Keyword && IsAggregateKeyword(t.keyword)) {
        node = ParseAggregate();
    } else if (t.IsKeyword("object")) {
        node = ParseObjectReference();
    } else {
        FailAt(t.Location(), "", "Expected an object, found " + t.Describe());
    }
    TransformList transforms;
    ParseTransforms(transforms);
    std::vector<std::shared_ptr<const Texture>> textures;
    while (tokens_.Peek().IsKeyword("texture"))
        if (std::shared_ptr<Texture> tex = ParseTexture()) textures.push_back(std::move(tex));
    if (!node) return nullptr;
    node->parentFromObject = std::move(transforms);
    node->SetTextures(std::move(textures));
    return node;
}

std::shared_ptr<Object> Parser::ParsePrimitive(const PrimitiveEntry& row) {
    Token kw = tokens_.Next();
    std::shared_ptr<const Surface> surface;
    bool surfaceFollows = PeekSurfaceStart();
    // heightfield's own argument is a file name, which may lex as a NAME too: a NAME is the
    // surface only when another file name follows it (as the original's grammar decides).
    if (surfaceFollows && kw.keyword == "heightfield" && tokens_.Peek().kind == TokenKind::Name) {
        TokenKind after = tokens_.Peek(1).kind;
        surfaceFollows = after == TokenKind::Name || after == TokenKind::Filename;
    }
    if (surfaceFollows && row.startsArguments && tokens_.Peek().kind == TokenKind::Name &&
        row.startsArguments(std::string(tokens_.Peek().text)))
        surfaceFollows = false;
    if (surfaceFollows) surface = ParseSurface(row.usage);
    TokenArgReader args(*this, kw, row.usage);
    std::shared_ptr<Primitive> prim = row.create(args);
    if (!prim) return nullptr;  // degenerate: the factory has warned
    std::shared_ptr<Object> node = Object::MakePrimitive(std::move(prim));
    // Spec §3.5 quirk: a height field without its own surface ignores applysurf.
    if (surface)
        node->surface = surface;
    else if (kw.keyword != "heightfield")
        node->surface = scopes_.back().current;
    SetDepth(node.get(), NodeDepth{0, 1}, kw);
    return node;
}

std::shared_ptr<Object> Parser::ParseAggregate() {
    Token kw = tokens_.Next();
    const std::string k(kw.keyword);
    const char* usage =
        k == "grid" ? "grid nx ny nz {object} end" : "list|union|intersect|difference {object} end";
    TokenArgReader args = Args(kw, usage);
    if (static_cast<int>(scopes_.size()) > kMaxModelDepth)
        args.Fail(StringPrintf("Model nesting too deep (the limit is %d levels)", kMaxModelDepth));
    int n[3] = {1, 1, 1};
    if (k == "grid")
        for (int& v : n) v = args.ReadInt();

    // The body is a new scope whose default surface starts empty (spec §3.5).
    scopes_.emplace_back();
    std::vector<std::shared_ptr<Object>> children;
    while (!tokens_.Peek().IsKeyword("end")) {
        const Token& t = tokens_.Peek();
        if (t.kind == TokenKind::End) args.Fail("Missing 'end' for this '" + k + "'");
        if (ParseScopedItem(children)) continue;
        // (None of these starts a scoped item.)
        if (t.kind == TokenKind::Keyword && IsTopLevelOnly(t.keyword))
            FailAt(t.Location(), "", "'" + std::string(t.text) + "' is not allowed inside an aggregate");
        FailAt(t.Location(), "", "Expected an object or 'end', found " + t.Describe());
    }
    tokens_.Next();
    scopes_.pop_back();

    if (children.empty()) {
        args.Warn("Null object defined");
        return nullptr;
    }
    std::shared_ptr<Aggregate> agg;
    if (k == "list") {
        agg = std::make_shared<ListAggregate>();
    } else if (k == "grid") {
        if (n[0] < 1 || n[1] < 1 || n[2] < 1) {
            args.Warn("Grid voxel counts must be at least 1; grid discarded");
            return nullptr;
        }
        if (static_cast<double>(n[0]) * n[1] * n[2] > static_cast<double>(Limits().gridVoxels))
            args.Fail(StringPrintf("A grid of %dx%dx%d voxels exceeds the limit of %ld voxels", n[0],
                                   n[1], n[2], Limits().gridVoxels));
        agg = std::make_shared<GridAggregate>(n[0], n[1], n[2]);
    } else {
        CsgAggregate::Op op = k == "union"       ? CsgAggregate::Op::Union
                              : k == "intersect" ? CsgAggregate::Op::Intersect
                                                 : CsgAggregate::Op::Difference;
        agg = std::make_shared<CsgAggregate>(op);
    }
    NodeDepth depth;
    for (auto& child : children) {
        NodeDepth d = DepthOf(child.get());
        depth.model = std::max(depth.model, d.model + 1);
        depth.total = std::max(depth.total, d.total + 1);
        agg->AddChild(std::move(child));  // (a grid of a million: no count updates)
    }
    if (auto* csg = dynamic_cast<CsgAggregate*>(agg.get())) {
        if (!csg->HasTwoOperands()) {
            args.Warn(StringPrintf("CSG '%s' needs exactly two operands, not %zu; discarded",
                                   k.c_str(), csg->Children().size()));
            return nullptr;
        }
        for (const auto& child : csg->Children()) {
            if (!child->IsClosed() && !advisedOpenCsgOperand_) {
                advisedOpenCsgOperand_ = true;
                args.Advise("A CSG operand is not a closed object; results may be wrong");
            }
        }
    }
    std::shared_ptr<Object> node = Object::MakeAggregate(std::move(agg));
    node->surface = scopes_.back().current;  // the enclosing scope's default
    SetDepth(node.get(), depth, kw);
    return node;
}

std::shared_ptr<Object> Parser::ParseObjectReference() {
    Token kw = tokens_.Next();
    const char* usage = "object [surface] objname [transforms] [textures]";
    // In `object A B` the first name is a surface; in `object A` it is the object.
    const Token& first = tokens_.Peek();
    bool hasSurface = first.IsKeyword("cursurf") || IsSurfaceAttribute(first);
    if (first.kind == TokenKind::Name) {
        const Token& second = tokens_.Peek(1);
        hasSurface = second.kind == TokenKind::Name || IsSurfaceAttribute(second);
    }
    std::shared_ptr<const Surface> surface;
    if (hasSurface) surface = ParseSurface(usage);
    TokenArgReader args = Args(kw, usage);
    Token nameTok = tokens_.Peek();
    std::string name = args.ReadName();
    auto it = objects_.find(name);
    if (it == objects_.end()) FailAt(nameTok.Location(), "", "Undefined object '" + name + "'");
    if (!it->second) return nullptr;  // its definition was discarded (already warned)
    std::shared_ptr<Object> node = Object::MakeInstance(it->second);
    node->surface = surface ? surface : scopes_.back().current;
    NodeDepth target = DepthOf(it->second.get());
    SetDepth(node.get(), NodeDepth{target.model, target.total + 1}, kw);
    return node;
}

void Parser::ParseTransforms(TransformList& list) {
    while (true) {
        const Token& t = tokens_.Peek();
        TransformKind kind;
        int count;
        const char* usage;
        if (t.IsKeyword("translate")) {
            kind = TransformKind::Translate, count = 3, usage = "translate dx dy dz";
        } else if (t.IsKeyword("scale")) {
            kind = TransformKind::Scale, count = 3, usage = "scale sx sy sz";
        } else if (t.IsKeyword("rotate")) {
            kind = TransformKind::Rotate, count = 4, usage = "rotate ax ay az degrees";
        } else if (t.IsKeyword("transform")) {
            kind = TransformKind::General, count = 9,
            usage = "transform a b c d e f g h i [tx ty tz]";
        } else {
            return;
        }
        Token kw = tokens_.Next();
        TokenArgReader args = Args(kw, usage);
        std::vector<ExprPtr> params;
        for (int i = 0; i < count; ++i) params.push_back(args.ReadExpression());
        if (kind == TransformKind::General && args.PeekNumber())
            for (int i = 0; i < 3; ++i) params.push_back(args.ReadExpression());

        bool animated = std::any_of(params.begin(), params.end(),
                                    [](const ExprPtr& e) { return e->IsTimeVarying(); });
        if (animated) {
            // Re-evaluated whenever the list is evaluated at a time (spec §3.15); a step
            // that is invalid at some time is skipped by TransformList.
            list.AppendAnimated([kind, params](double time) {
                std::vector<double> v;
                for (const ExprPtr& e : params) v.push_back(e->Evaluate(time));
                return BuildTransform(kind, v);
            });
            continue;
        }
        std::vector<double> v;
        for (const ExprPtr& e : params) {
            if (!std::isfinite(e->Value()))
                args.Fail("Transformation parameter is not a finite number");
            v.push_back(e->Value());
        }
        std::optional<Transform> step = BuildTransform(kind, v);
        if (step) {
            list.Append(*step);
        } else if (kind == TransformKind::Rotate) {
            args.Warn("Degenerate rotation axis; rotation ignored");
        } else {
            args.Fail("Singular matrix");
        }
    }
}

std::shared_ptr<Texture> Parser::ParseTexture() {
    tokens_.Skip();  // `texture`
    const Token& type = tokens_.Peek();
    const TextureEntry* row = nullptr;
    if (type.kind == TokenKind::Keyword) {
        for (const TextureEntry& e : TextureRegistry())
            if (type.keyword == e.keyword) row = &e;
    }
    if (!row) FailAt(type.Location(), "", "Unknown texture type " + type.Describe());
    Token typeTok = tokens_.Next();
    TokenArgReader args(*this, typeTok, row->usage);
    std::shared_ptr<Texture> texture = row->create(args);
    TransformList transforms;
    ParseTransforms(transforms);
    if (texture) texture->transform = std::move(transforms);
    return texture;
}

void Parser::SetDepth(const Object* node, NodeDepth d, const Token& at) {
    if (d.model > kMaxModelDepth || d.total > kMaxNodeDepth) {
        FailAt(at.Location(), "",
               StringPrintf("Model nesting too deep (the limit is %d levels)", kMaxModelDepth));
    }
    // Primitives have the default depth; not storing them keeps the map small.
    if (d.model == 0 && d.total == 1)
        depths_.erase(node);
    else
        depths_[node] = d;
}

NodeDepth Parser::DepthOf(const Object* node) const {
    auto it = depths_.find(node);
    return it == depths_.end() ? NodeDepth{} : it->second;
}

}  // namespace

Scene ParseSceneText(std::string text, const std::string& fileName,
                     const RenderOptions& options) {
    return Parser(std::move(text), fileName, options).Parse();
}

Scene ParseScene(const ParseInput& input, const RenderOptions& options) {
    SourceText src = ReadSceneSource(input.path, input.useCpp, input.cppArgs, input.extraDefines);
    return ParseSceneText(std::move(src.text), src.fileName, options);
}

}  // namespace rs
