// Ctrl-C (SIGINT) or SIGTERM as a request, honoured between frames: the handler only sets a flag
// (the simulator's, sim/run/stop_request.h), and the tuner stops at the next frame boundary
// (outside every timing) with its sample log whole. A second one ends the process at once, as
// usual.
#pragma once

namespace occsim::tune {

void installInterruptHandler();
bool interruptRequested();
// Throws Interrupted (tune/errors.h) when SIGINT arrived.
void throwIfInterrupted();

}  // namespace occsim::tune
