#include "sim/run/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace occsim {

ProgressStyle stderrProgressStyle(bool quiet) {
    if (quiet) return ProgressStyle::None;
    return ::isatty(STDERR_FILENO) != 0 ? ProgressStyle::Bar : ProgressStyle::Lines;
}

RunProgress::RunProgress(ProgressStyle style, std::string what, uint32_t total_frames,
                         uint32_t frames_per_repetition, std::FILE* out, double line_every_s)
    : style_(style),
      what_(std::move(what)),
      total_(total_frames),
      per_repetition_(std::max(1u, frames_per_repetition)),
      out_(out),
      line_every_s_(line_every_s) {}

std::string RunProgress::status(uint32_t done, double elapsed_s) const {
    const double left = done > 0 ? elapsed_s / done * (total_ - done) : 0.0;
    char text[160];
    std::snprintf(text, sizeof text, "frame %u/%u", done, total_);
    std::string s = text;
    if (total_ > per_repetition_) {
        const uint32_t rep =
            std::min(done == 0 ? 0 : (done - 1) / per_repetition_, (total_ - 1) / per_repetition_);
        std::snprintf(text, sizeof text, " (repetition %u/%u)", rep + 1,
                      (total_ + per_repetition_ - 1) / per_repetition_);
        s += text;
    }
    std::snprintf(text, sizeof text, ", %.0f s elapsed, about %.0f s left", elapsed_s, left);
    return s + ", " + what_ + text;
}

std::string RunProgress::bar(uint32_t done, double elapsed_s) const {
    constexpr uint32_t kWidth = 20;
    const uint32_t filled = total_ > 0 ? kWidth * std::min(done, total_) / total_ : 0;
    std::string out(kWidth + 3, '-');
    out.front() = '[';
    std::fill(out.begin() + 1, out.begin() + 1 + filled, '#');
    out[kWidth + 1] = ']';
    out.back() = ' ';
    out.append(status(done, elapsed_s));
    return out;
}

void RunProgress::frameDone(uint32_t done, double elapsed_s) {
    const bool last = done >= total_;
    switch (style_) {
        case ProgressStyle::None:
            return;
        case ProgressStyle::Bar:
            if (!last && elapsed_s - last_s_ < 0.25 && open_line_) return;
            std::fprintf(out_, "\r%s   ", bar(done, elapsed_s).c_str());
            open_line_ = !last;
            if (last) std::fputc('\n', out_);
            break;
        case ProgressStyle::Lines:
            // A line when the interval has passed; none at the end of a short run, whose table
            // follows at once.
            if (elapsed_s - last_s_ < line_every_s_) return;
            std::fprintf(out_, "progress: %s\n", status(done, elapsed_s).c_str());
            break;
    }
    last_s_ = elapsed_s;
    std::fflush(out_);
}

void RunProgress::finish() {
    if (style_ == ProgressStyle::Bar && open_line_) std::fputc('\n', out_);
    open_line_ = false;
    std::fflush(out_);
}

}  // namespace occsim
