// Ctrl-C (SIGINT) as a request, honoured between frames: the handler only sets a flag, and the
// tuner stops at the next frame boundary (outside every timing) with its sample log whole. A
// second Ctrl-C ends the process at once, as usual.
#pragma once

namespace occsim::tune {

void installInterruptHandler();
bool interruptRequested();
// Throws Interrupted (tune/errors.h) when SIGINT arrived.
void throwIfInterrupted();

}  // namespace occsim::tune
