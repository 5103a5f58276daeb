// occtune: tunes a culler's tunable options (by default the statistical culler's BASE_TIME and
// decay curve) to a scenario from measured frame times (docs/tuning.md). Bad input ends with one
// line on stderr and exit code 2 before any run; a fit that does not converge with exit 1 (no
// tuned.json); a result its own confirmation rejects with exit 3 (tuned.rejected.json, no
// tuned.json); Ctrl-C with exit 130, the sample log whole and a line saying how to resume. The
// verdict is the console's last line but one.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <sstream>

#include "render/headless_context.h"
#include "sim/scenario/errors.h"
#include "tune/errors.h"
#include "tune/parameters.h"
#include "tune/tuner.h"

namespace {

constexpr int kExitBadInput = 2;

std::string commandLine(int argc, char** argv) {
    std::ostringstream out;
    for (int i = 0; i < argc; ++i) out << (i ? " " : "") << argv[i];
    return out.str();
}

}  // namespace

int main(int argc, char** argv) {
    using occsim::tune::Objective;
    occsim::tune::TuneOptions o;
    CLI::App app{
        "occtune: tune a culler's options (default: the statistical culler's BASE_TIME and decay "
        "curve) to a "
        "scenario (docs/tuning.md)"};
    std::string scenario, objective = "mean", out;
    uint32_t frames = 0;
    uint64_t holdout_seed = 0;
    app.add_option("scenario", scenario, "Scenario file (JSON)")->required();
    app.add_option("--budget", o.budget,
                   "Samples to measure (besides the reference runs); default 20")
        ->check(CLI::Range(1u, 100000u));
    app.add_option(
        "--algo", o.algorithm,
        "The culler to tune (default statistical): any registered culler whose options "
        "descriptor marks options tunable (occsim cullers lists them), a plugin's included");
    std::vector<std::string> plugins;
    app.add_option("--plugin", plugins, "Load cullers from this shared object first (repeatable)");
    app.add_option("--params", o.params,
                   "Parameters to tune, comma-separated (default: every tunable option of --algo; "
                   "statistical: base_time, decay_a, decay_b)");
    app.add_option("--bounds", o.bounds, "Search range of a parameter, NAME=LO:HI (repeatable)")
        ->delimiter(',');
    app.add_option(
           "--objective", objective,
           "What a sample is judged by: its mean or p95 frame time (ratio to the paper's values)")
        ->check(CLI::IsMember({"mean", "p95"}));
    app.add_option("--repetitions", o.repetitions, "Repetitions of the confirmation run; default 3")
        ->check(CLI::Range(1u, 1000u));
    app.add_option("--out", out, "Output folder (default out/<scenario>/tune)");
    app.add_flag("--resume", o.resume,
                 "Continue the session whose sample log is in the output folder");
    app.add_option("--frames", frames, "Run this many frames instead of the scenario's")
        ->check(CLI::Range(1u, 10000000u));
    app.add_option("--seed", o.seed, "Seed of the sampling design; default 1");
    app.add_option("--batch", o.batch,
                   "Samples per interleaved run (beside one reference); default 4")
        ->check(CLI::Range(1u, 64u));
    app.add_option("--holdout-seed", holdout_seed,
                   "Scenario seed of the held-out confirmation (default: the scenario's + 1)");
    app.add_option("--max-fit-iterations", o.max_fit_iterations,
                   "Ceres iteration limit of each fit; default 200")
        ->check(CLI::Range(1, 100000));
    std::string backend = "auto";
    int device = -1;
    app.add_option("--backend", backend,
                   "Headless OpenGL: auto (EGL, or OSMesa where EGL is missing), egl, osmesa "
                   "(docs/headless-gpu.md)");
    app.add_option("--device", device, "EGL device index (occsim devices lists them; default 0)")
        ->check(CLI::Range(0, 1023));
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "occtune: %s (see occtune --help)\n", e.what());
        return kExitBadInput;
    }
    if (const auto b = occsim::parseBackend(backend)) {
        o.backend.backend = *b;
    } else {
        std::fprintf(stderr, "occtune: --backend: expected auto, egl or osmesa, got '%s'\n",
                     backend.c_str());
        return kExitBadInput;
    }
    if (device >= 0) o.backend.device = static_cast<uint32_t>(device);
    o.scenario = scenario;
    for (const std::string& p : plugins) o.plugins.emplace_back(p);
    o.out = out;
    o.objective = objective == "p95" ? Objective::P95 : Objective::Mean;
    if (app.count("--frames")) o.frames = frames;
    if (app.count("--holdout-seed")) o.holdout_seed = holdout_seed;
    o.progress = ::isatty(STDERR_FILENO) != 0;
    o.command_line = commandLine(argc, argv);

    try {
        // The backend and device are input too: checked before the first run writes anything.
        occsim::createHeadlessContext(o.backend, 16, 16);
        return occsim::tune::runTuner(o);
    } catch (const occsim::BackendUnavailable& e) {
        std::fprintf(stderr, "occtune: %s\n", e.what());
    } catch (const occsim::tune::TuneInputError& e) {
        std::fprintf(stderr, "occtune: %s\n", e.what());
    } catch (const occsim::ScenarioError& e) {
        std::fprintf(stderr, "occtune: %s\n", e.what());
    } catch (const occsim::GltfError& e) {
        std::fprintf(stderr, "occtune: %s\n", e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "occtune: %s\n", e.what());
        return 1;
    }
    return kExitBadInput;
}
