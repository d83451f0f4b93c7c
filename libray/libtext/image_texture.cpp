#include "libtext/image_texture.h"

#include <cmath>
#include <map>
#include <mutex>
#include <utility>

#include "libtext/texture_space.h"

namespace rs {
namespace {

// Tile sizes below this mean "no limit" on that axis.
constexpr double kNoTile = 0.001;
// Alpha below this leaves the surface alone; at or above the upper one the image is opaque.
constexpr double kTransparentAlpha = 0.001;
constexpr double kOpaqueAlpha = 0.999;

struct ComponentName {
    const char* word;
    ImageComponent component;
};

// `reflective` and `transparent` are the lexer's aliases of `reflect` and `transp`.
constexpr ComponentName kComponentNames[] = {
    {"ambient", ImageComponent::Ambient}, {"diffuse", ImageComponent::Diffuse},
    {"specular", ImageComponent::Specular}, {"body", ImageComponent::Body},
    {"reflect", ImageComponent::Reflect},   {"reflective", ImageComponent::Reflect},
    {"transp", ImageComponent::Transp},     {"transparent", ImageComponent::Transp},
    {"specpow", ImageComponent::Specpow},   {"bump", ImageComponent::Bump},
    {"index", ImageComponent::Index},
};

inline int Wrap(int i, int n) {
    i %= n;
    return i < 0 ? i + n : i;
}

}  // namespace

ImageTexture::ImageTexture(std::shared_ptr<const Image> image, ImageTextureOptions options)
    : image_(std::move(image)), options_(std::move(options)) {
    if (!options_.mapping) options_.mapping = std::make_shared<UVMapping>();
}

bool ImageTexture::ChannelsSuit(ImageComponent component, int channels) {
    switch (component) {
        case ImageComponent::Color:
        case ImageComponent::Ambient:
        case ImageComponent::Diffuse:
        case ImageComponent::Specular:
        case ImageComponent::Body:
            return channels >= 1 && channels <= 4;
        default:
            return channels == 1 || channels == 2;
    }
}

bool ImageTexture::Covers(double tileU, double tileV, double u, double v) {
    bool limitU = std::fabs(tileU) >= kNoTile, limitV = std::fabs(tileV) >= kNoTile;
    if (!limitU && !limitV) return true;
    if (limitU && limitV && tileU < 0 && tileV < 0) {
        return !(u > 0 && u < -tileU && v > 0 && v < -tileV);
    }
    if (limitU && tileU > 0 && (u < 0 || u > tileU)) return false;
    if (limitV && tileV > 0 && (v < 0 || v > tileV)) return false;
    if (limitU && tileU < 0 && u > 0 && u < -tileU) return false;
    if (limitV && tileV < 0 && v > 0 && v < -tileV) return false;
    return true;
}

std::shared_ptr<const Image> ImageTexture::LoadShared(const std::string& path,
                                                      std::string& error) {
    static std::mutex mutex;
    static std::map<std::string, std::shared_ptr<const Image>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto found = cache.find(path);
    if (found != cache.end()) return found->second;
    std::optional<Image> image = ReadImage(path, error);
    if (!image) return nullptr;
    if (image->width < 1 || image->height < 1) {
        error = "image file \"" + path + "\" has no pixels";
        return nullptr;
    }
    auto shared = std::make_shared<const Image>(std::move(*image));
    cache.emplace(path, shared);
    return shared;
}

std::shared_ptr<Texture> ImageTexture::Create(ArgReader& args) {
    std::string path = args.ReadDataFilename();
    ImageTextureOptions options;
    for (;;) {
        if (args.Accept("component")) {
            bool known = false;
            for (const ComponentName& c : kComponentNames) {
                if (args.Accept(c.word)) {
                    options.component = c.component;
                    known = true;
                    break;
                }
            }
            if (!known) {
                args.Fail("expected ambient, diffuse, specular, body, reflect, transp, "
                          "specpow, bump or index after component");
            }
        } else if (args.Accept("tile")) {
            options.tileU = args.ReadNumber();
            options.tileV = args.ReadNumber();
        } else if (args.Accept("textsurf")) {
            options.textSurface = args.ReadSurface();
        } else if (args.Accept("range")) {
            options.hi = args.ReadNumber();
            options.lo = args.ReadNumber();
        } else if (args.Accept("smooth")) {
            options.smooth = true;
        } else if (args.Accept("map")) {
            options.mapping = ReadMapping(args);
        } else {
            break;
        }
    }
    std::string error;
    std::shared_ptr<const Image> image = LoadShared(path, error);
    if (!image) args.Fail(error);
    if (!ChannelsSuit(options.component, image->channels)) {
        args.Fail("image \"" + path + "\" must have a single colour channel for this component");
    }
    return std::make_shared<ImageTexture>(std::move(image), std::move(options));
}

ImageTexture::Texel ImageTexture::Fetch(int x, int y) const {
    x = Wrap(x, image_->width);
    y = Wrap(y, image_->height);
    // Texture row y is the y-th stored row: the original reads the first row of a file as
    // row 0 (v = 0) (shared/reference/README.md), so an mtv or PNG file, stored top row
    // first, maps with its top row at v = 0, as the references were rendered.
    const uint8_t* px = image_->Row(y) + x * image_->channels;
    constexpr double kScale = 1.0 / 255.0;
    switch (image_->channels) {
        case 1:
            return {px[0] * kScale, px[0] * kScale, px[0] * kScale, 1};
        case 2:
            return {px[0] * kScale, px[0] * kScale, px[0] * kScale, px[1] * kScale};
        case 3:
            return {px[0] * kScale, px[1] * kScale, px[2] * kScale, 1};
        default:
            return {px[0] * kScale, px[1] * kScale, px[2] * kScale, px[3] * kScale};
    }
}

ImageTexture::Texel ImageTexture::Lookup(double u, double v) const {
    double x = u * image_->width, y = v * image_->height;
    int ix = static_cast<int>(x), iy = static_cast<int>(y);
    if (!options_.smooth) return Fetch(ix, iy);
    double fx = x - ix, fy = y - iy;
    Texel t00 = Fetch(ix, iy), t10 = Fetch(ix + 1, iy);
    Texel t01 = Fetch(ix, iy + 1), t11 = Fetch(ix + 1, iy + 1);
    auto mix = [&](double a00, double a10, double a01, double a11) {
        return (1 - fy) * ((1 - fx) * a00 + fx * a10) + fy * ((1 - fx) * a01 + fx * a11);
    };
    return {mix(t00.r, t10.r, t01.r, t11.r), mix(t00.g, t10.g, t01.g, t11.g),
            mix(t00.b, t10.b, t01.b, t11.b), mix(t00.alpha, t10.alpha, t01.alpha, t11.alpha)};
}

void ImageTexture::Apply(TextureContext& ctx, Surface& surface) const {
    SurfaceUV s = options_.mapping->Map(ctx);
    const TextureSpace space(transform, ctx.time);
    Vec2 uv = space.UV(s.uv);
    if (!Covers(options_.tileU, options_.tileV, uv.u, uv.v)) return;
    double u = uv.u - std::floor(uv.u), v = uv.v - std::floor(uv.v);

    if (options_.component == ImageComponent::Bump) {
        // Finite differences one pixel right and one stored row further, unsmoothed.
        int ix = static_cast<int>(u * image_->width), iy = static_cast<int>(v * image_->height);
        Texel h0 = Fetch(ix, iy);
        if (HasAlpha() && h0.alpha < kTransparentAlpha) return;
        double fu = options_.lo + (Fetch(ix + 1, iy).r - h0.r) * (options_.hi - options_.lo);
        double fv = options_.lo + (Fetch(ix, iy + 1).r - h0.r) * (options_.hi - options_.lo);
        space.Derivatives(s.dpdu, s.dpdv, ctx.normal);
        ctx.normal = BumpNormal(ctx.normal, s.dpdu, s.dpdv, fu, fv);
        return;
    }

    Texel t = Lookup(u, v);
    if (HasAlpha() && t.alpha < kTransparentAlpha) return;
    Color raw(t.r, t.g, t.b);
    Color ranged(Range(t.r), Range(t.g), Range(t.b));
    bool useTextSurface = options_.component == ImageComponent::Color && options_.textSurface;
    Surface m = useTextSurface ? *options_.textSurface : surface;
    switch (options_.component) {
        case ImageComponent::Color:
            m.ambient *= raw;
            m.diffuse *= raw;
            m.specular *= raw;
            break;
        case ImageComponent::Ambient: m.ambient *= ranged; break;
        case ImageComponent::Diffuse: m.diffuse *= ranged; break;
        case ImageComponent::Specular: m.specular *= ranged; break;
        case ImageComponent::Body: m.body *= ranged; break;
        case ImageComponent::Reflect: m.reflect *= ranged.r; break;
        case ImageComponent::Transp: m.transp *= ranged.r; break;
        case ImageComponent::Specpow: m.specpow *= ranged.r; break;
        case ImageComponent::Index: m.index *= ranged.r; break;
        case ImageComponent::Bump: break;
    }
    if (HasAlpha() && t.alpha < kOpaqueAlpha) {
        surface = BlendSurfaces(surface, 1 - t.alpha, m, t.alpha);
    } else {
        surface = m;
    }
}

}  // namespace rs
