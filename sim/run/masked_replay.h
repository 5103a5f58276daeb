// A recorded frame of occluders (Intel MOC's frame recorder, sim/scene/mocrec.h) replayed into
// masked's software depth buffer and into an exact depth raster of the same triangles at the
// recorded resolution, then both asked about the same screen rectangles: how much of what the
// exact buffer hides masked finds hidden too, and whether masked ever hides what the exact buffer
// sees (it must not). `occsim masked-replay` prints it (docs/masked.md).
//
// The rectangles:
//  - every 8×4 block of the screen and every 32×32 block (the last row and column cut at the
//    edge), each tested at two depths from the exact buffer's farthest 1/w over its pixel
//    centres, d: just behind it (d · 0.99, which the exact buffer hides) and just in front of it
//    (d · 1.01, which it sees); a block with an uncovered pixel centre is tested once, at the far
//    end of the view, where the exact buffer sees it;
//  - object-sized rectangles: 4,000 of 16 to 256 pixels a side at seeded random places, each at
//    a depth sampled from the exact buffer (its 1/w at a random covered pixel of the screen),
//    as if an object stood somewhere in the scene; hidden or seen there as the exact buffer says.
//    Both buffers draw both faces of every triangle, clipped at the recorded near
// plane (masked a little beyond it, as always); MOC culled the back faces the record names.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "occsim/culling/raster/masked_depth_buffer.h"
#include "sim/scene/mocrec.h"

namespace occsim {

struct ReplayLayout {
    std::string name;  // "8x4", "32x4", "32x8"
    MaskedLayout layout;
};
// The reference implementation's 8×4 cell (its AVX2 and SSE builds alike), 32×4 and 32×8 (one
// cell per tile: this project's masked before 2026-12-04).
std::vector<ReplayLayout> replayLayouts();

// What one set of rectangles found with one layout.
struct ReplayTally {
    uint64_t exact_hidden = 0;                               // tests the exact buffer hides
    uint64_t both_hidden = 0;                                // of those, the ones masked hides too
    double exact_hidden_area = 0.0, both_hidden_area = 0.0;  // the same weighted by pixels
    uint64_t tests = 0;
    uint64_t wrongly_hidden = 0;  // masked hides, the exact buffer sees: must be 0
    double share() const;         // both_hidden / exact_hidden (1 when nothing is hidden)
    double areaShare() const;
};

struct ReplaySet {
    std::string name;  // "8x4 blocks", "32x32 blocks", "objects"
    ReplayTally tally;
};

struct LayoutReplay {
    std::string layout;
    std::vector<ReplaySet> sets;
    ReplayTally total;
    double raster_ms = 0.0;     // rasterising every occluder into masked's buffer, this layout
    std::vector<float> bounds;  // per viewport pixel, the 1/w masked hides behind (0: none)
    // Per 8×4 block (row-major, ceil(width / 8) across): 1 where the exact buffer hides the block
    // just behind its farthest pixel and masked does not.
    std::vector<uint8_t> missed_blocks;
};

struct MaskedReplay {
    uint32_t width = 0, height = 0;
    uint64_t triangles = 0;
    std::vector<double> exact;  // per viewport pixel, the exact buffer's nearest 1/w (0: empty)
    std::vector<LayoutReplay> layouts;
};

// Replays `frame` with each layout (the AVX2 kernels where the CPU has them). `seed` places the
// object-sized rectangles.
MaskedReplay replayMaskedFrame(const MocFrame& frame, std::span<const ReplayLayout> layouts,
                               uint64_t seed = 1);

// Both buffers' depth side by side, exact on the left, masked's first layout on the right, each
// halved to (width / 2) × (height / 2): RGBA8, rows bottom-up. Nearer is brighter (by log w from
// the near plane to the farthest depth either holds); black where nothing is known; on masked's
// side, red where it misses an 8×4 block the exact buffer hides.
std::vector<uint8_t> replayDepthPicture(const MaskedReplay& replay, double near_w,
                                        uint32_t* picture_width, uint32_t* picture_height);

}  // namespace occsim
