// keepFreedMemory() (sim/run/heap_policy.h): after it, memory a frame frees stays with the
// process, so the next frame, whatever configuration renders it, does not fault it back in. The
// default policy is shown giving it back first, so the test can fail.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>
#include <vector>

#include "sim/run/heap_policy.h"

namespace occsim {
namespace {

// Bytes the heap gave back to the kernel when 64 MB in 64 KB blocks, allocated and written as a
// frame's binning memory is, were freed in reverse order.
size_t givenBackAfterAFrame() {
    std::vector<char*> blocks;
    for (int i = 0; i < 1024; ++i) {
        blocks.push_back(static_cast<char*>(std::malloc(64 * 1024)));
        blocks.back()[0] = 1;
        blocks.back()[64 * 1024 - 1] = 1;
    }
    const size_t peak = mallinfo2().arena;
    for (auto it = blocks.rbegin(); it != blocks.rend(); ++it) std::free(*it);
    const size_t after = mallinfo2().arena;
    return peak > after ? peak - after : 0;
}

TEST(HeapPolicy, MemoryAFrameFreesStaysWithTheProcess) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer's allocator replaces glibc's: no trim threshold to keep";
#endif
    ASSERT_EQ(std::getenv("MALLOC_TRIM_THRESHOLD_"), nullptr);
    ASSERT_EQ(std::getenv("MALLOC_MMAP_THRESHOLD_"), nullptr);
    // glibc's default: the free top of the heap goes back to the kernel.
    mallopt(M_TRIM_THRESHOLD, 128 * 1024);
    mallopt(M_MMAP_THRESHOLD, 128 * 1024 * 1024);
    EXPECT_GE(givenBackAfterAFrame(), size_t{16} << 20);

    EXPECT_EQ(keepFreedMemory(), "kept");
    EXPECT_EQ(givenBackAfterAFrame(), 0u);
    EXPECT_EQ(keepFreedMemory(), "kept");
}

TEST(HeapPolicy, TheEnvironmentsChoiceStands) {
    ASSERT_EQ(setenv("MALLOC_TRIM_THRESHOLD_", "131072", 1), 0);
    EXPECT_EQ(keepFreedMemory(), "as the environment sets it (MALLOC_TRIM_THRESHOLD_=131072)");
    ASSERT_EQ(setenv("MALLOC_MMAP_THRESHOLD_", "65536", 1), 0);
    EXPECT_EQ(keepFreedMemory(),
              "as the environment sets it (MALLOC_TRIM_THRESHOLD_=131072, "
              "MALLOC_MMAP_THRESHOLD_=65536)");
    unsetenv("MALLOC_TRIM_THRESHOLD_");
    unsetenv("MALLOC_MMAP_THRESHOLD_");
}

}  // namespace
}  // namespace occsim
