// A crash (SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL) inside a culler, a plugin's above all, ends
// the process: nothing can be saved then, but the one line the handler writes names the
// configuration and the frame in hand, so that the culler to blame is known. The handler writes
// with write(2) only (async-signal-safe) and re-raises the signal with its default action, so the
// exit status and any core dump are what they would have been without it.
#pragma once

#include <cstdint>

namespace occsim {

// Once per process, before the first frame.
void installCrashHandler();

// The configuration now rendering, and its frame. `label` must stay alive until the next call
// or clearCrashNote() (a RunConfig's label does, for the whole run).
void noteRendering(const char* label, uint32_t frame);
void clearCrashNote();

}  // namespace occsim
