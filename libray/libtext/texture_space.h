// The texture transform at one ray time, resolved once per Texture::Apply.
//
// A texture's transform list maps texture space to the node space its TextureContext is
// expressed in. Points go to texture space by the inverse; normals by the inverse's
// inverse transpose, and back by the forward map's inverse transpose. Static lists are
// referenced without copying, so an untransformed texture costs one branch.
#pragma once

#include "libcommon/transform.h"

namespace rs {

class TextureSpace {
  public:
    TextureSpace(const TransformList& list, double time)
        : identity_(list.IsIdentity()) {
        if (identity_) return;
        if (list.IsAnimated()) {
            animated_ = list.At(time);
            transform_ = &animated_;
        } else {
            transform_ = &list.Static();
        }
    }
    // Holds a pointer into itself for animated lists.
    TextureSpace(const TextureSpace&) = delete;
    TextureSpace& operator=(const TextureSpace&) = delete;

    // Node-space point → texture space.
    Vec3 Point(const Vec3& pNode) const {
        return identity_ ? pNode : transform_->InversePoint(pNode);
    }
    // Unit node-space normal → unit texture-space normal.
    Vec3 NormalToTexture(const Vec3& nNode) const {
        return identity_ ? nNode : Normalize(transform_->InverseNormal(nNode));
    }
    // Texture-space normal (any length) → unit node-space normal.
    Vec3 NormalToNode(const Vec3& nTexture) const {
        return Normalize(identity_ ? nTexture : transform_->ApplyNormal(nTexture));
    }
    // A (u, v) pair as the point (u, v, 0) mapped by the inverse transform (spec §3.13).
    Vec2 UV(const Vec2& uv) const {
        if (identity_) return uv;
        Vec3 q = transform_->InversePoint({uv.u, uv.v, 0});
        return {q.x, q.y};
    }

    // Surface derivatives for the bump rule (BumpNormal) of a texture read through UV():
    // the mapping's ∂P/∂u and ∂P/∂v (node space; n the unit normal completing the frame)
    // become the derivatives with respect to the transformed pair. With the forward map's
    // linear part M, (u, v, 0) = (u', v', w')·M, so by the chain rule ∂P/∂u' = M₀₀·∂P/∂u +
    // M₀₁·∂P/∂v + M₀₂·n and ∂P/∂v' likewise with M's second row: `rotate 0 0 1 θ` turns
    // the bump directions with the pattern, as in the original. Both leave normalised (a
    // zero one stays zero, and BumpNormal then keeps the normal).
    void Derivatives(Vec3& dpdu, Vec3& dpdv, const Vec3& n) const {
        if (!identity_) {
            const Vec3 rowU = transform_->ApplyVector({1, 0, 0});
            const Vec3 rowV = transform_->ApplyVector({0, 1, 0});
            const Vec3 du = dpdu, dv = dpdv;
            dpdu = du * rowU.x + dv * rowU.y + n * rowU.z;
            dpdv = du * rowV.x + dv * rowV.y + n * rowV.z;
        }
        if (LengthSquared(dpdu) > 0) dpdu = Normalize(dpdu);
        if (LengthSquared(dpdv) > 0) dpdv = Normalize(dpdv);
    }

  private:
    bool identity_;
    const Transform* transform_ = nullptr;
    Transform animated_;
};

// Replaces `normal` by `candidate` unless the candidate is zero or not finite (a
// perturbation that exactly cancels the normal leaves it unchanged).
inline void AssignNormal(Vec3& normal, const Vec3& candidate) {
    if (LengthSquared(candidate) > 0 && IsFinite(candidate)) normal = candidate;
}

}  // namespace rs
