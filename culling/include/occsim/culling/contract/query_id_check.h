// The check every RenderDevice makes on the query ids it is handed: an id passed to
// isQueryReady() or takeAnswer() must have been issued and not yet taken. Anything else is a bug
// in the caller (a culler that takes an answer twice, or keeps an id past its answer), so it is
// reported with the device's name and the id and the process aborts, instead of going on with an
// answer that belongs to another query. The production devices check in debug builds only (the
// GL device still never releases an id twice in any build); the CPU test devices always check,
// since tests are where such a bug should show.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "occsim/culling/contract/render_device.h"

namespace occsim {

#ifdef NDEBUG
inline constexpr bool kCheckQueryIds = false;
#else
inline constexpr bool kCheckQueryIds = true;
#endif

// `why` says what is wrong with the id: "was never issued", "was already taken".
[[noreturn]] inline void failQueryId(const char* device, const char* call, QueryId id,
                                     const char* why) {
    std::fprintf(stderr, "occsim: %s::%s: query id %u %s (a bug in the caller)\n", device, call,
                 static_cast<unsigned>(id), why);
    std::fflush(stderr);
    std::abort();
}

}  // namespace occsim
