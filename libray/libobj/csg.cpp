#include "libobj/csg.h"

#include <memory>
#include <vector>

#include "libcommon/constants.h"
#include "libobj/hit_classify.h"
#include "libobj/object.h"

namespace rs {

namespace {

// The state of a walk along one operand's hit sequence: its pending hit (the first beyond
// the last search start) and whether the ray enters the operand there.
class OperandState {
  public:
    bool valid() const { return valid_; }
    double t() const { return hit_.t(); }
    bool enters() const { return enters_; }
    const HitRecord& hit() const { return hit_; }
    // Whether the point at parameter t is inside this operand, for t before its next hit:
    // inside exactly when that next hit leaves the solid.
    bool ContainsBeforeNext() const { return valid_ && !enters_; }

  protected:
    // Records whether a search from `from` found a hit (into hit_) and classifies it with
    // the ray's origin moved to the midpoint between `from` and the hit: that point is
    // strictly off the operand's surfaces with no surface of the operand before the hit, so
    // origin-based tests ("ray start outside", spheres and boxes) are reliable. The origin
    // moves along the direction, so t shifts by the same amount.
    void Settle(bool found, const Ray& ray, double from) {
        valid_ = found;
        if (!found) return;
        const double t = hit_.t();
        const double tOrigin = 0.5 * (from + t);
        const Ray shifted{ray.At(tOrigin), ray.dir, ray.time};
        hit_.prim.t = t - tOrigin;
        enters_ = HitEnters(shifted, hit_);
        hit_.prim.t = t;
    }

    HitRecord hit_;
    bool valid_ = false;
    bool enters_ = false;
};

// An operand searched afresh for each of its hits.
class FreshOperand : public OperandState {
  public:
    FreshOperand(const Object& operand, const Ray& ray) : operand_(operand), ray_(ray) {}

    // Finds the first hit beyond `from`; returns whether there is one.
    bool Advance(double from) {
        double tFar = kFar;
        Settle(operand_.Intersect(ray_, from, tFar, hit_), ray_, from);
        return valid_;
    }

