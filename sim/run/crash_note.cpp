#include "sim/run/crash_note.h"

#include <unistd.h>

#include <csignal>
#include <cstring>

#include "sim/run/stop_request.h"

namespace occsim {
namespace {

// Read by the handler: a pointer and a number, each written whole by the frame loop.
const char* volatile g_label = nullptr;
volatile uint32_t g_frame = 0;

constexpr int kCrashSignals[] = {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL};

void writeText(const char* text) {
    // Nothing to do when stderr is gone: the exit status still tells.
    if (::write(STDERR_FILENO, text, std::strlen(text)) < 0) return;
}

void writeNumber(uint32_t n) {
    char digits[12];
    size_t i = sizeof digits - 1;
    digits[i] = '\0';
    do {
        digits[--i] = static_cast<char>('0' + n % 10);
        n /= 10;
    } while (n > 0 && i > 0);
    writeText(digits + i);
}

extern "C" void onCrash(int signal) {
    if (const char* label = g_label) {
        writeText("\noccsim: crashed (");
        writeText(signalName(signal));
        writeText(") in configuration '");
        writeText(label);
        writeText("' at frame ");
        writeNumber(g_frame);
        writeText("; the frames done so far are lost\n");
    }
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

}  // namespace

void installCrashHandler() {
    for (int signal : kCrashSignals) std::signal(signal, onCrash);
}

void noteRendering(const char* label, uint32_t frame) {
    g_frame = frame;
    g_label = label;
}

void clearCrashNote() { g_label = nullptr; }

}  // namespace occsim
