// `occsim masked-replay FILE.mocrec`: replays a frame recorded by Intel's Masked Occlusion
// Culling (its frame recorder) into masked's buffer and into an exact depth raster at the
// recorded resolution, for every cell layout, and prints how much of what the exact buffer hides
// masked finds too (sim/run/masked_replay.h); writes both buffers' depth side by side.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace occsim_cli {

struct MaskedReplayFlags {
    std::string file;
    std::string out;  // default out/masked-replay/<file stem>
    uint64_t seed = 1;
};

CLI::App* addMaskedReplay(CLI::App& app, MaskedReplayFlags& flags);
// Prints the table; 0 when masked hid nothing the exact buffer sees, 1 otherwise (bad input
// throws occsim::InputError).
int maskedReplayCommand(const MaskedReplayFlags& flags);

}  // namespace occsim_cli
