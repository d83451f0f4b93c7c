// The shading model of spec §3.6–3.8: surfaces and textures at the winning hit, lights with
// (transparent) shadows, reflection, refraction through a stack of media, and atmosphere.
#pragma once

#include "libcommon/random.h"
#include "libobj/hit.h"
#include "libshade/scene.h"
#include "libsurf/surface.h"

namespace rs {

// Per-sample state shared by an eye ray and all rays it spawns.
struct SampleState {
    int sampleNumber = -1;  // dithered sample number (§3.3), −1 when none
    int samplesPerSide = 1;
    Rng* rng = nullptr;
};

class Tracer {
  public:
    // For a scene whose world is prepared for the frame (Object::PrepareFrame).
    explicit Tracer(const Scene& scene);

    // Colour seen along an eye ray (unit direction); `hit` tells whether it hit anything
    // (the sample's alpha).
    Color TraceEye(const Ray& ray, SampleState& sample, bool& hit) const;

    // Everything shading needs at a hit, in world space.
    struct ShadingPoint {
        Vec3 point;
        Vec3 normal;     // shading normal, unit, facing the ray
        Vec3 geometric;  // geometric normal, unit, facing the ray
        bool smooth = false;
        bool entering = false;
        Surface surface;
    };
    // Evaluates the hit's surface (with textures when `textured`) and normals.
    ShadingPoint Evaluate(const Ray& ray, const HitRecord& hit, bool textured,
                          SampleState& sample) const;

  private:
    struct Medium {
        double index;
        double extinct;
    };
    static constexpr int kMaxMedia = 64;
    struct MediumStack {
        Medium media[kMaxMedia];
        int size = 0;
    };

    Color Trace(const Ray& ray, int depth, const Color& weight, MediumStack& media,
                SampleState& sample, double& hitDist, bool& hit) const;
    Color Shade(const Ray& ray, const HitRecord& hit, int depth, const Color& weight,
                MediumStack& media, SampleState& sample) const;
    // Light arriving at `p` from a light sample after occluders (black when blocked).
    // `footprint`: the beam's width at p (ray.h); the shadow ray's narrows to 0 at the light.
    // `lightIndex` and `depth` (the shaded ray's) pick the shadow cache's entry.
    Color LightThroughShadows(const Vec3& p, double time, const Color& light,
                              const Vec3& dir, double dist, double footprint, int lightIndex,
                              int depth, SampleState& sample) const;
    // Whether anything lies on the shadow ray's segment (tMin, dist) when every occluder is
    // opaque, asking the shadow cache's entry for (lightIndex, depth) first.
    bool OpaqueOccluded(const Ray& ray, double tMin, double dist, int lightIndex,
                        int depth) const;
    // This thread's shadow cache entry for a light and ray depth (null: no caching).
    const Object** ShadowCacheEntry(int lightIndex, int depth) const;
    // Whether the entry's cached primitive blocks the segment (counted as a cache hit).
    bool CachedBlockerAnswers(const Object** entry, const Ray& ray, double tMin,
                              double dist) const;
    Color Atmosphere(const Ray& ray, double dist, const Color& c) const;
    const Surface& UntexturedSurface(const HitRecord& hit) const;

    const Scene& scene_;
    const RenderOptions& options_;
    Surface defaultSurface_ = Surface::Default();
    // No occluder can let light through (no transparent surface in the scene, or shadows
    // through transparent objects are off): shadow rays ask only whether anything is hit.
    bool opaqueShadows_;
    // The shadow cache (spec §3.7; off with -s): the opaque primitive that blocked the
    // last shadow ray of each light at each ray depth, kept per thread (tracer.cpp) under
    // this tracer's serial, so entries are never read once the scene they name is gone.
    uint64_t serial_;  // unique among the tracers of this process
    // maxDepth + 1 (ray depths 0..maxDepth) when on; 0 when off (-s) or when there are no
    // lights or too many lights times depths (tracer.cpp).
    int cacheDepths_ = 0;
};

}  // namespace rs
