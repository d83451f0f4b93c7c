// Textures modify a hit's surface and shading normal (spec §3.12).
//
// At a hit, the renderer walks from the primitive's node up to (excluding) the World; at
// each node it expresses the hit in that node's PARENT space (the space its own transforms
// produce) and applies the node's textures in written order. Each texture then maps the
// point by the inverse of its own transform list before evaluating its pattern.
#pragma once

#include "libcommon/random.h"
#include "libcommon/transform.h"
#include "libobj/primitive.h"
#include "libsurf/surface.h"

namespace rs {

// Everything a texture may look at, for one node of the hit path.
struct TextureContext {
    Vec3 point;            // hit point in the node's parent space
    Vec3 normal;           // unit shading normal in the same space; textures may modify it
    Vec3 geometricNormal;  // unit geometric normal in the same space (read only)

    // The hit primitive, for `map uv` and the cloud texture.
    const Primitive* primitive = nullptr;
    PrimitiveHit primitiveHit;
    Vec3 pointPrimitive;          // hit point in the primitive's object space
    Vec3 facingNormalPrimitive;   // geometric normal there, flipped to face the ray
    Ray rayPrimitive;             // the incident ray in the primitive's object space
    Transform nodeFromPrimitive;  // carries primitive-space vectors into `point`'s space

    double time = 0;        // ray time (animated texture transforms)
    int sampleNumber = -1;  // the eye ray's sample number (gloss), −1 when none
    int samplesPerSide = 1; // n of the n×n sampling grid
    Rng* rng = nullptr;     // per-pixel random stream
};

class Texture {
  public:
    virtual ~Texture() = default;

    // Applies the texture: may replace or modify `surface` and ctx.normal.
    virtual void Apply(TextureContext& ctx, Surface& surface) const = 0;

    // The texture's own transform list (maps texture space to node space).
    TransformList transform;
};

}  // namespace rs
