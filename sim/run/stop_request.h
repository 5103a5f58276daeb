// SIGINT and SIGTERM as a request to stop, honoured between frames: the handler only records the
// signal, and runBenchmark() ends after the frame in hand with what it has, marked partial
// (BenchResult::partial), for the command to write and report before it exits 128 + signal. A
// second signal of the same kind ends the process at once, as usual.
#pragma once

namespace occsim {

// For SIGINT and SIGTERM; a command that runs frames calls it once before its first run.
void installStopHandlers();

// The signal that asked to stop (SIGINT or SIGTERM), or 0 when none arrived.
int stopSignal();

// "SIGINT", "SIGTERM", "SIGSEGV", ...: a signal's name for the one-line messages.
const char* signalName(int signal);

}  // namespace occsim
