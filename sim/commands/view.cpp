#include "sim/commands/view.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "occsim/culling/contract/input_error.h"
#include "render/glfw_context.h"
#include "sim/commands/exit_codes.h"
#include "sim/commands/flag_checks.h"
#include "sim/commands/shared_flags.h"
#include "sim/output/run_folder.h"
#include "sim/scenario/scenario.h"
#include "sim/view/view_script.h"
#include "sim/view/viewer.h"

namespace occsim_cli {

CLI::App* addView(CLI::App& app, ViewFlags& flags) {
    CLI::App* view = app.add_subcommand("view",
                                        "Watch a scenario in a window: fly, switch "
                                        "algorithms live, record a camera path "
                                        "(docs/viewer.md)");
    view->add_option("scenario", flags.scenario, "Scenario file (JSON)")->required();
    view->add_option(
        "--algo", flags.algorithm,
        "Culling algorithm to start with (default: the scenario's): " + occsim::cullerNameList());
    view->add_flag("--error", flags.error,
                   "Render ground truth every frame and show error pixels (key g)");
    view->add_option(
        "--size", flags.size,
        "Window size WIDTHxHEIGHT (default: the scenario's viewport, enlarged when small)");
    view->add_option("--script", flags.script,
                     "Drive the window from a script file, then close it");
    addPluginFlag(view, flags.plugins);
    view->add_option(
        "--out", flags.out,
        "Folder for screenshots and recorded scenarios (default: out/<scenario>/view)");
    return view;
}

int viewCommand(const ViewFlags& flags) {
    loadPlugins(flags.plugins);
    occsim::ViewOptions options;
    occsim::Scenario scenario = occsim::parseScenarioFile(flags.scenario);
    if (scenario.stereo) {
        // The window shows one view: the camera's, midway between the eyes.
        std::fprintf(stderr,
                     "note: %s: the viewer shows the camera midway between the eyes; stereo is "
                     "rendered by run, bench and regress (docs/views.md)\n",
                     flags.scenario.c_str());
        scenario.stereo.reset();
    }
    if (!flags.algorithm.empty())
        options.algorithm = algorithmNamed("--algo", flags.algorithm).name;
    options.error = flags.error;
    if (!flags.size.empty()) {
        unsigned w = 0, h = 0;
        char extra = 0;
        if (std::sscanf(flags.size.c_str(), "%ux%u%c", &w, &h, &extra) != 2 || w < 16 || h < 16 ||
            w > 8192 || h > 8192) {
            throw occsim::InputError("--size: expected WIDTHxHEIGHT, each in [16, 8192], got '" +
                                     flags.size + "'");
        }
        options.width = w;
        options.height = h;
    }
    if (!flags.script.empty()) options.script = occsim::readViewScript(flags.script);
    options.out_dir = flags.out.empty() ? occsim::defaultOutputFolder(scenario.name, "view")
                                        : std::filesystem::path(flags.out);
    // Recorded flights are the loaded scenario with a new camera path: keep its text.
    std::ifstream in(flags.scenario, std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    try {
        return occsim::runViewer(scenario, text, options);
    } catch (const occsim::WindowUnavailable& e) {
        // Bad input too (exit 2), in a line of its own: what to do without a window.
        std::fprintf(stderr,
                     "occsim view: cannot open a window: %s; the headless commands need no display "
                     "(occsim run|bench|regress SCENARIO), or run the viewer under xvfb-run\n",
                     e.what());
        return kExitBadInput;
    }
}

}  // namespace occsim_cli
