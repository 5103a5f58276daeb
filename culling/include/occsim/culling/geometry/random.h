// The project's one seeded random generator and hash, shared by the scene generators (sim/) and
// the cullers that randomise decisions (CHC++'s re-test intervals), so that scenes and decisions
// are identical on every machine and standard library (std::uniform_real_distribution is
// implementation-defined).
#pragma once

#include <cstdint>

namespace occsim {

inline constexpr uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;

// SplitMix64 (Steele, Lea & Flood, "Fast Splittable Pseudorandom Number Generators", OOPSLA
// 2014): the output of a generator whose state is x, i.e. a well-mixed 64-bit hash of x.
inline uint64_t splitMix64(uint64_t x) {
    uint64_t z = x + kGoldenGamma;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// SplitMix64 as a stream: 64-bit state, passes BigCrush, trivially seedable.
class Rng {
  public:
    explicit Rng(uint64_t seed) : state_(seed) {}

    uint64_t next() {
        const uint64_t out = splitMix64(state_);
        state_ += kGoldenGamma;
        return out;
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
