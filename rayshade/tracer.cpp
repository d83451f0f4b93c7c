#include "rayshade/tracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <vector>

#include "libcommon/constants.h"
#include "libcommon/stats.h"
#include "libobj/hit_classify.h"
#include "libobj/object.h"
#include "libtext/noise.h"
#include "libtext/texture.h"

namespace rs {

namespace {

const CounterId kEyeRays = RegisterCounter("eye rays");
const CounterId kShadowRays = RegisterCounter("shadow rays");
const CounterId kReflectedRays = RegisterCounter("reflected rays");
const CounterId kRefractedRays = RegisterCounter("refracted rays");
const CounterId kHitRays = RegisterCounter("hit rays");
const CounterId kShadowHits = RegisterCounter("shadow hits");
// Shadow rays a cached blocker answered, and those an opaque occluder blocked without it.
const CounterId kShadowCacheHits = RegisterCounter("shadow cache hits");
const CounterId kShadowCacheMisses = RegisterCounter("shadow cache misses");

// One thread's shadow cache entries: blockers[lightIndex * depths + depth] is the opaque
// primitive that blocked that light's last shadow ray from a hit at that depth, or null
// (the last ray was not blocked, or not by a primitive the world's ray can test directly,
// see Object::Occluded). The entries are hints: a cached primitive is tested on the same
// segment and only a blocking answer is taken from it, so images do not depend on which
// thread rendered what or in which order; only the counters and the time do.
struct ShadowCacheEntries {
    uint64_t owner = 0;  // the serial of the Tracer the entries belong to; 0: none
    std::vector<const Object*> blockers;
};
thread_local ShadowCacheEntries tShadowCache;

std::atomic<uint64_t> gNextTracerSerial{1};

// Above this many entries (lights times depths) a scene gets no shadow cache: one entry
// per light and depth is kept per thread, and such a scene's lights are not worth caching.
constexpr size_t kMaxShadowCacheEntries = size_t{1} << 20;
// Normals that arrived non-finite or zero and were replaced (see Tracer::Evaluate); printed
// by -v when non-zero. The numerics tests require it to stay zero.
const CounterId kBadNormals = RegisterCounter("Non-finite or zero normals replaced");

bool AnyAbove(const Color& c, const Color& threshold) {
    return c.r > threshold.r || c.g > threshold.g || c.b > threshold.b;
}

// Fraction left after `dist` through a medium whose colour halves every `halfDist`
// (spec §3.8 att()).
double Attenuation(double dist, double halfDist) {
    if (halfDist < kEpsilon) return 0;
    double q = std::log(0.5) * dist / halfDist;
    return q < -10 ? 0 : std::exp(q);
}

// x^e for the specular and translucency exponents (x in (0, 1]): binary powering when e is
// a whole number up to 1024 (nearly every surface: specpow 20), a few multiplications
// instead of a std::pow call, and within a few ulp of it.
double HighlightPower(double x, double e) {
    if (!(e >= 0 && e <= 1024 && e == std::floor(e))) return std::pow(x, e);
    double result = 1;
    for (unsigned n = static_cast<unsigned>(e); n != 0; n >>= 1) {
        if (n & 1) result *= x;
        x *= x;
    }
    return result;
}

// Heckbert's refraction: false on total internal reflection.
bool Refract(const Vec3& d, Vec3 n, double mu, Vec3& out) {
    double c1 = -Dot(d, n);
    if (c1 < 0) {
        n = -n;
        c1 = -c1;
    }
    double c2sq = 1 - mu * mu * (1 - c1 * c1);
    if (c2sq < 0) return false;
    out = Normalize(d * mu + n * (mu * c1 - std::sqrt(c2sq)));
    return true;
}

// The path walk of a textured hit: maps the primitive-space point and normals up the hit
// path (nodeTransforms[i] is node i's transform, null for identity) and applies the textures
// of the nodes up to path[lastTextured] to `surface` and the shading normal, each in that
// node's parent space. n and ng arrive in the primitive's space and leave in world space.
// Kept apart from Evaluate: its context is large, and most hits have no textures.
void ApplyPathTextures(const Ray& ray, const HitRecord& hit,
                       const Transform* const* nodeTransforms, int lastTextured,
                       const Ray& rayPrimitive, const Vec3& pPrimitive,
                       const Vec3& geometricPrimitive, const SampleState& sample,
                       Surface& surface, Vec3& n, Vec3& ng) {
    TextureContext ctx;
    ctx.primitive = hit.primitive;
    ctx.primitiveHit = hit.prim;
    ctx.pointPrimitive = pPrimitive;
    ctx.facingNormalPrimitive =
        Dot(rayPrimitive.dir, geometricPrimitive) > 0 ? -geometricPrimitive : geometricPrimitive;
    ctx.rayPrimitive = rayPrimitive;
    ctx.time = ray.time;
    ctx.sampleNumber = sample.sampleNumber;
    ctx.samplesPerSide = sample.samplesPerSide;
    ctx.rng = sample.rng;
    Vec3 p = pPrimitive;
    for (int i = 0; i < hit.pathLength; ++i) {
        const bool texturing = i <= lastTextured;
        if (nodeTransforms[i]) {
            const Transform& t = *nodeTransforms[i];
            n = Normalize(t.ApplyNormal(n));
            ng = Normalize(t.ApplyNormal(ng));
            if (texturing) {
                p = t.ApplyPoint(p);
                ctx.nodeFromPrimitive = ctx.nodeFromPrimitive.Then(t);
            }
        }
        if (!texturing || hit.path[i]->Textures().empty()) continue;
        ctx.point = p;
        ctx.normal = n;
        ctx.geometricNormal = ng;
        for (const auto& texture : hit.path[i]->Textures()) texture->Apply(ctx, surface);
        n = ctx.normal;
    }
}

// Whether the normals point along the ray direction `dir` (all in the primitive's space), so
// that shading flips them to face the ray: for interpolated normals the geometric normal
// decides when the two disagree (see Evaluate).
bool FacesAway(const Vec3& dir, const SurfaceNormals& normals) {
    const double dn = Dot(dir, normals.shading);
    const double dg = Dot(dir, normals.geometric);
    return (normals.smooth && ((dn > 0) != (dg > 0))) ? dg > 0 : dn > 0;
}

// Evaluate's `entering` alone (for an occluder without textures, whose surface is the
// untextured one): the ray mapped to the primitive as Evaluate maps it, and the primitive's
// normals there, nothing else.
bool EntersAsShaded(const Ray& ray, const HitRecord& hit) {
    if (hit.enterOverride >= 0) return hit.enterOverride == 1;
    const Ray rayPrimitive = RayInPrimitiveSpace(ray, hit);
    const Vec3 pPrimitive = rayPrimitive.At(hit.t());
    return !FacesAway(rayPrimitive.dir, hit.primitive->Normal(pPrimitive, hit.prim));
}

}  // namespace

Tracer::Tracer(const Scene& scene)
    : scene_(scene),
      options_(scene.options),
      opaqueShadows_(!options_.shadowTransparency ||
                     (defaultSurface_.transp < kEpsilon && !scene.world->HasTransparentSurfaceBelow())),
      serial_(gNextTracerSerial.fetch_add(1)) {
    // Entries for depths 0..maxDepth of every light, counted in size_t (maxDepth may be
    // INT_MAX for a library caller).
    const size_t depths = static_cast<size_t>(std::max(0, options_.maxDepth)) + 1;
    if (options_.shadowCache && !scene.lights.empty() &&
        depths <= kMaxShadowCacheEntries / scene.lights.size())
        cacheDepths_ = static_cast<int>(depths);
}

Color Tracer::TraceEye(const Ray& ray, SampleState& sample, bool& hit) const {
    Count(kEyeRays);
    MediumStack media;
    double dist = 0;
    return Trace(ray, 0, Color(1), media, sample, dist, hit);
}

Color Tracer::Trace(const Ray& ray, int depth, const Color& weight, MediumStack& media,
                    SampleState& sample, double& hitDist, bool& hit) const {
    HitRecord record;
    double tMax = kFar;
    Color c;
    hit = scene_.world->Intersect(ray, kEpsilon, tMax, record);
    if (hit) {
        Count(kHitRays);
        hitDist = record.t();
        c = Shade(ray, record, depth, weight, media, sample);
    } else {
        hitDist = kFar;
        c = options_.background;
    }
    if (media.size == 0 && !scene_.atmosphere.empty()) c = Atmosphere(ray, hitDist, c);
    return c;
}

const Surface& Tracer::UntexturedSurface(const HitRecord& hit) const {
    for (int i = 0; i < hit.pathLength; ++i)
        if (hit.path[i]->surface) return *hit.path[i]->surface;
    return defaultSurface_;
}

Tracer::ShadingPoint Tracer::Evaluate(const Ray& ray, const HitRecord& hit, bool textured,
                                      SampleState& sample) const {
    // Transforms along the path at the ray's time; path[0] is the primitive's node. Static
    // lists are referenced, animated ones evaluated into `animated`. Textures are applied
    // up to path[lastTextured]; beyond it only the normals still need mapping.
    // (No default-constructed Transform arrays here: this runs for every shaded hit.)
    const Transform* nodeTransforms[HitRecord::kMaxPath];
    std::vector<Transform> animated;
    int lastTextured = -1;
    for (int i = 0; i < hit.pathLength; ++i) {
        if (textured && !hit.path[i]->Textures().empty()) lastTextured = i;
        const TransformList& list = hit.path[i]->parentFromObject;
        if (list.IsIdentity()) {
            nodeTransforms[i] = nullptr;
        } else if (list.IsAnimated()) {
            if (animated.empty()) animated.reserve(hit.pathLength);  // keeps pointers stable
            animated.push_back(list.At(ray.time));
            nodeTransforms[i] = &animated.back();
        } else {
            nodeTransforms[i] = &list.Static();
        }
    }
    // The ray in the primitive's space, mapped down the path node by node as
    // Object::Intersect mapped it (so the hit point is the one that was found).
    Ray rayPrimitive = ray;
    for (int i = hit.pathLength - 1; i >= 0; --i)
        if (nodeTransforms[i]) rayPrimitive = nodeTransforms[i]->InverseRay(rayPrimitive);
    const Vec3 pPrimitive = rayPrimitive.At(hit.t());
    const SurfaceNormals normals = hit.primitive->Normal(pPrimitive, hit.prim);

    // The record is built only at the end, from finished parts: default-constructing it
    // first would clear its whole Surface per hit just to overwrite it.
    Surface surface = UntexturedSurface(hit);
    Vec3 n = normals.shading, ng = normals.geometric;
    if (lastTextured >= 0) {
        ApplyPathTextures(ray, hit, nodeTransforms, lastTextured, rayPrimitive, pPrimitive,
                          normals.geometric, sample, surface, n, ng);
    } else {
        for (int i = 0; i < hit.pathLength; ++i) {
            if (!nodeTransforms[i]) continue;
            n = Normalize(nodeTransforms[i]->ApplyNormal(n));
            ng = Normalize(nodeTransforms[i]->ApplyNormal(ng));
        }
    }
    // Face the ray (double-sided shading). For interpolated normals the geometric normal
    // decides when the two disagree. As in the original, the side is decided by the normals
    // before texturing (spec §3.6: they are made to face the ray, then textured), so a bump
    // that tilts the shading normal away from the viewer is kept, not mirrored back (the
    // bevels of `stripe` and every other bump). A dot product with the ray has the same sign
    // in every space along the path (normals map with the inverse transpose), so the test
    // is made in the primitive's space.
    const bool flip = FacesAway(rayPrimitive.dir, normals);
    if (flip) {
        n = -n;
        ng = -ng;
    }
    // Numerical guard, six finiteness tests per hit: a normal that overflowed or vanished
    // (extreme scale factors, degenerate geometry) must not carry NaN into the shading, so
    // the geometric normal falls back to facing the ray and the shading normal to it.
    if (!IsFinite(ng) || LengthSquared(ng) == 0) [[unlikely]] {
        Count(kBadNormals);
        ng = -ray.dir;
    }
    if (!IsFinite(n) || LengthSquared(n) == 0) [[unlikely]] {
        Count(kBadNormals);
        n = ng;
    }
    return {.point = ray.At(hit.t()),
            .normal = n,
            .geometric = ng,
            .smooth = normals.smooth,
            .entering = hit.enterOverride >= 0 ? hit.enterOverride == 1 : !flip,
            .surface = surface};
}

Color Tracer::Shade(const Ray& ray, const HitRecord& hit, int depth, const Color& weight,
                    MediumStack& media, SampleState& sample) const {
    const ShadingPoint sp = Evaluate(ray, hit, true, sample);
    const Surface& s = sp.surface;
    const Vec3& n = sp.normal;

    Color c = s.ambient * scene_.ambientLight;
    const Vec3 mirror = ray.dir + n * (2 * -Dot(ray.dir, n));
    // The beam's width at the hit (ray.h). Spawned rays start with it; reflected and
    // refracted rays keep the incoming spread (exact for flat interfaces, finer than the
    // true beam for convex ones, coarser only near the focus of a concave one), and shadow
    // rays narrow to a point at the light.
    const double width = ray.footprintWidth + ray.footprintSpread * hit.t();
    auto spawned = [&](const Vec3& dir) {
        Ray r{sp.point, dir, ray.time};
        r.footprintWidth = width;
        r.footprintSpread = ray.footprintSpread;
        return r;
    };

    // Lights are evaluated in reverse order of definition, as the original stores them.
    for (auto it = scene_.lights.rbegin(); it != scene_.lights.rend(); ++it) {
        const Light& light = **it;
        const int lightIndex = static_cast<int>(it - scene_.lights.rbegin());
        LightSample ls;
        if (!light.Sample(sp.point, sample.sampleNumber, sample.samplesPerSide, *sample.rng, ls))
            continue;
        double cosTheta = Dot(ls.shadeDir, n);
        if (sp.smooth && cosTheta <= 0 && Dot(ls.shadeDir, sp.geometric) > 0)
            cosTheta = Dot(ls.shadeDir, sp.geometric);
        bool noShadow = s.noshadow || light.noshadow || options_.noShadows;
        if (cosTheta > 0) {
            Color li = noShadow ? ls.color
                                : LightThroughShadows(sp.point, ray.time, ls.color, ls.shadowDir,
                                                      ls.shadowDist, width, lightIndex, depth,
                                                      sample);
            if (li == Color{}) continue;
            c += s.diffuse * li * cosTheta;
            double cosAlpha = Dot(mirror, ls.shadeDir);
            if (s.specpow >= kEpsilon && cosAlpha > 0)
                c += s.specular * li * HighlightPower(cosAlpha, s.specpow);
        } else if (s.translucency >= kEpsilon) {
            // Light from behind the surface. The original scales the whole colour
            // accumulated so far by τ (spec §3.6); we scale only this light's share, the
            // intended behaviour (no shipped scene uses translucency).
            Color li = noShadow ? ls.color
                                : LightThroughShadows(sp.point, ray.time, ls.color, ls.shadowDir,
                                                      ls.shadowDist, width, lightIndex, depth,
                                                      sample);
            if (li == Color{}) continue;
            Color share = s.translucentColor * li * (-cosTheta);
            double cosAlpha = -Dot(mirror, ls.shadeDir);
            if (s.translucentPow >= kEpsilon && cosAlpha > 0)
                share += s.body * li * HighlightPower(cosAlpha, s.translucentPow);
            c += share * s.translucency;
        }
    }

    if (depth >= options_.maxDepth) return c;

    Color reflectWeight = s.specular * s.reflect;
    if (s.transp > kEpsilon) {
        Color transmitWeight = s.body * s.transp;
        if (AnyAbove(transmitWeight * weight, options_.cutoff)) {
            // Indices on each side: entering pushes the surface's medium, leaving pops it.
            MediumStack inner;  // a copy of the media in use (not of all kMaxMedia slots)
            inner.size = media.size;
            std::copy_n(media.media, media.size, inner.media);
            double fromIndex, toIndex, extinct;
            if (sp.entering) {
                fromIndex = media.size ? media.media[media.size - 1].index : scene_.atmosphereIndex;
                toIndex = s.index;
                if (inner.size < kMaxMedia) inner.media[inner.size++] = {s.index, s.extinct};
                extinct = s.extinct;
            } else {
                if (inner.size > 0) --inner.size;
                fromIndex = s.index;
                toIndex = inner.size ? inner.media[inner.size - 1].index : scene_.atmosphereIndex;
                extinct = inner.size ? inner.media[inner.size - 1].extinct : 1.0;
            }
            Vec3 dir;
            if (Refract(ray.dir, n, fromIndex / toIndex, dir)) {
                Count(kRefractedRays);
                double dist = 0;
                bool hitAny = false;
                Color t = Trace(spawned(dir), depth + 1, weight * transmitWeight,
                                inner, sample, dist, hitAny);
                double fade = extinct == 1.0 ? 1.0 : std::pow(extinct, dist);
                c += transmitWeight * t * fade;
            } else {
                reflectWeight += transmitWeight;  // total internal reflection
            }
        }
    }
    if (reflectWeight.AnyAbove(kEpsilon) && AnyAbove(reflectWeight * weight, options_.cutoff)) {
        Count(kReflectedRays);
        double dist = 0;
        bool hitAny = false;
        c += reflectWeight * Trace(spawned(mirror), depth + 1, weight * reflectWeight,
                                   media, sample, dist, hitAny);
    }
    return c;
}

const Object** Tracer::ShadowCacheEntry(int lightIndex, int depth) const {
    if (depth >= cacheDepths_) return nullptr;  // depths count from 0; none when off
    ShadowCacheEntries& cache = tShadowCache;
    if (cache.owner != serial_) {
        cache.owner = serial_;
        cache.blockers.assign(scene_.lights.size() * static_cast<size_t>(cacheDepths_), nullptr);
    }
    return &cache.blockers[static_cast<size_t>(lightIndex) * cacheDepths_ + depth];
}

bool Tracer::CachedBlockerAnswers(const Object** entry, const Ray& ray, double tMin,
                                  double dist) const {
    // The cached primitive's parent space is the world's (Object::Occluded's contract).
    if (entry == nullptr || *entry == nullptr || !(*entry)->Occluded(ray, tMin, dist)) return false;
    Count(kShadowCacheHits);
    return true;
}

bool Tracer::OpaqueOccluded(const Ray& ray, double tMin, double dist, int lightIndex,
                            int depth) const {
    const Object** entry = ShadowCacheEntry(lightIndex, depth);
    if (entry == nullptr) return scene_.world->Occluded(ray, tMin, dist);
    if (CachedBlockerAnswers(entry, ray, tMin, dist)) return true;
    const Object* blocker = nullptr;
    const bool blocked = scene_.world->Occluded(ray, tMin, dist, &blocker);
    // A ray that found nothing forgets the entry: the next blocked ray is likely in another
    // shadow, cast by another object.
    *entry = blocked ? blocker : nullptr;
    if (blocked) Count(kShadowCacheMisses);
    return blocked;
}

Color Tracer::LightThroughShadows(const Vec3& p, double time, const Color& light,
                                  const Vec3& dir, double dist, double footprint,
                                  int lightIndex, int depth, SampleState& sample) const {
    Count(kShadowRays);
    Ray ray{p, dir, time};
    ray.footprintWidth = footprint;
    ray.footprintSpread = std::isfinite(dist) && dist > 0 ? -footprint / dist : 0;
    Color c = light;
    double tMin = kShadowEpsilon;
    if (opaqueShadows_) {
        // Every occluder is opaque, so the light is blocked exactly when anything lies on
        // the segment: the search may stop at the first hit it finds.
        if (!OpaqueOccluded(ray, tMin, dist, lightIndex, depth)) return c;
        Count(kShadowHits);
        return {};
    }
    // A cached primitive was found opaque through its path, so if it lies on the segment
    // the loop below ends black too, at it or at a transparent occluder before it that
    // absorbs everything. (The loop alone would miss it only behind a transparent surface
    // closer than kShadowEpsilon, which it steps over.)
    const Object** entry = ShadowCacheEntry(lightIndex, depth);
    if (CachedBlockerAnswers(entry, ray, tMin, dist)) {
        Count(kShadowHits);
        return {};
    }
    if (entry != nullptr) *entry = nullptr;  // set again below if an opaque occluder blocks
    bool previousEntering = false;
    double previousT = 0, previousExtinct = 1;
    // Each pass moves past one transparent occluder; a bound keeps pathological stacks of
    // coincident transparent surfaces from looping for long.
    constexpr int kMaxOccluders = 1024;
    for (int pass = 0; pass < kMaxOccluders; ++pass) {
        HitRecord hit;
        double tMax = dist;
        if (!scene_.world->Intersect(ray, tMin, tMax, hit)) return c;
        if (!options_.shadowTransparency || UntexturedSurface(hit).transp < kEpsilon) {
            if (entry != nullptr) {
                *entry = Object::PlainPathPrimitive(hit);
                Count(kShadowCacheMisses);
            }
            Count(kShadowHits);
            return {};
        }
        if (previousEntering)
            c *= std::pow(previousExtinct, hit.t() - previousT - kEpsilon);
        // What the occluder passes on: its surface with textures applied and whether the ray
        // enters it. With no textures on its path the surface is the untextured one, and
        // only the side of the hit is needed (EntersAsShaded; a CSG hit carries it).
        const bool textured = std::any_of(hit.path, hit.path + hit.pathLength,
                                          [](const Object* o) { return !o->Textures().empty(); });
        const Surface* surface = &UntexturedSurface(hit);
        bool entering;
        std::optional<ShadingPoint> sp;
        if (textured) {
            sp = Evaluate(ray, hit, true, sample);
            surface = &sp->surface;
            entering = sp->entering;
        } else {
            entering = EntersAsShaded(ray, hit);
        }
        c *= surface->body * surface->transp;
        if (!c.AnyAbove(kEpsilon)) {
            Count(kShadowHits);
            return {};
        }
        previousEntering = entering;
        previousT = hit.t();
        previousExtinct = surface->extinct;
        tMin = hit.t() + kShadowEpsilon;
    }
    Count(kShadowHits);
    return {};
}

Color Tracer::Atmosphere(const Ray& ray, double dist, const Color& in) const {
    Color c = in;
    // Effects apply in reverse order of listing. Each one blends towards its colour by
    // att(d, T) per channel (spec §3.8) over an effective distance d.
    for (auto it = scene_.atmosphere.rbegin(); it != scene_.atmosphere.rend(); ++it) {
        const AtmosphereEffect& e = *it;
        double effectiveDist = dist;
        Color halfDist = e.thinness;
        if (e.kind == AtmosphereEffect::Kind::Mist) {
            // Mean density along the ray of exp(zero − h/scale) between both end heights.
            double oz = ray.origin.z, pz = ray.At(dist).z;
            double delta = (pz - oz) / e.scale;
            double rho = std::fabs(delta) > kEpsilon
                             ? (std::exp(e.zero - oz / e.scale) - std::exp(e.zero - pz / e.scale)) / delta
                             : std::exp(e.zero - pz / e.scale);
            effectiveDist = dist * rho;
        } else if (e.kind == AtmosphereEffect::Kind::FogDeck) {
            // The deck is the plane z = altitude; a ray crossing it in (ε, dist] is fogged
            // over the rest of its length, dist − tCross, with the density ρ found at the
            // crossing. This is the original's intent; its parallelism test used integer
            // abs() and skipped nearly every ray.
            if (std::fabs(ray.dir.z) < kEpsilon) continue;
            double tCross = (e.altitude - ray.origin.z) / ray.dir.z;
            if (tCross < kEpsilon || tCross > dist) continue;
            Vec3 p = MulComponents(ray.At(tCross), e.deckScale);
            // ρ = offset + chaoscale·Σ_{k<octaves} 2^−k |Noise(2^k p)|.
            double sum = 0, weight = 1;
            for (int k = 0; k < e.octaves; ++k) {
                sum += weight * std::fabs(Noise(p));
                weight *= 0.5;
                p *= 2.0;
            }
            double rho = e.offset + e.chaoScale * sum;
            if (rho < kEpsilon) continue;  // thinness T/ρ is infinite: no fog
            halfDist = e.thinness * (1 / rho);
            effectiveDist = dist - tCross;
        }
        double ar = Attenuation(effectiveDist, halfDist.r);
        double ag = Attenuation(effectiveDist, halfDist.g);
        double ab = Attenuation(effectiveDist, halfDist.b);
        c = {ar * c.r + (1 - ar) * e.color.r, ag * c.g + (1 - ag) * e.color.g,
             ab * c.b + (1 - ab) * e.color.b};
    }
    return c;
}

}  // namespace rs
