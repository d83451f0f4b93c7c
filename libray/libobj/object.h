// A node of the scene graph: a primitive, an aggregate, or an instance of a named node
// ("object NAME"), with its own transform list, optional surface and textures.
//
// Nodes form a DAG: a named node may be instanced many times. Each node's transform maps
// the node's object space to its parent's space (parentFromObject).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "libcommon/transform.h"
#include "libobj/aggregate.h"
#include "libobj/hit.h"
#include "libobj/primitive.h"

namespace rs {

struct Surface;
class Texture;

class Object {
  public:
    enum class Kind : uint8_t { Primitive, Aggregate, Instance };

    static std::shared_ptr<Object> MakePrimitive(std::shared_ptr<Primitive> p);
    static std::shared_ptr<Object> MakeAggregate(std::shared_ptr<Aggregate> a);
    static std::shared_ptr<Object> MakeInstance(std::shared_ptr<Object> of);

    Kind kind() const { return kind_; }
    // What the node holds; null when it is of another kind.
    const Primitive* primitive() const { return Is(Kind::Primitive) ? PrimitiveNode() : nullptr; }
    Primitive* primitive() { return Is(Kind::Primitive) ? PrimitiveNode() : nullptr; }
    const Aggregate* aggregate() const { return Is(Kind::Aggregate) ? AggregateNode() : nullptr; }
    const Object* instanceOf() const { return Is(Kind::Instance) ? InstanceNode() : nullptr; }
    Object* instanceOf() { return Is(Kind::Instance) ? InstanceNode() : nullptr; }

    std::string name;  // the `name` it was defined under, for reports; may be empty
    TransformList parentFromObject;
    std::shared_ptr<const Surface> surface;  // null: inherit from the nearest ancestor

    // The node's own textures, applied in written order (most nodes have none).
    std::span<const std::shared_ptr<const Texture>> Textures() const {
        if (!textures_) return {};
        return *textures_;
    }
    void SetTextures(std::vector<std::shared_ptr<const Texture>> textures);

    // Nearest hit with tMin < t < tMax for a ray given in the PARENT's space. On success
    // shrinks tMax, fills `hit`, appends this node to hit.path and returns true.
    // Primitives without transforms (most leaves) take an inline path, so aggregates call
    // the primitive's test directly.
    bool Intersect(const Ray& rayParent, double tMin, double& tMax, HitRecord& hit) const {
        if (kind_ == Kind::Primitive && parentFromObject.IsIdentity())
            return IntersectPrimitive(rayParent, tMin, tMax, hit);
        return IntersectGeneral(rayParent, tMin, tMax, hit);
    }

    // Whether anything below this node has a hit with tMin < t < tMax, for a ray in the
    // PARENT's space: the same answer as Intersect's return value, but a search may stop at
    // the first hit it finds (shadow rays through opaque scenes).
    bool Occluded(const Ray& rayParent, double tMin, double tMax) const {
        return Occluded(rayParent, tMin, tMax, nullptr);
    }
    // The same question, also naming what blocks: when the answer is true and `blocker` is
    // not null, *blocker is either a primitive node P, this one or one below it, with
    // P.Occluded(rayParent, tMin, tMax) true for this same ray (every node from this one
    // down to P, P excluded, is a list, grid or instance without a transform, so P's parent
    // space is this node's), or null: the hit is a CSG one or lies below a transformed
    // aggregate or instance, whose test would cost about as much as the whole search. A
    // shadow cache tests P first on the next shadow ray. On false, *blocker is unspecified.
    bool Occluded(const Ray& rayParent, double tMin, double tMax, const Object** blocker) const {
        if (kind_ == Kind::Primitive && parentFromObject.IsIdentity())
            return OccludedPrimitive(rayParent, tMin, tMax, blocker);
        return OccludedGeneral(rayParent, tMin, tMax, blocker);
    }

    // The primitive node of a hit found by a search from the root of hit.path when every
    // node above it on the path is a list, grid or instance without a transform, so that
    // the primitive's own Occluded, given the root's ray, finds that hit again (the
    // blocker of Occluded's contract); null otherwise, or when the path was cut short.
    static const Object* PlainPathPrimitive(const HitRecord& hit);

    // Bounds in the parent's space for the current frame (union over the shutter interval
    // when animated) and whether the node is bounded at all (planes are not).
    const Bounds3& BoundsInParent() const { return boundsInParent_; }
    bool IsBounded() const { return bounded_; }
    bool IsClosed() const;
    // The box pre-test IntersectGeneral applies to an aggregate or instance node, a cull:
    // false only when the ray (in the node's object space) misses the node's box over
    // (tMin, tMax). Always true for unbounded nodes, and, without clipping, for a ray that
    // starts strictly inside the box: the secondary and shadow rays leaving the scene's
    // surfaces mostly do, and for them the clip (three divisions) would almost always
    // admit. (A ray that starts inside but whose segment lies beyond the box, as a
    // transparent shadow's later passes may, is admitted and searched in vain.)
    bool BoxAdmits(const Ray& rayObject, double tMin, double tMax) const {
        // bounded_ is false for aggregates holding unbounded children, see PrepareFrame.
        if (!bounded_) return true;
        Count(kBoundsTests);
        return boundsObject_.ContainsStrictly(rayObject.origin) ||
               boundsObject_.ClipRay(rayObject, tMin, tMax);
    }

