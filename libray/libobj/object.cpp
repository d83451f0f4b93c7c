#include "libobj/object.h"

#include <algorithm>

#include "libcommon/constants.h"
#include "libcommon/parallel_build.h"
#include "libsurf/surface.h"

namespace rs {

const CounterId Object::kBoundsTests = RegisterCounter("bounding box tests");

std::shared_ptr<Object> Object::MakePrimitive(std::shared_ptr<Primitive> p) {
    auto o = std::make_shared<Object>(Key{}, Kind::Primitive);
    o->counters_ = &p->Counters();
    o->node_ = std::move(p);
    return o;
}

std::shared_ptr<Object> Object::MakeAggregate(std::shared_ptr<Aggregate> a) {
    auto o = std::make_shared<Object>(Key{}, Kind::Aggregate);
    o->node_ = std::move(a);
    return o;
}

std::shared_ptr<Object> Object::MakeInstance(std::shared_ptr<Object> of) {
    auto o = std::make_shared<Object>(Key{}, Kind::Instance);
    o->node_ = std::move(of);
    return o;
}

void Object::SetTextures(std::vector<std::shared_ptr<const Texture>> textures) {
    if (textures.empty()) {
        textures_.reset();
    } else {
        textures_ = std::make_unique<const std::vector<std::shared_ptr<const Texture>>>(
            std::move(textures));
    }
}

bool Object::IntersectGeneral(const Ray& rayParent, double tMin, double& tMax,
                              HitRecord& hit) const {
    // The rest of the search with the ray in this node's object space. Called on the
    // parent's ray itself when there is no transform, so no object-space Ray is built then.
    const auto inObjectSpace = [&](const Ray& ray) {
        bool found = false;
        switch (kind_) {
            case Kind::Primitive:
                // IntersectPrimitive adds this node to the path.
                return IntersectPrimitive(ray, tMin, tMax, hit);
            case Kind::Aggregate:
            case Kind::Instance:
                if (!BoxAdmits(ray, tMin, tMax)) return false;
                found = kind_ == Kind::Aggregate ? AggregateNode()->Intersect(ray, tMin, tMax, hit)
                                                 : InstanceNode()->Intersect(ray, tMin, tMax, hit);
                break;
        }
        if (found && hit.pathLength < HitRecord::kMaxPath) hit.path[hit.pathLength++] = this;
        return found;
    };
    RayStorage storage;
    return inObjectSpace(ObjectRay(rayParent, storage));
}

bool Object::OccludedGeneral(const Ray& rayParent, double tMin, double tMax,
                             const Object** blocker) const {
    RayStorage storage;
    const Ray& ray = ObjectRay(rayParent, storage);
    if (kind_ == Kind::Primitive) return OccludedPrimitive(ray, tMin, tMax, blocker);
    // Nothing is named unless a primitive below names itself and this node passes the name
    // on. The search stops at the first child that blocks, and that child's call is the
    // last to write *blocker (a child that did not block wrote before it), so the name
    // left is the blocking chain's.
    if (blocker) *blocker = nullptr;
    const Object** below = blocker != nullptr && PassesBlockerNames() ? blocker : nullptr;
    if (!BoxAdmits(ray, tMin, tMax)) return false;
    return kind_ == Kind::Aggregate ? AggregateNode()->Occluded(ray, tMin, tMax, below)
                                    : InstanceNode()->Occluded(ray, tMin, tMax, below);
}

const Object* Object::PlainPathPrimitive(const HitRecord& hit) {
    if (hit.pathLength < 1 || hit.pathLength >= HitRecord::kMaxPath) return nullptr;
    for (int i = 1; i < hit.pathLength; ++i)
        if (!hit.path[i]->PassesBlockerNames()) return nullptr;
    return hit.path[0];
}

bool Object::IsClosed() const {
    switch (kind_) {
        case Kind::Primitive: return PrimitiveNode()->IsClosed();
        case Kind::Aggregate: return AggregateNode()->IsClosed();
        case Kind::Instance: return InstanceNode()->IsClosed();
    }
    return false;
}

Object::ChildrenSummary Object::PrepareChildren(double frameTime, double shutter) {
    const std::vector<std::shared_ptr<Object>>& children = AggregateNode()->Children();
    // Below this many, one thread prepares them faster than a loop is handed out (a
    // primitive child costs about 40 ns: its transform, its box, the box in the parent).
    constexpr size_t kParallelChildren = 16384;
    constexpr size_t kChunk = 4096;
    ChildrenSummary summary;
    if (children.size() < kParallelChildren || !BuildLoopInstalled()) {
        for (const auto& child : children) {
            child->PrepareFrame(frameTime, shutter);
            summary.Add(*child);
        }
        return summary;
    }
    // A primitive node has this aggregate as its only parent (instances share only their
    // targets), so a chunk that prepares only primitives without frame work writes only its
    // own children's nodes. The other children of each chunk wait in `later` and are
    // prepared after the loop, in order (they may share nodes below them). Summaries are a
    // conjunction and a disjunction: the same in any order.
    const size_t chunks = (children.size() + kChunk - 1) / kChunk;
    std::vector<ChildrenSummary> chunkSummaries(chunks);
    std::vector<std::vector<size_t>> later(chunks);
    RunBuildLoopInChunks(children.size(), kChunk, [&](size_t begin, size_t end) {
        const size_t chunk = begin / kChunk;
        for (size_t i = begin; i < end; ++i) {
            Object& child = *children[i];
            if (child.kind_ != Kind::Primitive || child.PrimitiveNode()->PrepareFrameDoesWork()) {
                later[chunk].push_back(i);
                continue;
            }
            child.PrepareFrame(frameTime, shutter);
            chunkSummaries[chunk].Add(child);
        }
    });
    for (size_t c = 0; c < chunks; ++c) {
        summary.allBounded = summary.allBounded && chunkSummaries[c].allBounded;
        summary.anyTransparent = summary.anyTransparent || chunkSummaries[c].anyTransparent;
        for (size_t i : later[c]) {
            children[i]->PrepareFrame(frameTime, shutter);
            summary.Add(*children[i]);
        }
    }
    return summary;
}

void Object::PrepareFrame(double frameTime, double shutter) {
    if (preparedFor_ == frameTime) return;
    preparedFor_ = frameTime;
    parentFromObject.PrepareAt(frameTime);
    transparentBelow_ = surface != nullptr && surface->transp >= kEpsilon;

    switch (kind_) {
        case Kind::Primitive:
            PrimitiveNode()->PrepareFrame(frameTime, shutter);
            bounded_ = PrimitiveNode()->IsBounded();
            boundsObject_ = PrimitiveNode()->Bounds();
            break;
        case Kind::Aggregate: {
            const ChildrenSummary children = PrepareChildren(frameTime, shutter);
            AggregateNode()->PrepareFrame(frameTime, shutter);
            // The aggregate's box covers only its bounded children. With an unbounded child
            // the node as a whole is unbounded, so neither its own box pre-test nor its
            // parent's clips that child away (spec §6 recommends fixing the original's
            // clipping; top-level planes must never be clipped).
            bounded_ = AggregateNode()->IsBounded() && children.allBounded;
            transparentBelow_ = transparentBelow_ || children.anyTransparent;
            boundsObject_ = AggregateNode()->Bounds();
            break;
        }
        case Kind::Instance:
            InstanceNode()->PrepareFrame(frameTime, shutter);
            bounded_ = InstanceNode()->IsBounded();
            transparentBelow_ = transparentBelow_ || InstanceNode()->transparentBelow_;
            boundsObject_ = InstanceNode()->BoundsInParent();
            break;
    }
    if (!bounded_) {
        boundsInParent_ = Bounds3{};
        return;
    }
    if (!parentFromObject.IsAnimated()) {
        boundsInParent_ = parentFromObject.Static().ApplyBounds(boundsObject_);
        return;
    }
    // Animated: the union of the boxes at times spread over the shutter interval, padded
    // by ε (spec §3.15 samples n²·10 times; 64 evenly spread instants plus the ends give
    // the same conservative box for smooth motions).
    Bounds3 b;
    const int kSamples = shutter > 0 ? 64 : 0;
    b.Extend(parentFromObject.At(frameTime).ApplyBounds(boundsObject_));
    for (int i = 1; i <= kSamples; ++i) {
        double t = frameTime + shutter * i / kSamples;
        b.Extend(parentFromObject.At(t).ApplyBounds(boundsObject_));
    }
    boundsInParent_ = b.Padded(kEpsilon);
}

std::string Object::TypeName() const {
    switch (kind_) {
        case Kind::Primitive: return counters_->typeName;
        case Kind::Aggregate: return AggregateNode()->TypeName();
        case Kind::Instance: return "instance";
    }
    return "object";
}

long Object::PrimitiveCount() const {
    switch (kind_) {
        case Kind::Primitive: return 1;
        case Kind::Instance: return InstanceNode()->PrimitiveCount();
        case Kind::Aggregate: {
            long n = 0;
            for (const auto& c : AggregateNode()->Children()) n += c->PrimitiveCount();
            return n;
        }
    }
    return 0;
}

bool Object::HasPrimitive() const {
    switch (kind_) {
        case Kind::Primitive: return true;
        case Kind::Instance: return InstanceNode()->HasPrimitive();
        case Kind::Aggregate:
            for (const auto& c : AggregateNode()->Children())
                if (c->HasPrimitive()) return true;
            return false;
    }
    return false;
}

}  // namespace rs
