// What the C library does with memory freed during a run. By default glibc gives the top of its
// heap back to the kernel once more than 128 KB lies free there, and maps large blocks apart, to
// unmap them when freed: a configuration whose frame allocates and frees a lot (vfc's draws, in
// llvmpipe's binning) then leaves the next frame, whatever configuration renders it, to fault those
// pages back in. On a walled courtyard at 320×180 the configuration rendered after vfc paid about
// 1.4 ms a frame for it, and vfc about 8 ms of its own 17 (docs/results.md). A benchmark keeps the
// memory instead: what it measures is then the cullers, not the allocator's trimming.
#pragma once

#include <string>

namespace occsim {

// Keeps freed memory in the process for the rest of it (glibc's trim threshold and mmap threshold
// fixed high), unless the environment already sets either (MALLOC_TRIM_THRESHOLD_,
// MALLOC_MMAP_THRESHOLD_: the user's choice stands). Returns what holds, for summary.json:
// "kept" or "as the environment sets it (MALLOC_TRIM_THRESHOLD_=...)". Idempotent.
std::string keepFreedMemory();

}  // namespace occsim
