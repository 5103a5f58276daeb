// How far a long run is, on stderr (run, bench, regress): on a terminal a bar redrawn in place at
// most four times a second; otherwise (a log, CI) a line every `line_every_s` seconds (10 by
// default) with the frame, the configurations, the time elapsed and the time left, so that a run
// of many minutes shows it is alive; nothing with --quiet. A run shorter than the interval prints
// no line, and stdout never carries progress.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace occsim {

enum class ProgressStyle { None, Bar, Lines };

// Bar when stderr is a terminal, Lines when it is not, None when `quiet`.
ProgressStyle stderrProgressStyle(bool quiet);

class RunProgress {
  public:
    // `what`: the scenario and its configurations ("teapots, 8 configurations"); `total_frames`
    // over every repetition, `frames_per_repetition` to say which repetition a frame is in.
    RunProgress(ProgressStyle style, std::string what, uint32_t total_frames,
                uint32_t frames_per_repetition, std::FILE* out = stderr,
                double line_every_s = 10.0);

    // `done` frames of every configuration are done, `elapsed_s` after the first frame began.
    void frameDone(uint32_t done, double elapsed_s);
    // Ends the bar's line when the run stopped before its last frame.
    void finish();

    // The texts, without the bar's carriage return: "frame 60/120 (repetition 1/2), teapots, 8
    // configurations, 35 s elapsed, about 35 s left".
    std::string status(uint32_t done, double elapsed_s) const;
    std::string bar(uint32_t done, double elapsed_s) const;  // "[#####-----] " + status

  private:
    ProgressStyle style_;
    std::string what_;
    uint32_t total_, per_repetition_;
    std::FILE* out_;
    double line_every_s_;
    double last_s_ = 0.0;
    bool open_line_ = false;  // a bar drawn and not ended
};

}  // namespace occsim
