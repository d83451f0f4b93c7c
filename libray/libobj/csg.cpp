#include "libobj/csg.h"

#include "libcommon/constants.h"
#include "libobj/hit_classify.h"
#include "libobj/object.h"

namespace rs {

namespace {

// The walk along one operand's hit sequence: its next hit beyond the last one visited, and
// whether the ray enters the operand there.
class OperandWalk {
  public:
    OperandWalk(const Object& operand, const Ray& ray) : operand_(operand), ray_(ray) {}

    // Finds the first hit beyond `from`; returns whether there is one.
    bool Advance(double from) {
        double tFar = kFar;
        valid_ = operand_.Intersect(ray_, from, tFar, hit_);
        if (!valid_) return false;
        // Classify with the ray's origin moved to the midpoint between `from` and the hit:
        // that point is strictly off the operand's surfaces with no surface of the operand
        // before the hit, so origin-based tests ("ray start outside", spheres and boxes) are
        // reliable. The origin moves along the direction, so t shifts by the same amount.
        const double t = hit_.t();
        const double tOrigin = 0.5 * (from + t);
        const Ray shifted{ray_.At(tOrigin), ray_.dir, ray_.time};
        hit_.prim.t = t - tOrigin;
        enters_ = HitEnters(shifted, hit_);
        hit_.prim.t = t;
        return true;
    }

    bool valid() const { return valid_; }
    double t() const { return hit_.t(); }
    bool enters() const { return enters_; }
    const HitRecord& hit() const { return hit_; }
    // Whether the point at parameter t is inside this operand, for t before its next hit:
    // inside exactly when that next hit leaves the solid.
    bool ContainsBeforeNext() const { return valid_ && !enters_; }

  private:
    const Object& operand_;
    const Ray& ray_;
    HitRecord hit_;
    bool valid_ = false;
    bool enters_ = false;
};

}  // namespace

const char* CsgAggregate::TypeName() const {
    switch (op_) {
        case Op::Union: return "union";
        case Op::Intersect: return "intersect";
        case Op::Difference: return "difference";
    }
    return "csg";
}

bool CsgAggregate::Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const {
    if (!HasTwoOperands()) return false;
    OperandWalk a(*children_[0], ray), b(*children_[1], ray);
    a.Advance(tMin);
    b.Advance(tMin);
    while (a.valid() || b.valid()) {
        // Visit the nearer pending hit. Surfaces of A and B closer than ε along the ray are
        // coincident (the user's responsibility, spec §3.10), and are ordered as the
        // original orders exact ties, whatever the rounding of the two distances: A first
        // for union and intersection, B first for difference (so a face of B lying on a
        // face of A cuts A open there).
        const bool onA =
            a.valid() && (!b.valid() || (op_ == Op::Difference ? a.t() < b.t() - kEpsilon
                                                               : a.t() <= b.t() + kEpsilon));
        OperandWalk& self = onA ? a : b;
        const OperandWalk& other = onA ? b : a;
        if (self.t() >= tMax) return false;
        const bool insideOther = other.ContainsBeforeNext();
        bool accept = false;
        bool enters = self.enters();
        switch (op_) {
            case Op::Union: accept = !insideOther; break;
            case Op::Intersect: accept = insideOther; break;
            case Op::Difference:
                // A's boundary outside B, or B's boundary inside A seen from the other side.
                accept = onA ? !insideOther : insideOther;
                if (!onA) enters = !enters;
                break;
        }
        if (accept) {
            tMax = self.t();
            hit = self.hit();
            hit.enterOverride = enters ? 1 : 0;
            return true;
        }
        self.Advance(self.t() + kEpsilon);
    }
    return false;
}

void CsgAggregate::PrepareFrame(double /*frameTime*/, double /*shutter*/) {
    bounds_ = Bounds3{};
    bounded_ = false;
    if (!HasTwoOperands()) {
        // Hits nothing: a bounded, empty box lets every box test reject it.
        bounded_ = true;
        return;
    }
    const Object& a = *children_[0];
    const Object& b = *children_[1];
    switch (op_) {
        case Op::Union:
            bounded_ = a.IsBounded() && b.IsBounded();
            if (bounded_) bounds_ = Union(a.BoundsInParent(), b.BoundsInParent());
            break;
        case Op::Intersect:
            bounded_ = a.IsBounded() || b.IsBounded();
            if (a.IsBounded() && b.IsBounded()) {
                bounds_ = Intersection(a.BoundsInParent(), b.BoundsInParent());
            } else if (bounded_) {
                bounds_ = a.IsBounded() ? a.BoundsInParent() : b.BoundsInParent();
            }
            break;
        case Op::Difference:
            bounded_ = a.IsBounded();
            if (bounded_) bounds_ = a.BoundsInParent();
            break;
    }
}

}  // namespace rs