    // Prepares this node and everything below it for a frame: lets primitives rebuild,
    // rebuilds aggregates, recomputes bounds. Safe to call more than once per frame on a
    // shared node (the work is done once per distinct frameTime).
    void PrepareFrame(double frameTime, double shutter);
    // Whether this node or one below it (for an instance, below its target) has a surface
    // of its own with transp >= kEpsilon; known once the node is prepared (PrepareFrame
    // works it out on its pass over the nodes, so asking never walks a large scene again).
    bool HasTransparentSurfaceBelow() const { return transparentBelow_; }

    // Number of primitives below this node (instances count their target's).
    long PrimitiveCount() const;
    // Whether there is a primitive below this node (PrimitiveCount() > 0, stopping at the
    // first: the parser asks it of every scene, whose world may hold millions).
    bool HasPrimitive() const;
    // What the node is, for reports: the primitive's type ("Sphere"), the aggregate's
    // keyword ("grid"), or "instance".
    std::string TypeName() const;

    // Only the Make functions can make the key (one allocation holds the node and its count).
    class Key {
        friend class Object;
        Key() = default;
    };
    Object(Key, Kind k) : kind_(k) {}

  private:
    // PrepareFrame of an aggregate node's children: in a large set, the primitives without
    // frame work of their own on the build's threads, then anything else one at a time in
    // order. Returns what the aggregate needs to know of them.
    struct ChildrenSummary {
        bool allBounded = true;
        bool anyTransparent = false;  // some child's HasTransparentSurfaceBelow()
        void Add(const Object& child) {
            allBounded = allBounded && child.bounded_;
            anyTransparent = anyTransparent || child.transparentBelow_;
        }
    };
    ChildrenSummary PrepareChildren(double frameTime, double shutter);

    // Intersect for a primitive node, with the ray already in the node's object space.
    bool IntersectPrimitive(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const {
        Count(counters_->tests);
        PrimitiveHit ph;
        const Primitive* primitive = PrimitiveNode();
        if (!primitive->Intersect(ray, tMin, tMax, ph)) return false;
        Count(counters_->hits);
        tMax = ph.t;
        hit.prim = ph;
        hit.primitive = primitive;
        hit.path[0] = this;
        hit.pathLength = 1;
        hit.enterOverride = -1;
        return true;
    }
    bool IntersectGeneral(const Ray& rayParent, double tMin, double& tMax, HitRecord& hit) const;
    bool OccludedPrimitive(const Ray& ray, double tMin, double tMax, const Object** blocker) const {
        Count(counters_->tests);
        PrimitiveHit ph;
        if (!PrimitiveNode()->Intersect(ray, tMin, tMax, ph)) return false;
        Count(counters_->hits);
        if (blocker) *blocker = this;
        return true;
    }
    bool OccludedGeneral(const Ray& rayParent, double tMin, double tMax,
                         const Object** blocker) const;
    // Whether a blocker named below this node is one for this node's parent space too (the
    // plain nodes of Occluded's contract): no transform, so the nodes below see the same
    // ray, and not CSG, whose hits are not simply its children's.
    bool PassesBlockerNames() const {
        return parentFromObject.IsIdentity() &&
               !(Is(Kind::Aggregate) && !AggregateNode()->HitsAreChildHits());
    }
    // Room for a mapped ray, not written unless a transform maps one into it (most nodes
    // have none, and a Ray's defaults are nine stores per search through the node).
    union RayStorage {
        RayStorage() {}
        Ray ray;
    };
    // The ray in this node's object space: rayParent itself without a transform, else
    // mapped into `storage`.
    const Ray& ObjectRay(const Ray& rayParent, RayStorage& storage) const {
        if (parentFromObject.IsIdentity()) return rayParent;
        storage.ray = parentFromObject.IsAnimated()
                          ? parentFromObject.At(rayParent.time).InverseRay(rayParent)
                          : parentFromObject.Static().InverseRay(rayParent);
        return storage.ray;
    }

    static const CounterId kBoundsTests;

    // The held primitive, aggregate or instanced node, by kind_. One owner for the three
    // kinds, and fields ordered for packing: a large mesh has one node per triangle, and
    // its nodes' memory (first touched while parsing) is a good part of the setup's cost.
    bool Is(Kind k) const { return kind_ == k; }
    Primitive* PrimitiveNode() const { return static_cast<Primitive*>(node_.get()); }
    Aggregate* AggregateNode() const { return static_cast<Aggregate*>(node_.get()); }
    Object* InstanceNode() const { return static_cast<Object*>(node_.get()); }

    std::shared_ptr<void> node_;
    const IntersectionCounters* counters_ = nullptr;  // the primitive's, looked up once
    std::unique_ptr<const std::vector<std::shared_ptr<const Texture>>> textures_;  // null: none
    Bounds3 boundsObject_;   // bounds in the node's own space (for the ray pre-test)
    Bounds3 boundsInParent_;
    double preparedFor_ = -1e300;
    Kind kind_;
    bool bounded_ = false;
    bool transparentBelow_ = false;
};

}  // namespace rs
