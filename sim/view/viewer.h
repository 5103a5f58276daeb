// `occsim view`: a window on the same simulation that `run` measures (sim/run/simulation.h),
// one frame at a time, with the camera on the scenario's path or flown by hand, live algorithm
// switching, node boxes, the bird's-eye inset, ground truth, screenshots and flight recording
// into a new scenario. docs/viewer.md describes the keys, the flags and the script format.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "sim/scenario/scenario.h"
#include "sim/view/view_script.h"

namespace occsim {

struct ViewOptions {
    std::string algorithm;             // empty: the scenario's
    bool error = false;                // ground truth from the first frame
    uint32_t width = 0, height = 0;    // the window; 0: the scenario's viewport, enlarged if small
    std::optional<ViewScript> script;  // scripted input: fixed time steps, closes at its end
    std::filesystem::path out_dir;     // screenshots and recorded scenarios
};

// Opens the window and runs until it is closed (0). `scenario_text` is the file `scenario` was
// parsed from, the base of recorded scenarios. Throws WindowUnavailable (render/glfw_context.h)
// when no window can be opened, before building the scene.
int runViewer(const Scenario& scenario, const std::string& scenario_text,
              const ViewOptions& options);

}  // namespace occsim
