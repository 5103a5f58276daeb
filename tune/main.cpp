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

#include "occsim/culling/contract/input_error.h"
#include "occsim/culling/registry/plugin_loader.h"
#include "render/headless_context.h"
#include "sim/output/version.h"
#include "tune/console.h"
#include "tune/parameter_table.h"
#include "tune/parameters.h"
#include "tune/session_files.h"
#include "tune/tuner.h"

namespace {

using occsim::tune::Objective;
using occsim::tune::TuneOptions;
using occsim::tune::TuneSession;

constexpr int kExitBadInput = 2;

std::string commandLine(int argc, char** argv) {
    std::ostringstream out;
    for (int i = 0; i < argc; ++i) out << (i ? " " : "") << argv[i];
    return out.str();
}

// The flags read as text or kept apart from TuneOptions until they are checked.
struct RawFlags {
    std::string scenario, objective = "mean", out;
    uint32_t frames = 0;
    uint64_t holdout_seed = 0;
    std::vector<std::string> plugins;
    bool list_parameters = false;
    bool markdown = false;
    std::string backend = "auto";
    int device = -1;
};

void addOptions(CLI::App& app, TuneOptions& o, RawFlags& raw) {
    // Required, except with --list-parameters (checked after parsing).
    app.add_option("scenario", raw.scenario, "Scenario file (JSON)");
    app.add_flag("--list-parameters", raw.list_parameters,
                 "Print every registered culler's tunable parameters (a plugin's with --plugin) "
                 "and exit");
    app.add_flag("--markdown", raw.markdown,
                 "With --list-parameters: as the Markdown table of docs/tuning.md");
    app.add_option("--budget", o.budget,
                   "Samples to measure (besides the reference runs); default 20")
        ->check(CLI::Range(1u, 100000u));
    app.add_option(
        "--algo", o.algorithm,
        "The culler to tune (default statistical): any registered culler whose options "
        "descriptor marks options tunable (occsim cullers lists them), a plugin's included");
    app.add_option("--plugin", raw.plugins,
                   "Load cullers from this shared object first (repeatable)");
    app.add_option("--params", o.params,
                   "Parameters to tune, comma-separated (default: every tunable option of --algo; "
                   "statistical: base_time, decay_a, decay_b)");
    app.add_option("--bounds", o.bounds, "Search range of a parameter, NAME=LO:HI (repeatable)")
        ->delimiter(',');
    app.add_option(
           "--objective", raw.objective,
           "What a sample is judged by: its mean or p95 frame time (ratio to the paper's values)")
        ->check(CLI::IsMember({"mean", "p95"}));
    app.add_option("--repetitions", o.repetitions, "Repetitions of the confirmation run; default 3")
        ->check(CLI::Range(1u, 1000u));
    app.add_option("--out", raw.out, "Output folder (default out/<scenario>/tune)");
    app.add_flag("--resume", o.resume,
                 "Continue the session whose sample log is in the output folder");
    app.add_option("--frames", raw.frames, "Run this many frames instead of the scenario's")
        ->check(CLI::Range(1u, 10000000u));
    app.add_option("--seed", o.seed, "Seed of the sampling design; default 1");
    app.add_option("--batch", o.batch,
                   "Samples per interleaved run (beside one reference); default 4")
        ->check(CLI::Range(1u, 64u));
    app.add_option("--holdout-seed", raw.holdout_seed,
                   "Scenario seed of the held-out confirmation (default: the scenario's + 1)");
    app.add_option("--max-fit-iterations", o.max_fit_iterations,
                   "Ceres iteration limit of each fit; default 200")
        ->check(CLI::Range(1, 100000));
    app.add_flag("--apply-cost-model", o.apply_cost_model,
                 "Confirm and write the tuned options with the fitted cost model when it fits "
                 "well enough (residual RMS at most 25 % of the mean frame); default: the culler "
                 "calibrates at start-up, as in every sample");
    app.add_option("--backend", raw.backend,
                   "Headless OpenGL: auto (EGL, or OSMesa where EGL is missing), egl, osmesa "
                   "(docs/headless-gpu.md)");
    app.add_option("--device", raw.device,
                   "EGL device index (occsim devices lists them; default 0)")
        ->check(CLI::Range(0, 1023));
}

// --list-parameters: the tunable parameters of every culler, a plugin's loaded first.
int listParameters(const RawFlags& raw) {
    for (const std::string& plugin : raw.plugins) {
        try {
            occsim::loadPlugin(plugin);
        } catch (const occsim::PluginError& e) {
            throw occsim::givenBy("--plugin", e);
        }
    }
    std::printf("%s", (raw.markdown ? occsim::tune::tunableParametersMarkdown()
                                    : occsim::tune::tunableParametersText())
                          .c_str());
    return 0;
}

// The parsed flags into `o`. Throws InputError when --backend names no backend.
void applyFlags(const CLI::App& app, const RawFlags& raw, TuneOptions& o) {
    const auto backend = occsim::parseBackend(raw.backend);
    if (!backend)
        throw occsim::InputError("--backend: expected auto, egl or osmesa, got '" + raw.backend +
                                 "'");
    o.backend.backend = *backend;
    if (raw.device >= 0) o.backend.device = static_cast<uint32_t>(raw.device);
    o.scenario = raw.scenario;
    for (const std::string& p : raw.plugins) o.plugins.emplace_back(p);
    o.out = raw.out;
    o.objective = raw.objective == "p95" ? Objective::P95 : Objective::Mean;
    if (app.count("--frames")) o.frames = raw.frames;
    if (app.count("--holdout-seed")) o.holdout_seed = raw.holdout_seed;
    o.progress = ::isatty(STDERR_FILENO) != 0;
}

// What the session ended with, said on the console and, when it finished, written to its folder.
int report(TuneSession& session, const TuneOptions& o) {
    switch (session.end) {
        case TuneSession::End::Interrupted:
            occsim::tune::printInterrupted(session, o);
            break;
        case TuneSession::End::FitFailed:
            occsim::tune::printFitFailed(session);
            break;
        case TuneSession::End::Finished:
            occsim::tune::printFinished(session, occsim::tune::writeSessionFiles(session));
            break;
    }
    return session.exitCode();
}

int runSession(const TuneOptions& o) {
    // The backend and device are input too: checked before the first run writes anything.
    occsim::createHeadlessContext(o.backend, 16, 16);
    TuneSession session = occsim::tune::runTuner(o);
    return report(session, o);
}

// What the parsed command line asks for, done.
int tune(const CLI::App& app, const RawFlags& raw, TuneOptions& o, const std::string& command) {
    if (raw.list_parameters) return listParameters(raw);
    if (raw.scenario.empty())
        throw occsim::InputError("scenario: a scenario file is required (see occtune --help)");
    applyFlags(app, raw, o);
    o.command_line = command;
    return runSession(o);
}

// tune(), with every error it can end in turned into its one line and exit code: bad input
// (whichever module found it) 2, a failure while running 1.
int tuneReportingErrors(const CLI::App& app, const RawFlags& raw, TuneOptions& o,
                        const std::string& command) {
    try {
        return tune(app, raw, o, command);
    } catch (const occsim::InputError& e) {
        std::fprintf(stderr, "occtune: %s\n", e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "occtune: %s\n", e.what());
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv) {
    TuneOptions o;
    RawFlags raw;
    CLI::App app{
        "occtune: tune a culler's options (default: the statistical culler's BASE_TIME and decay "
        "curve) to a "
        "scenario (docs/tuning.md)"};
    addOptions(app, o, raw);
    app.set_version_flag("--version", occsim::versionLine("occtune"),
                         "Print the version and the commit it was built from, and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "occtune: %s (see occtune --help)\n", e.what());
        return kExitBadInput;
    }
    return tuneReportingErrors(app, raw, o, commandLine(argc, argv));
}
