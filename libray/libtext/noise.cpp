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
// Shift applied to every coordinate (the original's), keeping indices positive above −10^6.
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

// One axis of the lattice: the two corner indices (mod 4096), the offsets f and f − 1 from
// those corners, and the smoothstep weights 1 − s and s with s = f²(3 − 2f).
struct Axis {
    int i0, i1;
    double d0, d1;
    double w0, w1;
};

inline Axis MakeAxis(double coordinate) {
    double q = coordinate + kNoiseShift;
    long i = static_cast<long>(q);
    if (q < static_cast<double>(i)) --i;  // floor, also below −10^6
    Axis a;
    double f = q - static_cast<double>(i);
    double s = f * f * (3.0 - 2.0 * f);
    a.i0 = static_cast<int>(i & kHashMask);
    a.i1 = static_cast<int>((i + 1) & kHashMask);
    a.d0 = f;
    a.d1 = f - 1.0;
    a.w0 = 1.0 - s;
    a.w1 = s;
    return a;
}

// Two doubles operated on lane by lane (SSE2 on x86-64; GCC and Clang vector extension).
// Each lane rounds exactly as the same scalar operation would.
typedef double Double2 __attribute__((vector_size(16)));

// The eight corners (cx, cy, cz) of the cell around p, k = cx + 2·cy + 4·cz: gradient
// offsets m in [0, 255], and per axis the offsets of p from the two corner planes and the
// smoothstep weights. The x axis is held as lane pairs (cx = 0, 1), so the corners are
// summed two at a time.
struct Lattice {
    int m[8];
    Double2 dx, wx;
    double dy[2], dz[2];
    double wy[2], wz[2];
};

inline void MakeLattice(const int* h, const Vec3& p, Lattice& l) {
    Axis x = MakeAxis(p.x), y = MakeAxis(p.y), z = MakeAxis(p.z);
    int hx[2] = {h[x.i0], h[x.i1]};
    int iy[2] = {y.i0, y.i1}, iz[2] = {z.i0, z.i1};
    for (int k = 0; k < 8; ++k) {
        int cx = k & 1, cy = (k >> 1) & 1, cz = k >> 2;
        l.m[k] = h[h[hx[cx] ^ iy[cy]] ^ iz[cz]] & 255;
    }
    l.dx = Double2{x.d0, x.d1};
    l.wx = Double2{x.w0, x.w1};
    l.dy[0] = y.d0;
    l.dy[1] = y.d1;
    l.dz[0] = z.d0;
    l.dz[1] = z.d1;
    l.wy[0] = y.w0;
    l.wy[1] = y.w1;
    l.wz[0] = z.w0;
    l.wz[1] = z.w1;
}

// Σ over corners, in order k = 0…7, of w·(½R[m+o] + R[m+o+1]·dx + R[m+o+2]·dy + R[m+o+3]·dz)
// with w = wx·wy·wz: the corners of each x pair are evaluated in the two lanes with the same
// operations in the same order, then added to the sum one after the other, so the result is
// bit-identical to the corner-by-corner loop.
inline double Sum(const Lattice& l, const double* r, int o) {
    double sum = 0;
    for (int pair = 0; pair < 4; ++pair) {
        const int cy = pair & 1, cz = pair >> 1;
        const double* g0 = r + l.m[2 * pair] + o;
        const double* g1 = r + l.m[2 * pair + 1] + o;
        const Double2 w = l.wx * l.wy[cy] * l.wz[cz];
        const Double2 term = w * (0.5 * Double2{g0[0], g1[0]} + Double2{g0[1], g1[1]} * l.dx +
                                  Double2{g0[2], g1[2]} * l.dy[cy] +
                                  Double2{g0[3], g1[3]} * l.dz[cz]);
        sum += term[0];
        sum += term[1];
    }
    return sum;
}

}  // namespace

double Noise(const Vec3& p) {
    const NoiseTables& t = Tables();
    Lattice l;
    MakeLattice(t.hash, p, l);
    return Sum(l, t.gradient, 0);
}

Vec3 DNoise(const Vec3& p) {
    const NoiseTables& t = Tables();
    Lattice l;
    MakeLattice(t.hash, p, l);
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
