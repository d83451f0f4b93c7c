// CSG `union | intersect | difference A B end` (spec §3.10) of two closed operands.
#pragma once

#include "libobj/aggregate.h"

namespace rs {

class CsgWalk;

class CsgAggregate final : public Aggregate {
  public:
    enum class Op { Union, Intersect, Difference };

    explicit CsgAggregate(Op op) : op_(op) {}

    const char* TypeName() const override;
    bool HitsAreChildHits() const override { return false; }

    // Exactly two children (A first, then B) make a valid CSG node; the parser warns and
    // discards the node otherwise. An invalid node hits nothing.
    bool HasTwoOperands() const { return children_.size() == 2; }

    // Nearest boundary point of the combined solid in (tMin, tMax), found by walking the
    // hit sequences of A and B front to back (each searched up to kFar, to classify):
    //   union       a hit on A or B not inside the other solid;
    //   intersect   a hit on A or B inside the other solid;
    //   difference  a hit on A not inside B, or a hit on B inside A (enter flag inverted).
    // The winner's record has enterOverride set (1 enter, 0 leave). Successive hits of one
    // operand are searched from kEpsilon past the previous one, so surfaces of an operand
    // closer together than kEpsilon along the ray are not resolved.
    // An operand that is itself a CSG node with a CSG operand of its own (possibly behind
    // instances with static transforms) is walked incrementally: its walk is resumed rather
    // than restarted for each of its successive hits, with the same results as restarting.
    bool Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const override;

    // Union: box union (unbounded if either operand is); intersect: box intersection of the
    // bounded operands; difference: A's box.
    Bounds3 Bounds() const override { return bounds_; }
    bool IsBounded() const override { return bounded_; }
    bool IsClosed() const override { return true; }
    void PrepareFrame(double frameTime, double shutter) override;

    // How an operand reaches a CSG node: nodes[0] is the operand, each further node the
    // target of the instance before it, and nodes[length - 1] the CSG node's own node; all
    // transforms static. length 0: the operand is not walked incrementally.
    struct OperandChain {
        static constexpr int kMaxNodes = 8;
        const Object* nodes[kMaxNodes];
        int length = 0;
        const CsgAggregate* csg = nullptr;
    };

  private:
    friend class CsgWalk;

    static OperandChain ChainTo(const Object& operand);

    Op op_;
    OperandChain chains_[2];
    bool hasCsgOperand_ = false;  // an operand reaches a CSG node (chained or not)
    Bounds3 bounds_;
    bool bounded_ = false;
};

}  // namespace rs
