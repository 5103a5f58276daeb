// Seconds of the steady clock since a moment: what the GL devices add to their counters of time
// spent submitting, polling and waiting.
#pragma once

#include <chrono>

namespace occsim {

inline double steadySecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace occsim
