#include "tune/interrupt.h"

#include "sim/run/stop_request.h"
#include "tune/errors.h"

namespace occsim::tune {

// The simulator's stop request (sim/run/stop_request.h): one flag for SIGINT and SIGTERM, which
// runBenchmark() reads too, so a signal between a frame's hook and the loop's own check still
// ends the session as an interruption (measure.cpp).
void installInterruptHandler() { installStopHandlers(); }

bool interruptRequested() { return stopSignal() != 0; }

void throwIfInterrupted() {
    if (interruptRequested()) throw Interrupted();
}

}  // namespace occsim::tune