  private:
    const Object& operand_;
    const Ray& ray_;
};

// The nearest boundary point of `op` applied to the operands along (from, tMax), given
// walks whose pending hits are the first beyond `from` (see CsgAggregate::Intersect).
template <class Walk>
bool NearestBoundary(CsgAggregate::Op op, Walk& a, Walk& b, double& tMax, HitRecord& hit) {
    using Op = CsgAggregate::Op;
    while (a.valid() || b.valid()) {
        // Visit the nearer pending hit. Surfaces of A and B closer than ε along the ray are
        // coincident (the user's responsibility, spec §3.10), and are ordered as the
        // original orders exact ties, whatever the rounding of the two distances: A first
        // for union and intersection, B first for difference (so a face of B lying on a
        // face of A cuts A open there).
        const bool onA =
            a.valid() && (!b.valid() || (op == Op::Difference ? a.t() < b.t() - kEpsilon
                                                              : a.t() <= b.t() + kEpsilon));
        Walk& self = onA ? a : b;
        const Walk& other = onA ? b : a;
        if (self.t() >= tMax) return false;
        const bool insideOther = other.ContainsBeforeNext();
        bool accept = false;
        bool enters = self.enters();
        switch (op) {
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

struct NestedWalk;

// An operand whose walk can resume: a chained operand (see CsgAggregate::OperandChain)
// keeps the walk of the CSG node it reaches, so its successive hits continue that walk
// instead of restarting it; any other operand is searched afresh.
class ResumableOperand : public OperandState {
  public:
    // `ray` (in the CSG node's space) must outlive the walk.
    void Start(const Object& operand, const CsgAggregate::OperandChain& chain, const Ray& ray) {
        operand_ = &operand;
        chain_ = &chain;
        ray_ = &ray;
        nested_ = nullptr;
        started_ = false;
    }

    // Finds the first hit beyond `from`; returns whether there is one.
    bool Advance(double from) {
        started_ = true;
        double tFar = kFar;
        Settle(chain_->length == 0 ? operand_->Intersect(*ray_, from, tFar, hit_)
                                   : SearchChained(from),
               *ray_, from);
        return valid_;
    }

    // Makes the pending hit the first beyond `from`, exactly as Advance(from) would, but
    // without searching again when the pending hit already lies beyond `from`. `from`
    // must not decrease from one search start to the next.
    bool Seek(double from) {
        if (!started_) return Advance(from);
        // Nothing beyond an earlier start leaves nothing beyond this one.
        if (!valid_) return false;
        if (hit_.t() <= from) return Advance(from);
        Settle(true, *ray_, from);
        return true;
    }

  private:
    // For a chained operand: its first hit beyond `from` into hit_, as
    // operand.Intersect(ray, from, kFar) finds it.
    bool SearchChained(double from);

    // All set by Start.
    const Object* operand_;
    const CsgAggregate::OperandChain* chain_;
    const Ray* ray_;
    NestedWalk* nested_;  // the chained CSG node's walk, once started
    bool started_;
};

}  // namespace

// A resumable walk over the boundary points of one CSG node along one ray (in the node's
// space): successive NextAfter calls with non-decreasing `from` give what
// CsgAggregate::Intersect would give for each, while the operands' pending hits carry over.
class CsgWalk {
  public:
    // `ray` must outlive the walk. Requires csg.HasTwoOperands().
    void Start(const CsgAggregate& csg, const Ray& ray) {
        op_ = csg.op_;
        a_.Start(*csg.children_[0], csg.chains_[0], ray);
        b_.Start(*csg.children_[1], csg.chains_[1], ray);
    }

    // The nearest boundary point with from < t < tMax (see CsgAggregate::Intersect).
    bool NextAfter(double from, double& tMax, HitRecord& hit) {
        a_.Seek(from);
        b_.Seek(from);
        return NearestBoundary(op_, a_, b_, tMax, hit);
    }

  private:
    CsgAggregate::Op op_;
    ResumableOperand a_, b_;
};

namespace {

// A chained operand's walk with the ray mapped down its chain (rays[k] in nodes[k]'s space).
struct NestedWalk {
    Ray rays[CsgAggregate::OperandChain::kMaxNodes];
    CsgWalk walk;
};

// Nested walks of the calling thread, used as a stack: the walks taken during one
// CsgAggregate::Intersect call are given back when it returns (PoolScope). Kept across calls
// so that walking allocates only while the pool grows to the scene's nesting.
struct WalkPool {
    std::vector<std::unique_ptr<NestedWalk>> walks;
    size_t top = 0;

    NestedWalk* Take() {
        if (top == walks.size()) walks.push_back(std::make_unique<NestedWalk>());
        return walks[top++].get();
    }
};

thread_local WalkPool pool;

class PoolScope {
  public:
    PoolScope() : top_(pool.top) {}
    ~PoolScope() { pool.top = top_; }
    PoolScope(const PoolScope&) = delete;
    PoolScope& operator=(const PoolScope&) = delete;

  private:
    size_t top_;
};

bool ResumableOperand::SearchChained(double from) {
    double tFar = kFar;
    const int n = chain_->length;
    if (!nested_) {
        nested_ = pool.Take();
        // The ray in each chain node's space, mapped as Object::Intersect maps it.
        Ray ray = *ray_;
        for (int k = 0; k < n; ++k) {
            const TransformList& list = chain_->nodes[k]->parentFromObject;
            if (!list.IsIdentity()) ray = list.Static().InverseRay(ray);
            nested_->rays[k] = ray;
        }
        nested_->walk.Start(*chain_->csg, nested_->rays[n - 1]);
    }
    // The chain nodes' box pre-tests, as Object::Intersect applies them on the way down.
    for (int k = 0; k < n; ++k)
        if (!chain_->nodes[k]->BoxAdmits(nested_->rays[k], from, tFar)) return false;
    if (!nested_->walk.NextAfter(from, tFar, hit_)) return false;
    // The nodes add themselves to the path on the way back up, innermost first.
    for (int k = n - 1; k >= 0; --k)
        if (hit_.pathLength < HitRecord::kMaxPath) hit_.path[hit_.pathLength++] = chain_->nodes[k];
    return true;
}

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
    if (chains_[0].length == 0 && chains_[1].length == 0) {
        FreshOperand a(*children_[0], ray), b(*children_[1], ray);
        a.Advance(tMin);
        b.Advance(tMin);
        return NearestBoundary(op_, a, b, tMax, hit);
    }
    PoolScope scope;
    CsgWalk walk;
    walk.Start(*this, ray);
    return walk.NextAfter(tMin, tMax, hit);
}

CsgAggregate::OperandChain CsgAggregate::ChainTo(const Object& operand) {
    OperandChain chain;
    const Object* node = &operand;
    for (int k = 0; k < OperandChain::kMaxNodes; ++k) {
        if (node->parentFromObject.IsAnimated()) return {};
        chain.nodes[k] = node;
        if (node->kind() == Object::Kind::Instance) {
            node = node->instanceOf();
            continue;
        }
        if (node->kind() != Object::Kind::Aggregate) return {};
        chain.csg = dynamic_cast<const CsgAggregate*>(node->aggregate());
        if (!chain.csg) return {};
        chain.length = k + 1;
        return chain;
    }
    return {};
}

void CsgAggregate::PrepareFrame(double /*frameTime*/, double /*shutter*/) {
    bounds_ = Bounds3{};
    bounded_ = false;
    chains_[0] = chains_[1] = {};
    hasCsgOperand_ = false;
    if (!HasTwoOperands()) {
        // Hits nothing: a bounded, empty box lets every box test reject it.
        bounded_ = true;
        return;
    }
    const Object& a = *children_[0];
    const Object& b = *children_[1];
    const OperandChain toA = ChainTo(a), toB = ChainTo(b);
    hasCsgOperand_ = toA.length > 0 || toB.length > 0;
    // Resuming a walk saves searching its operands again, which pays for the walk's upkeep
    // only when an operand is itself CSG: a CSG node over plain operands is cheaper to
    // search afresh.
    if (toA.length > 0 && toA.csg->hasCsgOperand_) chains_[0] = toA;
    if (toB.length > 0 && toB.csg->hasCsgOperand_) chains_[1] = toB;
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
