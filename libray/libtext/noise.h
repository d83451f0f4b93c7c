// Perlin/Skinner lattice noise and its fractal sums (spec §3.12.1).
//
// The hash and gradient tables are built once, on first use, from drand48 seeded with 1 and
// a CRC-16 of fixed doubles, so every texture matches the original's pattern exactly.
// All functions are pure and thread-safe.
#pragma once

#include "libcommon/vector.h"

namespace rs {

// Scalar noise at p; roughly in [-1, 1], continuous with continuous first derivatives.
// Points are shifted by +10^6 per axis before the lattice lookup, as in the original; the
// lattice cell is the floor of the shifted coordinate everywhere (the original truncated,
// which differs only below −10^6).
double Noise(const Vec3& p);

// Vector noise at p on the same lattice; its x component equals Noise(p).
Vec3 DNoise(const Vec3& p);

// Σ_{j<octaves} 2^-j Noise(2^j p).
double Chaos(const Vec3& p, int octaves);

// Σ_{j<octaves} omega^j Noise(lambda^j p).
double FBm(const Vec3& p, double omega, double lambda, int octaves);

// Σ_{j<octaves} omega^j DNoise(lambda^j p), stopping before the first octave whose weight
// omega^j falls below kEpsilon.
Vec3 VFBm(const Vec3& p, double omega, double lambda, int octaves);

// The fbm-family octave weight for roughness H and lacunarity lambda:
// omega = lambda^-(1+2H)/2, so the power spectrum falls off as f^-(1+2H).
double FBmOmega(double h, double lambda);

// The table entry R[i] of spec §3.12.1 (0 ≤ i < 267), for tests.
double NoiseGradientTableEntry(int i);

}  // namespace rs
