// `image FILE {imgopt}` (spec §3.13): modulates one surface field, or bumps the normal,
// from an image looked up at the mapped (u, v).
//
// Orientation: v = 0 is the FIRST STORED row of the file, u = 0 its left column. PNG and
// mtv files store the top row first, so their top row lies at v = 0, exactly as the
// original's mtv build reads them (the reference images were made that way). The texture
// transform acts on (u, v).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "libcommon/arg_reader.h"
#include "libimage/image.h"
#include "libtext/mapping.h"
#include "libtext/texture.h"

namespace rs {

// Which field an image modulates. Color multiplies ambient, diffuse and specular by the raw
// pixel; the four colour components accept 1- or 3-channel images and use the range; the
// scalar ones (reflect … index) and bump need a 1-channel (grey) image.
enum class ImageComponent {
    Color, Ambient, Diffuse, Specular, Body, Reflect, Transp, Specpow, Bump, Index
};

struct ImageTextureOptions {
    ImageComponent component = ImageComponent::Color;
    double hi = 1, lo = 0;    // `range hi lo`: a pixel value x means lo + x·(hi − lo)
    bool smooth = false;      // bilinear interpolation, wrapping at the edges
    double tileU = 0, tileV = 0;  // `tile`: see ImageTexture::Covers
    std::optional<Surface> textSurface;  // `textsurf`: base surface (Color component only)
    std::shared_ptr<const Mapping> mapping;  // null: `map uv`
};

class ImageTexture : public Texture {
  public:
    // `image` must hold at least one pixel and suit the component (see
    // ChannelsSuit); Create checks both.
    ImageTexture(std::shared_ptr<const Image> image, ImageTextureOptions options);
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

    // Whether an image with `channels` (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA) can feed
    // the component.
    static bool ChannelsSuit(ImageComponent component, int channels);
    // Whether the tile settings apply the image at (u, v) (spec §3.13 `tile`): |t| < 0.001
    // on both axes repeats forever; t > 0 limits that axis to [0, t]; t < 0 excludes
    // (0, −t) on that axis, and when both are negative only the rectangle
    // (0, −tu)×(0, −tv) is excluded.
    static bool Covers(double tileU, double tileV, double u, double v);

    // Loads an image once per path; later calls share it. Thread-safe. On failure returns
    // null and sets `error`.
    static std::shared_ptr<const Image> LoadShared(const std::string& path,
                                                   std::string& error);

  private:
    struct Texel {
        double r, g, b, alpha;
    };
    Texel Fetch(int x, int y) const;  // x, y wrapped; y = 0 is the first stored row
    Texel Lookup(double u, double v) const;
    bool HasAlpha() const { return image_->channels == 2 || image_->channels == 4; }
    double Range(double x) const { return options_.lo + x * (options_.hi - options_.lo); }

    std::shared_ptr<const Image> image_;
    ImageTextureOptions options_;
};

}  // namespace rs
