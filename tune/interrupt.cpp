#include "tune/interrupt.h"

#include <csignal>

#include "tune/errors.h"

namespace occsim::tune {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void onInterrupt(int) {
    g_interrupted = 1;
    std::signal(SIGINT, SIG_DFL);  // the next Ctrl-C is not a request
}

}  // namespace

void installInterruptHandler() { std::signal(SIGINT, onInterrupt); }

bool interruptRequested() { return g_interrupted != 0; }

void throwIfInterrupted() {
    if (interruptRequested()) throw Interrupted();
}

}  // namespace occsim::tune
