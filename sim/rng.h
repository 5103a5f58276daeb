// A small seeded random generator with our own distributions, so that scenes are identical on
// every machine and standard library (std::uniform_real_distribution is implementation-defined).
#pragma once

#include <cstdint>

namespace occsim {

// SplitMix64 (Steele, Lea, Flood 2014): 64-bit state, passes BigCrush, trivially seedable.
class Rng {
public:
    explicit Rng(uint64_t seed) : state_(seed) {}

    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1).
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    // Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; bias below 2^-32 for our sizes).
    uint32_t below(uint32_t n) {
        return static_cast<uint32_t>(((next() >> 32) * static_cast<uint64_t>(n)) >> 32);
    }

private:
    uint64_t state_;
};

// Derives an independent stream for one purpose, so that adding a mover does not move teapots.
inline uint64_t deriveSeed(uint64_t seed, uint64_t stream, uint64_t purpose) {
    Rng r(seed ^ (stream * 0xD1B54A32D192ED03ull) ^ (purpose * 0xABC98388FB8FAC03ull));
    return r.next();
}

}  // namespace occsim
