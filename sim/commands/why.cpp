#include "sim/commands/why.h"

#include <cstdio>

#include "occsim/culling/contract/input_error.h"
#include "sim/commands/flag_checks.h"
#include "sim/output/console_table.h"
#include "sim/record/why.h"

namespace occsim_cli {

CLI::App* addWhy(CLI::App& app, WhyFlags& flags) {
    CLI::App* why = app.add_subcommand(
        "why", "Say why objects were drawn or left out, from a run recorded with --record objects");
    why->add_option("run", flags.run, "Run folder (the --out of run, bench or regress)")
        ->required();
    why->add_option("--object", flags.object,
                    "The object, by index or name: each configuration's decision and reason");
    why->add_option("--frame", flags.frame, "Only this frame (with --object)")
        ->check(integerIn(0, 9999999));
    why->add_option("--algo", flags.algo,
                    "Only this configuration (its label), or every configuration of this "
                    "algorithm");
    why->add_flag("--overdraw", flags.overdraw,
                  "The objects each configuration drew while ground truth saw none of them");
    why->add_flag("--missed", flags.missed,
                  "Every object ground truth saw that a configuration did not draw");
    why->add_option("--view", flags.view,
                    "Whose decisions: camera (the default; the left eye's in a stereo run culled "
                    "per eye), left, right (a stereo run culled per eye) or light (the light's "
                    "view, culled with --shadow-casters culler or culler+receivers)");
    why->add_option("--limit", flags.limit, "Over-drawn objects listed per configuration (20)")
        ->check(integerIn(1, 1000000));
    return why;
}

int whyCommand(const WhyFlags& flags) {
    occsim::WhyRequest request;
    request.run = flags.run;
    request.object = flags.object;
    if (flags.frame >= 0) request.frame = static_cast<uint32_t>(flags.frame);
    request.algo = flags.algo;
    request.overdraw = flags.overdraw;
    request.missed = flags.missed;
    request.limit = flags.limit;
    if (flags.view != "camera" && flags.view != "left" && flags.view != "right" &&
        flags.view != "light") {
        throw occsim::InputError("--view: expected camera, left, right or light, got '" +
                                 flags.view + "'");
    }
    request.view = flags.view == "right"   ? occsim::RecordedView::RightEye
                   : flags.view == "light" ? occsim::RecordedView::Light
                                           : occsim::RecordedView::Camera;
    request.left_eye = flags.view == "left";
    // Lines that fit a terminal (100 columns), each broken one indented under its start.
    std::fputs(occsim::wrappedText(occsim::answerWhy(request)).c_str(), stdout);
    return 0;
}

}  // namespace occsim_cli
