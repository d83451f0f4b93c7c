#include "libobj/object.h"

#include <algorithm>

#include "libcommon/constants.h"

namespace rs {

const CounterId Object::kBoundsTests = RegisterCounter("bounding box tests");

std::shared_ptr<Object> Object::MakePrimitive(std::shared_ptr<Primitive> p) {
    auto o = std::make_shared<Object>(Key{}, Kind::Primitive);
    o->primitive_ = std::move(p);
    o->counters_ = &o->primitive_->Counters();
    return o;
}

std::shared_ptr<Object> Object::MakeAggregate(std::shared_ptr<Aggregate> a) {
    auto o = std::make_shared<Object>(Key{}, Kind::Aggregate);
    o->aggregate_ = std::move(a);
    return o;
}

std::shared_ptr<Object> Object::MakeInstance(std::shared_ptr<Object> of) {
    auto o = std::make_shared<Object>(Key{}, Kind::Instance);
    o->instanceOf_ = std::move(of);
    return o;
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
                found = kind_ == Kind::Aggregate ? aggregate_->Intersect(ray, tMin, tMax, hit)
                                                 : instanceOf_->Intersect(ray, tMin, tMax, hit);
                break;
        }
        if (found && hit.pathLength < HitRecord::kMaxPath) hit.path[hit.pathLength++] = this;
        return found;
    };
    Ray storage;
    return inObjectSpace(ObjectRay(rayParent, storage));
}

bool Object::OccludedGeneral(const Ray& rayParent, double tMin, double tMax) const {
    Ray storage;
    const Ray& ray = ObjectRay(rayParent, storage);
    switch (kind_) {
        case Kind::Primitive: return OccludedPrimitive(ray, tMin, tMax);
        case Kind::Aggregate:
            return BoxAdmits(ray, tMin, tMax) && aggregate_->Occluded(ray, tMin, tMax);
        case Kind::Instance:
            return BoxAdmits(ray, tMin, tMax) && instanceOf_->Occluded(ray, tMin, tMax);
    }
    return false;
}

bool Object::IsClosed() const {
    switch (kind_) {
        case Kind::Primitive: return primitive_->IsClosed();
        case Kind::Aggregate: return aggregate_->IsClosed();
        case Kind::Instance: return instanceOf_->IsClosed();
    }
    return false;
}

void Object::PrepareFrame(double frameTime, double shutter) {
    if (preparedFor_ == frameTime) return;
    preparedFor_ = frameTime;
    parentFromObject.PrepareAt(frameTime);

    switch (kind_) {
        case Kind::Primitive:
            primitive_->PrepareFrame(frameTime, shutter);
            bounded_ = primitive_->IsBounded();
            boundsObject_ = primitive_->Bounds();
            break;
        case Kind::Aggregate:
            for (const auto& child : aggregate_->Children()) child->PrepareFrame(frameTime, shutter);
            aggregate_->PrepareFrame(frameTime, shutter);
            // The aggregate's box covers only its bounded children. With an unbounded child
            // the node as a whole is unbounded, so neither its own box pre-test nor its
            // parent's clips that child away (spec §6 recommends fixing the original's
            // clipping; top-level planes must never be clipped).
            bounded_ = aggregate_->IsBounded() &&
                       std::all_of(aggregate_->Children().begin(), aggregate_->Children().end(),
                                   [](const auto& child) { return child->IsBounded(); });
            boundsObject_ = aggregate_->Bounds();
            break;
        case Kind::Instance:
            instanceOf_->PrepareFrame(frameTime, shutter);
            bounded_ = instanceOf_->IsBounded();
            boundsObject_ = instanceOf_->BoundsInParent();
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
        case Kind::Aggregate: return aggregate_->TypeName();
        case Kind::Instance: return "instance";
    }
    return "object";
}

long Object::PrimitiveCount() const {
    switch (kind_) {
        case Kind::Primitive: return 1;
        case Kind::Instance: return instanceOf_->PrimitiveCount();
        case Kind::Aggregate: {
            long n = 0;
            for (const auto& c : aggregate_->Children()) n += c->PrimitiveCount();
            return n;
        }
    }
    return 0;
}

}  // namespace rs
