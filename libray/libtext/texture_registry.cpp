#include "libtext/texture_registry.h"

#include "libtext/blotch.h"
#include "libtext/bump.h"
#include "libtext/checker.h"
#include "libtext/cloud.h"
#include "libtext/fbm.h"
#include "libtext/fbmbump.h"
#include "libtext/gloss.h"
#include "libtext/image_texture.h"
#include "libtext/marble.h"
#include "libtext/mount.h"
#include "libtext/patches_texture.h"
#include "libtext/sky.h"
#include "libtext/stripe.h"
#include "libtext/windy.h"
#include "libtext/wood.h"

namespace rs {

const std::vector<TextureEntry>& TextureRegistry() {
    static const std::vector<TextureEntry> entries = {
        {"checker", &CheckerTexture::Create, "texture checker SURFACE"},
        {"blotch", &BlotchTexture::Create, "texture blotch MIX SURFACE"},
        {"bump", &BumpTexture::Create, "texture bump SCALE"},
        {"marble", &MarbleTexture::Create, "texture marble [COLORMAP]"},
        {"fbm", &FBmTexture::Create,
         "texture fbm OFFSET SCALE H LAMBDA OCTAVES THRESHOLD [COLORMAP]"},
        {"fbmbump", &FBmBumpTexture::Create, "texture fbmbump OFFSET SCALE H LAMBDA OCTAVES"},
        {"wood", &WoodTexture::Create, "texture wood"},
        {"gloss", &GlossTexture::Create, "texture gloss GLOSSINESS"},
        {"cloud", &CloudTexture::Create,
         "texture cloud SCALE H LAMBDA OCTAVES CTHRESH LTHRESH TRANSCALE"},
        {"sky", &SkyTexture::Create, "texture sky SCALE H LAMBDA OCTAVES CTHRESH LTHRESH"},
        {"stripe", &StripeTexture::Create, "texture stripe SURFACE WIDTH BUMP [map MAPPING]"},
        {"windy", &WindyTexture::Create,
         "texture windy SCALE WINDSCALE CHAOSCALE BUMPSCALE OCTAVES TSCALE HSCALE OFFSET"},
        {"mount", &MountTexture::Create, "texture mount COLORMAP TURBULENCE SLOPE"},
        {"image", &ImageTexture::Create,
         "texture image FILE [component C] [tile U V] [textsurf SURFACE] [range HI LO] "
         "[smooth] [map MAPPING]"},
        {"patches", &PatchesTexture::Create, "texture patches"},
    };
    return entries;
}

}  // namespace rs
