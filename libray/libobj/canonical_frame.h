// The canonical frame of the axial primitives (cylinder, cone, torus), spec §3.9: the unit
// canonical shape is scaled by (sx, sy, sz), then turned by the minimal rotation taking +z
// to the axis (about z×axis by acos(axis_z); about +x by π when the axis is −z), then
// translated to `origin`. The image of canonical +x is where texture u = 0 lies.
//
// The rotation is orthonormal, so the inverse needs no matrix inversion (and no singular-
// matrix test that would reject thin shapes): canonical q_i = (p − origin)·axis_i / s_i.
#pragma once

#include <algorithm>
#include <cmath>

#include "libcommon/bounds.h"

namespace rs {

class CanonicalFrame {
  public:
    CanonicalFrame() = default;
    // `axis` must be unit length; the scales must be non-zero.
    CanonicalFrame(const Vec3& origin, const Vec3& axis, double sx, double sy, double sz)
        : origin_(origin) {
        const double s2 = axis.x * axis.x + axis.y * axis.y;  // sin²θ
        if (s2 == 0) {
            // Axis ±z: identity, or a half turn about +x (x ↦ x, y ↦ −y, z ↦ −z).
            const double sign = axis.z >= 0 ? 1.0 : -1.0;
            u_ = {1, 0, 0};
            v_ = {0, sign, 0};
            w_ = {0, 0, sign};
        } else {
            // Rodrigues' formula for R(x̂) with k = (z×a)/|z×a|, cosθ = a_z, sinθ = √s2:
            // R(x̂) = (c + a_y²/(1+c), −a_x·a_y/(1+c), −a_x), and 1/(1+c) = (1−c)/s2 avoids
            // the cancellation in 1 + c when the axis is close to −z.
            const double h = (1 - axis.z) / s2;
            u_ = {axis.z + axis.y * axis.y * h, -axis.x * axis.y * h, -axis.x};
            w_ = axis;
            v_ = Cross(w_, u_);
        }
        scale_ = {sx, sy, sz};
        invU_ = u_ / sx;
        invV_ = v_ / sy;
        invW_ = w_ / sz;
    }

    // Object space → canonical space.
    Vec3 ToCanonicalPoint(const Vec3& p) const {
        const Vec3 d = p - origin_;
        return {Dot(d, invU_), Dot(d, invV_), Dot(d, invW_)};
    }
    Vec3 ToCanonicalVector(const Vec3& v) const {
        return {Dot(v, invU_), Dot(v, invV_), Dot(v, invW_)};
    }
    // Canonical space → object space.
    Vec3 FromCanonicalPoint(const Vec3& q) const { return origin_ + FromCanonicalVector(q); }
    Vec3 FromCanonicalVector(const Vec3& v) const {
        return u_ * (v.x * scale_.x) + v_ * (v.y * scale_.y) + w_ * (v.z * scale_.z);
    }
    // Normals map with the inverse transpose: n_i / s_i along each axis (not normalised).
    Vec3 FromCanonicalNormal(const Vec3& n) const { return invU_ * n.x + invV_ * n.y + invW_ * n.z; }

    // Unit object-space images of the canonical axes.
    const Vec3& XAxis() const { return u_; }
    const Vec3& YAxis() const { return v_; }
    const Vec3& ZAxis() const { return w_; }

  private:
    Vec3 origin_;
    Vec3 u_{1, 0, 0}, v_{0, 1, 0}, w_{0, 0, 1};
    Vec3 scale_{1, 1, 1};
    Vec3 invU_{1, 0, 0}, invV_{0, 1, 0}, invW_{0, 0, 1};
};

// The tight box of a circle of radius r centred at c in the plane with unit normal n:
// along axis i the circle reaches r·√(1 − n_i²).
inline Bounds3 CircleBounds(const Vec3& c, const Vec3& n, double r) {
    const Vec3 e{r * std::sqrt(std::max(0.0, 1 - n.x * n.x)),
                 r * std::sqrt(std::max(0.0, 1 - n.y * n.y)),
                 r * std::sqrt(std::max(0.0, 1 - n.z * n.z))};
    return {c - e, c + e};
}

}  // namespace rs
