#include "sim/run/heap_policy.h"

#include <malloc.h>

#include <cstdlib>

namespace occsim {

std::string keepFreedMemory() {
    std::string set;
    for (const char* name : {"MALLOC_TRIM_THRESHOLD_", "MALLOC_MMAP_THRESHOLD_"}) {
        if (const char* value = std::getenv(name)) {
            set += (set.empty() ? "" : ", ") + std::string(name) + "=" + value;
        }
    }
    if (!set.empty()) return "as the environment sets it (" + set + ")";
    // Blocks up to 32 MB (glibc's own ceiling for its adaptive threshold) come from the heap, and
    // nothing freed goes back to the kernel before the process ends.
    mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 2147483647);
    return "kept";
}

}  // namespace occsim
