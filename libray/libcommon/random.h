// Random numbers.
//
// Rng: the renderer's stream. It is seeded per pixel (and frame, and pass), never per
// thread, so images are bit-identical whatever the number of threads.
// Drand48: the POSIX drand48 generator, reproduced exactly; the noise tables are built
// from it seeded with 1 (spec §3.12.1) so textures match the original's.
#pragma once

#include <cstdint>

namespace rs {

class Rng {
  public:
    Rng() = default;
    explicit Rng(uint64_t seed) { Seed(seed); }

    // Seeds from up to four integers (pixel x, y, frame, purpose) by hashing them together.
    static Rng ForKey(uint64_t a, uint64_t b = 0, uint64_t c = 0, uint64_t d = 0) {
        uint64_t h = Mix(a + 0x9e3779b97f4a7c15ULL);
        h = Mix(h ^ (b + 0x632be59bd9b4e019ULL));
        h = Mix(h ^ (c + 0x8cb92ba72f3d8dd7ULL));
        h = Mix(h ^ (d + 0x4f1bbcdcbfa53e0bULL));
        return Rng(h);
    }

    void Seed(uint64_t seed) {
        // xoshiro256** state filled by splitmix64 (never all zero).
        for (uint64_t& s : state_) {
            seed += 0x9e3779b97f4a7c15ULL;
            s = Mix(seed);
        }
    }

    uint64_t NextU64() {
        uint64_t result = Rotl(state_[1] * 5, 7) * 9;
        uint64_t t = state_[1] << 17;
        state_[2] ^= state_[0];
        state_[3] ^= state_[1];
        state_[1] ^= state_[2];
        state_[0] ^= state_[3];
        state_[2] ^= t;
        state_[3] = Rotl(state_[3], 45);
        return result;
    }

    // Uniform in [0, 1): the top 53 bits scaled by 2^-53.
    double Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }

  private:
    static uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    static uint64_t Mix(uint64_t z) {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    uint64_t state_[4] = {1, 2, 3, 4};
};

// POSIX drand48: x ← (0x5DEECE66D·x + 0xB) mod 2^48, value x / 2^48; srand48(s) sets the
// high 32 bits of x to s and the low 16 bits to 0x330E.
class Drand48 {
  public:
    explicit Drand48(uint32_t seed) : x_((static_cast<uint64_t>(seed) << 16) | 0x330E) {}
    double Next() {
        x_ = (0x5DEECE66DULL * x_ + 0xB) & ((1ULL << 48) - 1);
        return static_cast<double>(x_) / static_cast<double>(1ULL << 48);
    }

  private:
    uint64_t x_;
};

}  // namespace rs
