// libFuzzer target, built once per entry of fuzzTargets() with OCCSIM_FUZZ_TARGET set to its
// name (tests/fuzz/CMakeLists.txt).
#include <cstdio>
#include <cstdlib>

#include "fuzz_inputs.h"

#ifndef OCCSIM_FUZZ_TARGET
#error "OCCSIM_FUZZ_TARGET names the fuzz target (a name of fuzzTargets())"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const occsim::fuzz::FuzzTarget* target = [] {
        const auto* t = occsim::fuzz::findFuzzTarget(OCCSIM_FUZZ_TARGET);
        if (!t) {
            std::fprintf(stderr, "fuzz: no target named '%s'\n", OCCSIM_FUZZ_TARGET);
            std::abort();
        }
        return t;
    }();
    target->input(data, size);
    return 0;
}
