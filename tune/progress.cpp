#include "tune/progress.h"

#include <cstdio>

namespace occsim::tune {
namespace {

std::string duration(double seconds) {
    char buf[32];
    if (seconds < 90)
        std::snprintf(buf, sizeof buf, "%.0f s", seconds);
    else if (seconds < 5400)
        std::snprintf(buf, sizeof buf, "%.0f min", seconds / 60);
    else
        std::snprintf(buf, sizeof buf, "%.1f h", seconds / 3600);
    return buf;
}

}  // namespace

void Progress::frameDone() {
    ++done_;
    if (left_ > 0) --left_;
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && now - last_draw_ < std::chrono::milliseconds(250)) return;
    last_draw_ = now;
    draw();
}

void Progress::draw() {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = done_ > 0 ? elapsed / static_cast<double>(done_) : 0.0;
    std::string line =
        "\r" + stage_ + "  ~" + duration(rate * static_cast<double>(left_)) + " left";
    if (!best_.empty()) line += "  best " + best_;
    // Blank out what is left of a longer previous line.
    const size_t length = line.size();
    if (length < last_length_) line.append(last_length_ - length, ' ');
    last_length_ = length;
    std::fputs(line.c_str(), stderr);
    std::fflush(stderr);
    drawn_ = true;
}

void Progress::finish() {
    if (!enabled_ || !drawn_) return;
    std::fputc('\n', stderr);
    std::fflush(stderr);
    drawn_ = false;
}

}  // namespace occsim::tune
