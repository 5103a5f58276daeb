// What one configuration's culling got wrong or wasted on each frame of its first repetition,
// object by object: the objects it missed (ground truth saw them, it did not draw them) and those
// it drew while ground truth saw none of their pixels. The worst windows are found after the run
// (worst_windows.h), so every frame's are kept until then, for the windows' pictures to show
// (BenchOptions::on_window_frame). Sparse, under a byte budget: a frame that would pass it keeps
// nothing, and at() says so; objects drawn and seen, or culled, are not kept.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace occsim {

struct FrameVerdicts {
    std::vector<uint32_t> missed;        // object indices, ascending
    std::vector<uint32_t> drawn_hidden;  // object indices, ascending
};

class VerdictLog {
  public:
    explicit VerdictLog(size_t budget_bytes) : budget_bytes_(budget_bytes) {}

    // Frame `frame`'s verdicts (Simulation::objectVerdicts(): an ObjectVerdict per object).
    // Frames are recorded in order; one past the budget, and every one after it, keeps nothing.
    void record(uint32_t frame, std::span<const uint8_t> verdicts);

    // The frame's lists; nullptr when it was not recorded or did not fit the budget.
    const FrameVerdicts* at(uint32_t frame) const;
    // Whether some recorded frame did not fit the budget.
    bool overflowed() const { return overflowed_; }
    size_t bytes() const { return bytes_; }

  private:
    size_t budget_bytes_;
    size_t bytes_ = 0;
    bool overflowed_ = false;
    std::vector<uint32_t> frame_index_;  // per frame: its place in frames_ + 1; 0: none
    std::vector<FrameVerdicts> frames_;
};

}  // namespace occsim
