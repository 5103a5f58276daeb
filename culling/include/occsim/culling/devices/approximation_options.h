// Two ways to trade image error for time, for any culler that issues queries (applied by
// ApproximateDevice, approximate_device.h):
// - threshold_pixels: a query passing at most this many samples counts as occluded (the CHC
//   paper's approximate visibility, n_vp);
// - stale_results: a result not ready when the culler asks for it is taken from the last frame's
//   query on the same boxes instead of waited for.
// Both make conservative cullers approximate; with both off nothing changes.
#pragma once

#include <cstdint>

namespace occsim {

struct ApproximationOptions {
    uint32_t threshold_pixels = 0;
    bool stale_results = false;

    bool active() const { return threshold_pixels > 0 || stale_results; }
};

}  // namespace occsim
