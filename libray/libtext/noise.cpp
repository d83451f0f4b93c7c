#include "libtext/noise.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

#include "libcommon/constants.h"
#include "libcommon/random.h"

namespace rs {
namespace {

// Lattice size: coordinates are reduced modulo 4096 before hashing.
constexpr int kHashSize = 4096;
constexpr int kHashMask = kHashSize - 1;
// Gradient table: a lattice corner hashes to m in [0, 255] and DNoise reads up to R[m + 11].
constexpr int kGradientSize = 256 + 11;
// Shift applied to every coordinate so lattice indices are positive for |p| < 10^6.
constexpr double kNoiseShift = 1e6;

// CRC-16/ARC (reflected polynomial 0xA001, initial value 0) of `size` bytes.
uint16_t Crc16Arc(const uint8_t* bytes, int size) {
    uint16_t crc = 0;
    for (int i = 0; i < size; ++i) {
        crc ^= bytes[i];
        for (int bit = 0; bit < 8; ++bit) crc = (crc & 1) ? (crc >> 1) ^ 0xA001 : crc >> 1;
    }
    return crc;
}

struct NoiseTables {
    int hash[kHashSize];
    double gradient[kGradientSize];

    NoiseTables() {
        // H: a permutation of 0…4095 shuffled by drand48 seeded with 1.
        for (int i = 0; i < kHashSize; ++i) hash[i] = i;
        Drand48 random(1);
        for (int i = kHashSize - 1; i > 0; --i) {
            int j = static_cast<int>(random.Next() * kHashSize);
            std::swap(hash[i], hash[j]);
        }
        // R[i]: CRC of three copies of i·0.12345 as little-endian IEEE doubles, mapped from
        // [0, 65536) to [-1, 1).
        for (int i = 0; i < kGradientSize; ++i) {
            uint64_t bits = std::bit_cast<uint64_t>(i * 0.12345);
            uint8_t bytes[24];
            for (int copy = 0; copy < 3; ++copy) {
                for (int b = 0; b < 8; ++b) bytes[copy * 8 + b] = (bits >> (8 * b)) & 0xFF;
            }
            gradient[i] = Crc16Arc(bytes, 24) * 2.0 / 65536.0 - 1.0;
        }
    }
};

const NoiseTables& Tables() {
    static const NoiseTables tables;
    return tables;
}

// One axis of the lattice: the two corner indices (mod 4096), the fraction f in [0, 1) and
// the smoothstep weight s = f²(3 − 2f).
struct Axis {
    int i0, i1;
    double f, s;
};

inline Axis MakeAxis(double coordinate) {
    double q = coordinate + kNoiseShift;
    long i = static_cast<long>(q);
    if (q < static_cast<double>(i)) --i;  // floor for the (unsupported) far negative range
    Axis a;
    a.f = q - static_cast<double>(i);
    a.s = a.f * a.f * (3.0 - 2.0 * a.f);
    a.i0 = static_cast<int>(i & kHashMask);
    a.i1 = static_cast<int>((i + 1) & kHashMask);
    return a;
}

// The eight corners' gradient offsets m (already reduced to [0, 255]) and weights, in the
// order (cx, cy, cz) = 000, 100, 010, 110, 001, 101, 011, 111.
struct Lattice {
    int m[8];
    double w[8];
    double fx, fy, fz;
};

inline Lattice MakeLattice(const NoiseTables& t, const Vec3& p) {
    Axis x = MakeAxis(p.x), y = MakeAxis(p.y), z = MakeAxis(p.z);
    const int* h = t.hash;
    int hx0 = h[x.i0], hx1 = h[x.i1];
    int hxy[4] = {h[hx0 ^ y.i0], h[hx1 ^ y.i0], h[hx0 ^ y.i1], h[hx1 ^ y.i1]};
    double wxy[4] = {(1 - x.s) * (1 - y.s), x.s * (1 - y.s), (1 - x.s) * y.s, x.s * y.s};
    Lattice l;
    for (int k = 0; k < 4; ++k) {
        l.m[k] = h[hxy[k] ^ z.i0] & 255;
        l.m[k + 4] = h[hxy[k] ^ z.i1] & 255;
        l.w[k] = wxy[k] * (1 - z.s);
        l.w[k + 4] = wxy[k] * z.s;
    }
    l.fx = x.f;
    l.fy = y.f;
    l.fz = z.f;
    return l;
}

// Σ over corners of w·(½R[m+o] + R[m+o+1](fx−cx) + R[m+o+2](fy−cy) + R[m+o+3](fz−cz)).
inline double Sum(const Lattice& l, const double* r, int o) {
    double sum = 0;
    for (int k = 0; k < 8; ++k) {
        const double* g = r + l.m[k] + o;
        double dx = l.fx - (k & 1), dy = l.fy - ((k >> 1) & 1), dz = l.fz - (k >> 2);
        sum += l.w[k] * (0.5 * g[0] + g[1] * dx + g[2] * dy + g[3] * dz);
    }
    return sum;
}

}  // namespace

double Noise(const Vec3& p) {
    const NoiseTables& t = Tables();
    return Sum(MakeLattice(t, p), t.gradient, 0);
}

Vec3 DNoise(const Vec3& p) {
    const NoiseTables& t = Tables();
    Lattice l = MakeLattice(t, p);
    return {Sum(l, t.gradient, 0), Sum(l, t.gradient, 4), Sum(l, t.gradient, 8)};
}

double Chaos(const Vec3& p, int octaves) {
    double sum = 0, weight = 1;
    Vec3 q = p;
    for (int j = 0; j < octaves; ++j) {
        sum += weight * Noise(q);
        weight *= 0.5;
        q *= 2.0;
    }
    return sum;
}

double FBm(const Vec3& p, double omega, double lambda, int octaves) {
    double sum = 0, weight = 1;
    Vec3 q = p;
    for (int j = 0; j < octaves; ++j) {
        sum += weight * Noise(q);
        weight *= omega;
        q *= lambda;
    }
    return sum;
}

Vec3 VFBm(const Vec3& p, double omega, double lambda, int octaves) {
    Vec3 sum;
    double weight = 1;
    Vec3 q = p;
    for (int j = 0; j < octaves && weight >= kEpsilon; ++j) {
        sum += weight * DNoise(q);
        weight *= omega;
        q *= lambda;
    }
    return sum;
}

double FBmOmega(double h, double lambda) { return std::pow(lambda, -0.5 - h); }

double NoiseGradientTableEntry(int i) { return Tables().gradient[i]; }

}  // namespace rs
