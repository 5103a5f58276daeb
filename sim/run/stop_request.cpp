#include "sim/run/stop_request.h"

#include <csignal>

namespace occsim {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void onStopSignal(int signal) {
    g_stop_signal = signal;
    std::signal(signal, SIG_DFL);  // the next one is not a request
}

}  // namespace

void installStopHandlers() {
    std::signal(SIGINT, onStopSignal);
    std::signal(SIGTERM, onStopSignal);
}

int stopSignal() { return g_stop_signal; }

const char* signalName(int signal) {
    switch (signal) {
        case SIGINT:
            return "SIGINT";
        case SIGTERM:
            return "SIGTERM";
        case SIGSEGV:
            return "SIGSEGV";
        case SIGABRT:
            return "SIGABRT";
        case SIGBUS:
            return "SIGBUS";
        case SIGFPE:
            return "SIGFPE";
        case SIGILL:
            return "SIGILL";
        default:
            return "a signal";
    }
}

}  // namespace occsim
