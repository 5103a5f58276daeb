// The exit codes every command shares: 0 done, 1 a failure while running (or failed checks), 2 bad
// input (an occsim::InputError, whichever module found it). A run that a signal stopped exits with
// 128 + the signal, as a shell reports a process the signal ended.
#pragma once

namespace occsim_cli {

inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

}  // namespace occsim_cli
