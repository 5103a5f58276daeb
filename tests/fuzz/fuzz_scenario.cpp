// libFuzzer target: the scenario parser (JSON reader, every section reader, expectations).
#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    occsim::fuzz::scenarioInput(data, size);
    return 0;
}
