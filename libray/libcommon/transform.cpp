#include "libcommon/transform.h"

#include <cmath>

#include "libcommon/constants.h"

namespace rs {

double Affine::Determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

bool Affine::IsIdentity() const {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (m[i][j] != (i == j ? 1.0 : 0.0)) return false;
    return t == Vec3{};
}

Affine Then(const Affine& a, const Affine& b) {
    Affine r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    r.t = b.ApplyPoint(a.t);
    return r;
}

namespace {

// Inverse of an affine map with non-zero determinant (adjugate / determinant).
Affine InvertAffine(const Affine& a, double det) {
    Affine r;
    const auto& m = a.m;
    r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    r.t = -r.ApplyVector(a.t);
    return r;
}

}  // namespace

std::optional<Transform> Transform::FromAffine(const Affine& forward) {
    double det = forward.Determinant();
    if (!(std::fabs(det) >= kEpsilon * kEpsilon)) return std::nullopt;
    Transform t;
    t.forward_ = forward;
    t.inverse_ = InvertAffine(forward, det);
    t.identity_ = forward.IsIdentity();
    return t;
}

Transform Transform::Translate(const Vec3& d) {
    Affine a;
    a.t = d;
    return *FromAffine(a);
}

std::optional<Transform> Transform::Scale(const Vec3& s) {
    Affine a;
    a.m[0][0] = s.x;
    a.m[1][1] = s.y;
    a.m[2][2] = s.z;
    return FromAffine(a);
}

std::optional<Transform> Transform::Rotate(const Vec3& axis, double degrees) {
    double len = Length(axis);
    if (!(len > 0)) return std::nullopt;
    Vec3 n = axis / len;
    double theta = degrees * kPi / 180.0;
    double c = std::cos(theta), s = std::sin(theta), k = 1 - c;
    // Row-vector form of the Rodrigues matrix: X' = X·M, counter-clockwise about n.
    Affine a;
    a.m[0][0] = n.x * n.x * k + c;
    a.m[0][1] = n.x * n.y * k + n.z * s;
    a.m[0][2] = n.x * n.z * k - n.y * s;
    a.m[1][0] = n.x * n.y * k - n.z * s;
    a.m[1][1] = n.y * n.y * k + c;
    a.m[1][2] = n.y * n.z * k + n.x * s;
    a.m[2][0] = n.x * n.z * k + n.y * s;
    a.m[2][1] = n.y * n.z * k - n.x * s;
    a.m[2][2] = n.z * n.z * k + c;
    return FromAffine(a);
}

std::optional<Transform> Transform::General(const Vec3& xImage, const Vec3& yImage,
                                            const Vec3& zImage, const Vec3& translation) {
    Affine a;
    for (int j = 0; j < 3; ++j) {
        a.m[0][j] = xImage[j];
        a.m[1][j] = yImage[j];
        a.m[2][j] = zImage[j];
    }
    a.t = translation;
    return FromAffine(a);
}

Transform Transform::Then(const Transform& next) const {
    if (identity_) return next;
    if (next.identity_) return *this;
    Transform r;
    r.forward_ = rs::Then(forward_, next.forward_);
    r.inverse_ = rs::Then(next.inverse_, inverse_);
    r.identity_ = false;
    return r;
}

Transform Transform::Inverted() const {
    Transform r;
    r.forward_ = inverse_;
    r.inverse_ = forward_;
    r.identity_ = identity_;
    return r;
}

Bounds3 Transform::ApplyBounds(const Bounds3& b) const {
    if (identity_ || b.IsEmpty()) return b;
    Bounds3 r;
    for (int i = 0; i < 8; ++i) r.Extend(ApplyPoint(b.Corner(i)));
    return r;
}

TransformList::TransformList(const TransformList& other)
    : steps_(other.steps_ ? std::make_unique<Steps>(*other.steps_) : nullptr) {}

TransformList& TransformList::operator=(const TransformList& other) {
    if (this != &other) steps_ = other.steps_ ? std::make_unique<Steps>(*other.steps_) : nullptr;
    return *this;
}

TransformList::Steps& TransformList::MutableSteps() {
    if (!steps_) steps_ = std::make_unique<Steps>();
    steps_->prepared = false;
    return *steps_;
}

void TransformList::Append(const Transform& step) {
    if (step.IsIdentity()) return;
    Steps& s = MutableSteps();
    if (!s.steps.empty() && !s.steps.back().animated) {
        s.steps.back().fixed = s.steps.back().fixed.Then(step);
    } else {
        s.steps.push_back({step, {}});
    }
    if (!s.animated) s.composedStatic = s.composedStatic.Then(step);
}

void TransformList::AppendAnimated(AnimatedStep step) {
    Steps& s = MutableSteps();
    s.steps.push_back({Transform{}, std::move(step)});
    s.animated = true;
}

void TransformList::Append(const TransformList& other) {
    if (!other.steps_) return;
    if (&other == this) {  // appending iterates the steps it grows: go through a copy
        const TransformList copy = other;
        Append(copy);
        return;
    }
    for (const Step& s : other.steps_->steps) {
        if (s.animated)
            AppendAnimated(s.animated);
        else
            Append(s.fixed);
    }
}

Transform TransformList::At(double time) const {
    if (!IsAnimated()) return Static();
    if (steps_->prepared && time == steps_->preparedTime) return steps_->preparedTransform;
    Transform r;
    for (const Step& s : steps_->steps) {
        if (s.animated) {
            if (std::optional<Transform> t = s.animated(time)) r = r.Then(*t);
        } else {
            r = r.Then(s.fixed);
        }
    }
    return r;
}

void TransformList::PrepareAt(double time) {
    if (!IsAnimated()) return;
    steps_->prepared = false;  // At below must evaluate
    steps_->preparedTransform = At(time);
    steps_->preparedTime = time;
    steps_->prepared = true;
}

}  // namespace rs
