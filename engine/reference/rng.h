// Random numbers for the path-traced reference: one independent stream per (seed, pixel, sample), so that an
// image is the same for a seed whatever the thread count or the way samples are split into calls.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

namespace vct::reference {

// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms for Random
// Number Generation"), XSH-RR output on a 64-bit LCG.
class Pcg32 {
  public:
    Pcg32(uint64_t seed, uint64_t stream) {
        state_ = 0;
        increment_ = (stream << 1u) | 1u;
        next();
        state_ += seed;
        next();
    }
    uint32_t next() {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ull + increment_;
        const uint32_t xorShifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        const uint32_t rotation = uint32_t(old >> 59u);
        return (xorShifted >> rotation) | (xorShifted << ((32u - rotation) & 31u));
    }
    // Uniform in [0, 1): 24 random bits, so 1 is never returned.
    float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }
    glm::vec2 uniform2() {
        const float a = uniform();
        return glm::vec2(a, uniform());
    }

  private:
    uint64_t state_, increment_;
};

// SplitMix64 finaliser (Steele et al. 2014): decorrelates nearby keys (pixel and sample indices).
inline uint64_t mixBits(uint64_t x) {
    x ^= x >> 30u;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27u;
    x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31u);
}

// The stream of sample `sample` of pixel `pixel` for `seed`.
inline Pcg32 sampleRng(uint64_t seed, uint64_t pixel, uint64_t sample) {
    return Pcg32(mixBits(seed ^ mixBits(pixel * 0x9e3779b97f4a7c15ull + sample)), mixBits(pixel) ^ sample);
}

}  // namespace vct::reference
