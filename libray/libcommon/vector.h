// Small value types for 3-D math: Vec3 (points, directions, normals), Vec2 and Color.
// Everything is double precision: the original's Doc/BUGS notes that single precision
// breaks refraction.
#pragma once

#include <algorithm>
#include <cmath>

namespace rs {

struct Vec3 {
    double x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

    // Component i (0, 1, 2) through a member-pointer table: one indexed load, no branches,
    // which matters in the per-axis loops of box and grid traversal.
    constexpr double operator[](int i) const { return this->*kAxes[i]; }
    double& operator[](int i) { return this->*kAxes[i]; }

    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
    Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
    constexpr bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }

  private:
    static constexpr double Vec3::*kAxes[3] = {&Vec3::x, &Vec3::y, &Vec3::z};
};

constexpr Vec3 operator*(double s, const Vec3& v) { return v * s; }
constexpr double Dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 Cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr Vec3 MulComponents(const Vec3& a, const Vec3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
constexpr double LengthSquared(const Vec3& v) { return Dot(v, v); }
inline double Length(const Vec3& v) { return std::sqrt(Dot(v, v)); }
inline Vec3 Min(const Vec3& a, const Vec3& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 Max(const Vec3& a, const Vec3& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

// Returns v / |v|, or the zero vector when |v| == 0 (callers that must not see a zero
// vector check `Length` themselves first).
inline Vec3 Normalize(const Vec3& v) {
    double len = Length(v);
    return len > 0 ? v / len : Vec3{};
}

inline bool IsFinite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Two unit axes u, v perpendicular to n (spec §3.11.1): u = normalize(-n.y, n.x, 0), or
// normalize(n.z, 0, -n.x) if that is zero; v = normalize(n × u).
inline void CoordinateSystem(const Vec3& n, Vec3& u, Vec3& v) {
    Vec3 a{-n.y, n.x, 0};
    if (LengthSquared(a) == 0) a = {n.z, 0, -n.x};
    u = Normalize(a);
    v = Normalize(Cross(n, u));
}

struct Vec2 {
    double u = 0, v = 0;
};

struct Color {
    double r = 0, g = 0, b = 0;

    constexpr Color() = default;
    constexpr Color(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Color(double grey) : r(grey), g(grey), b(grey) {}

    constexpr Color operator+(const Color& o) const { return {r + o.r, g + o.g, b + o.b}; }
    constexpr Color operator-(const Color& o) const { return {r - o.r, g - o.g, b - o.b}; }
    constexpr Color operator*(const Color& o) const { return {r * o.r, g * o.g, b * o.b}; }
    constexpr Color operator*(double s) const { return {r * s, g * s, b * s}; }
    Color& operator+=(const Color& o) { r += o.r; g += o.g; b += o.b; return *this; }
    Color& operator*=(const Color& o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
    Color& operator*=(double s) { r *= s; g *= s; b *= s; return *this; }
    constexpr bool operator==(const Color& o) const { return r == o.r && g == o.g && b == o.b; }

    // True when any channel exceeds `threshold` (the shading model's cutoff tests).
    constexpr bool AnyAbove(double threshold) const {
        return r > threshold || g > threshold || b > threshold;
    }
};

constexpr Color operator*(double s, const Color& c) { return c * s; }

}  // namespace rs
