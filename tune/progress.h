// The tuner's progress line on a terminal (stderr): samples done, the estimated time left and the
// best sample so far, redrawn in place at most four times a second. Nothing when stderr is not a
// terminal, so logs and tests stay clean.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

namespace occsim::tune {

class Progress {
  public:
    explicit Progress(bool enabled) : enabled_(enabled) {}

    // Rendered frames (one configuration's frame each) still to come in this session.
    void setWorkLeft(uint64_t frames) { left_ = frames; }
    void setStage(std::string stage) { stage_ = std::move(stage); }
    void setBest(std::string best) { best_ = std::move(best); }
    // One configuration's frame was rendered.
    void frameDone();
    // Ends the line (before other output).
    void finish();

  private:
    void draw();

    bool enabled_;
    uint64_t left_ = 0, done_ = 0;
    std::string stage_, best_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point last_draw_{};
    bool drawn_ = false;
    size_t last_length_ = 0;
};

}  // namespace occsim::tune
