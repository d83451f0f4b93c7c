// Affine transforms in Rayshade's row-vector convention: a point X maps to X·M + t, and a
// list of transforms applies in the order written (first listed acts first).
//
// A Transform carries its matrix and the inverse, so rays (inverse) and normals (inverse
// transpose) can be mapped without re-inverting. Names say the direction of a mapping:
// `parentFromObject.ApplyPoint(pObject)` gives the point in the parent's space.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "libcommon/ray.h"
#include "libcommon/bounds.h"

namespace rs {

// A 3×3 linear part plus translation: X' = X·m + t (X a row vector).
struct Affine {
    double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3 t;

    Vec3 ApplyPoint(const Vec3& p) const { return ApplyVector(p) + t; }
    Vec3 ApplyVector(const Vec3& v) const {
        return {v.x * m[0][0] + v.y * m[1][0] + v.z * m[2][0],
                v.x * m[0][1] + v.y * m[1][1] + v.z * m[2][1],
                v.x * m[0][2] + v.y * m[1][2] + v.z * m[2][2]};
    }
    // v·mᵀ: used with the inverse's matrix to carry normals (inverse transpose).
    Vec3 ApplyTransposed(const Vec3& v) const {
        return {Dot(v, {m[0][0], m[0][1], m[0][2]}), Dot(v, {m[1][0], m[1][1], m[1][2]}),
                Dot(v, {m[2][0], m[2][1], m[2][2]})};
    }
    double Determinant() const;
    bool IsIdentity() const;
};

// `a` then `b`: X·(a then b) = (X·a)·b.
Affine Then(const Affine& a, const Affine& b);

class Transform {
  public:
    Transform() = default;  // identity

    // Builds a transform from its forward map. Returns nothing when the matrix is singular
    // (|det| < kEpsilon², the original's "Singular matrix" test).
    static std::optional<Transform> FromAffine(const Affine& forward);

    static Transform Translate(const Vec3& d);
    // Requires all components non-zero (else nothing: singular).
    static std::optional<Transform> Scale(const Vec3& s);
    // Right-handed rotation by `degrees` about `axis` (normalised here; must be non-zero).
    static std::optional<Transform> Rotate(const Vec3& axis, double degrees);
    // Rows are the images of the x, y and z unit vectors; `translation` is added.
    static std::optional<Transform> General(const Vec3& xImage, const Vec3& yImage,
                                            const Vec3& zImage, const Vec3& translation);

    const Affine& Forward() const { return forward_; }
    const Affine& Inverse() const { return inverse_; }
    bool IsIdentity() const { return identity_; }

    // This transform followed by `next`.
    Transform Then(const Transform& next) const;
    Transform Inverted() const;

    Vec3 ApplyPoint(const Vec3& p) const { return forward_.ApplyPoint(p); }
    Vec3 ApplyVector(const Vec3& v) const { return forward_.ApplyVector(v); }
    // Normals map with the inverse transpose; the result is not renormalised.
    Vec3 ApplyNormal(const Vec3& n) const { return inverse_.ApplyTransposed(n); }
    Vec3 InversePoint(const Vec3& p) const { return inverse_.ApplyPoint(p); }
    Vec3 InverseVector(const Vec3& v) const { return inverse_.ApplyVector(v); }
    Vec3 InverseNormal(const Vec3& n) const { return forward_.ApplyTransposed(n); }
    // The ray in the source space of this transform; t is preserved (no renormalising).
    Ray InverseRay(const Ray& r) const {
        Ray out = r;  // keeps the time and footprint
        out.origin = inverse_.ApplyPoint(r.origin);
        out.dir = inverse_.ApplyVector(r.dir);
        return out;
    }
    // Conservative image of a box: the box around its 8 transformed corners.
    Bounds3 ApplyBounds(const Bounds3& b) const;

  private:
    Affine forward_;
    Affine inverse_;
    bool identity_ = true;
};

// A list of transform steps applied in written order, some of which may depend on time
// (animated parameters, spec §3.15). Static neighbours are merged into one matrix when the
// list is built, so evaluating a static list costs nothing.
class TransformList {
  public:
    // An animated step: returns the transform at a given time, or nothing when its
    // parameters are invalid at that time (singular scale, zero rotation axis).
    using AnimatedStep = std::function<std::optional<Transform>(double time)>;

    TransformList() = default;
    TransformList(const TransformList& other);
    TransformList& operator=(const TransformList& other);
    TransformList(TransformList&&) noexcept = default;
    TransformList& operator=(TransformList&&) noexcept = default;

    void Append(const Transform& step);
    void AppendAnimated(AnimatedStep step);
    void Append(const TransformList& other);

    bool IsIdentity() const { return !steps_; }
    bool IsAnimated() const { return steps_ && steps_->animated; }
    // The composed transform at `time` (time is ignored for a static list). A step that is
    // invalid at that time is skipped (and counted by the caller as a warning elsewhere).
    Transform At(double time) const;
    // The composed transform of a static list (requires !IsAnimated()).
    const Transform& Static() const { return steps_ ? steps_->composedStatic : kIdentity; }
    // Evaluates an animated list at `time` once and keeps the result, so that At(time) for
    // that same time is a copy instead of an evaluation of every animated step (the
    // renderer prepares each frame's start: without motion blur every ray has that time).
    // Call it before rendering; At stays safe to call from any number of threads.
    void PrepareAt(double time);

  private:
    struct Step {
        Transform fixed;
        AnimatedStep animated;  // empty for a fixed step
    };
    // The steps of a non-empty list and what is composed from them. Held on the heap, and
    // only once a step is appended: most nodes of a scene (every triangle of a mesh) have
    // no transform, and their list then costs one pointer instead of three transforms.
    struct Steps {
        std::vector<Step> steps;
        Transform composedStatic;
        bool animated = false;
        bool prepared = false;
        double preparedTime = 0;
        Transform preparedTransform;  // At(preparedTime), when prepared
    };
    Steps& MutableSteps();

    inline static const Transform kIdentity{};
    std::unique_ptr<Steps> steps_;  // null for the identity
};

}  // namespace rs
