// occsim: the simulator executable. Commands: run, bench, regress, merge, history, info, devices,
// cullers, view.
// Bad input (flags, scenario and script files, plugins, a headless backend or device that is
// missing or falls short) ends with one line on stderr and exit code 2, and so does `view` where
// no window can be opened; runtime failures (OpenGL, output) with exit 1.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "occsim/culling/contract/input_error.h"
#include "occsim/culling/registry/plugin_loader.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/registry/registry_text.h"
#include "render/glfw_context.h"
#include "render/headless_context.h"
#include "sim/output/atomic_file.h"
#include "sim/output/pictures.h"
#include "sim/output/report.h"
#include "sim/output/run_folder.h"
#include "sim/output/run_outputs.h"
#include "sim/output/shell_quote.h"
#include "sim/regress/regress.h"
#include "sim/regress/result_files.h"
#include "sim/regress_commands.h"
#include "sim/run/crash_note.h"
#include "sim/run/run_config.h"
#include "sim/run/runner.h"
#include "sim/run/stop_request.h"
#include "sim/scenario/culling_file.h"
#include "sim/scenario/errors.h"
#include "sim/scenario/json_reader.h"
#include "sim/scenario/scenario.h"
#include "sim/view/viewer.h"
#include "sim/world/scene_info.h"

namespace {

constexpr int kExitBadInput = 2;
constexpr int kExitFailure = 1;

// The one place a command-line algorithm name is checked.
const occsim::AlgorithmTraits& algorithmNamed(const std::string& flag, const std::string& name) {
    if (const occsim::AlgorithmTraits* a = occsim::findAlgorithm(name)) return *a;
    throw occsim::InputError(flag + ": unknown algorithm '" + name +
                             "'; expected one of: " + occsim::algorithmNameList());
}

// A whole number in [lo, hi], checked on the text before CLI11 converts it, so a bad value gets
// the same one-line message as a bad scenario value: what was expected, and what was given.
CLI::Validator integerIn(long long lo, long long hi) {
    const std::string expected =
        "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    return CLI::Validator(
        [lo, hi, expected](std::string& text) -> std::string {
            size_t used = 0;
            long long value = 0;
            try {
                value = std::stoll(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (text.empty() || used != text.size() || value < lo || value > hi) {
                return expected + ", got '" + text + "'";
            }
            return {};
        },
        "INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

// As typed, quoted for a shell, so that summary.json's command pastes back.
std::string commandLine(int argc, char** argv) { return occsim::shellCommand({argv, argv + argc}); }

// --backend and --device, on every command that renders headless.
struct BackendFlags {
    std::string backend = "auto";
    int64_t device = -1;
};

void addBackendFlags(CLI::App* cmd, BackendFlags& flags) {
    cmd->add_option("--backend", flags.backend,
                    "Headless OpenGL: auto (EGL, or OSMesa where EGL is missing), egl, osmesa "
                    "(docs/headless-gpu.md)");
    cmd->add_option("--device", flags.device,
                    "EGL device index (occsim devices lists them; default 0)")
        ->check(integerIn(0, 1023));
}

occsim::BackendChoice backendChoice(const BackendFlags& flags) {
    occsim::BackendChoice choice;
    const auto backend = occsim::parseBackend(flags.backend);
    if (!backend)
        throw occsim::InputError("--backend: expected auto, egl or osmesa, got '" + flags.backend +
                                 "'");
    choice.backend = *backend;
    if (flags.device >= 0) choice.device = static_cast<uint32_t>(flags.device);
    return choice;
}

struct CommonFlags {
    BackendFlags backend;
    std::string scenario;
    uint32_t repetitions = 1;
    std::string sweep;
    bool error = false;
    std::string out;
    uint32_t frames = 0;
    std::vector<uint32_t> capture;
    int deterministic_latency = -1;
    bool plots = false;
    int64_t birds_eye = -1;
    std::string culling;
    bool out_given = false;  // --out on the command line (an empty one is refused)
    bool wait_lock = false;
    std::vector<std::string> plugins;
    std::string ablate;
};

void addPluginFlag(CLI::App* cmd, std::vector<std::string>& plugins) {
    cmd->add_option("--plugin", plugins,
                    "Load cullers from this shared object (repeatable; docs/plugins.md); they run "
                    "wherever the built-ins run");
}

// Plugins load before any scenario is read: a scenario may name their cullers and options.
void loadPlugins(const std::vector<std::string>& plugins) {
    for (const std::string& file : plugins) {
        try {
            occsim::loadPlugin(file);
        } catch (const occsim::PluginError& e) {
            throw occsim::givenBy("--plugin", e);
        }
    }
}

void addCommonFlags(CLI::App* cmd, CommonFlags& flags) {
    cmd->add_option("scenario", flags.scenario, "Scenario file (JSON)")->required();
    addBackendFlags(cmd, flags.backend);
    cmd->add_flag(
        "--error", flags.error,
        "Measure image error against a ground-truth render of every frame (outside the timing)");
    cmd->add_option("--out", flags.out,
                    "Output folder (default: out/<scenario>/<command>), replaced as a whole by "
                    "the run");
    cmd->add_flag("--wait-lock", flags.wait_lock,
                  "Wait for another run writing the same --out to finish (default: exit)");
    cmd->add_option("--frames", flags.frames, "Run this many frames instead of the scenario's")
        ->check(integerIn(1, 10000000));
    cmd->add_option("--capture", flags.capture, "Save these frames' colour buffers as PNG")
        ->delimiter(',')
        ->check(integerIn(0, 9999999));
    cmd->add_option("--repetitions", flags.repetitions,
                    "Run every configuration N times (interleaved); report medians and min-max")
        ->check(integerIn(1, 1000));
    cmd->add_option(
           "--deterministic-latency", flags.deterministic_latency,
           "A query result counts as ready only after N later draw calls (reproducible counts)")
        ->check(integerIn(0, 1000000));
    cmd->add_flag(
        "--plots", flags.plots,
        "Chart frame time, time against error, queries and triangles with gnuplot (PNG and SVG)");
    cmd->add_option("--birds-eye", flags.birds_eye,
                    "Picture this frame's culling decisions from above, per configuration (PNG)")
        ->check(integerIn(0, 9999999));
    addPluginFlag(cmd, flags.plugins);
    cmd->add_option("--culling", flags.culling,
                    "Culling options from this file ({\"format_version\": 1, \"culling\": {...}}, "
                    "e.g. occtune's "
                    "tuned.json), overriding the scenario's");
}

// The scenario with the --culling file, when given, applied over its own culling options.
occsim::Scenario scenarioWithCulling(const std::string& scenario_file,
                                     const std::string& culling_file) {
    occsim::Scenario scenario = occsim::parseScenarioFile(scenario_file);
    if (!culling_file.empty())
        occsim::applyCullingFile(occsim::readCullingFile(culling_file), scenario);
    return scenario;
}

// What `run` and `bench` share once their flags are read: the scenario (parsed once), the
// algorithms (checked once) and which command this is.
struct RunRequest {
    std::string command;  // "run" or "bench"
    std::string command_line;
    const CommonFlags& flags;
    occsim::Scenario scenario;
    std::vector<const occsim::AlgorithmTraits*> algorithms;
    std::string default_subdir;
};

occsim::BenchOptions benchOptions(const RunRequest& request) {
    const CommonFlags& flags = request.flags;
    occsim::BenchOptions o;
    o.algorithms = request.algorithms;
    o.command = request.command;
    o.command_line = request.command_line;
    o.measure_error = flags.error;
    o.backend = backendChoice(flags.backend);
    if (flags.frames > 0) o.frames = flags.frames;
    o.repetitions = flags.repetitions;
    if (!flags.sweep.empty()) {
        try {
            o.sweep = occsim::parseSweep(flags.sweep, request.algorithms);
        } catch (const std::invalid_argument& e) {
            throw occsim::InputError(std::string("--sweep: ") + e.what());
        }
    }
    o.ablate = flags.ablate;
    // The configurations are planned once here, before any work, so that a swept value that makes
    // options invalid or repeats an ablation row is bad input, named by its flag.
    if (o.sweep || !o.ablate.empty()) {
        try {
            occsim::planConfigs(request.algorithms, request.scenario.culler, o.sweep, o.ablate);
        } catch (const std::invalid_argument& e) {
            throw occsim::InputError(std::string(o.ablate.empty() ? "--sweep: " : "--ablate: ") +
                                     e.what());
        }
    }
    if (flags.deterministic_latency >= 0) {
        o.latency.deterministic = true;
        o.latency.latency_commands = static_cast<uint32_t>(flags.deterministic_latency);
    }
    const uint32_t frames = flags.frames > 0 ? flags.frames : request.scenario.frames;
    auto checkFrame = [frames](const char* flag, int64_t frame) {
        if (frame >= frames) {
            throw occsim::InputError(std::string(flag) + ": frame " + std::to_string(frame) +
                                     " is past the last frame (" + std::to_string(frames) +
                                     " frames, from 0)");
        }
    };
    if (flags.birds_eye >= 0) {
        checkFrame("--birds-eye", flags.birds_eye);
        o.trace_frame = static_cast<uint32_t>(flags.birds_eye);
    }
    for (uint32_t frame : flags.capture) checkFrame("--capture", frame);
    o.progress = ::isatty(STDERR_FILENO) != 0;
    return o;
}

// An output path is checked before any work, so that a run never ends on a path it cannot
// write: a folder flag must not name a file, a file flag not a folder, and neither may be empty
// when given.
void checkOutputFolder(const std::string& flag, const std::string& path, bool given) {
    if (given && path.empty())
        throw occsim::InputError(flag + ": empty; expected a folder (created when missing)");
    std::error_code ec;
    if (!path.empty() && std::filesystem::exists(path, ec) &&
        !std::filesystem::is_directory(path, ec)) {
        throw occsim::InputError(flag + " " + path +
                                 ": is a file; expected a folder (created when missing)");
    }
}

void checkOutputFile(const std::string& flag, const std::string& path, bool given) {
    if (given && path.empty()) throw occsim::InputError(flag + ": empty; expected a file name");
    std::error_code ec;
    if (!path.empty() && std::filesystem::is_directory(path, ec)) {
        throw occsim::InputError(flag + " " + path + ": is a folder; expected a file name");
    }
}

// --algos as given: every name registered, none twice, none empty (a trailing comma).
// The names come comma-separated, space-separated or both ("vfc,chc" or "vfc chc").
std::vector<const occsim::AlgorithmTraits*> algorithmsNamed(const std::vector<std::string>& lists) {
    std::vector<std::string> names;
    for (const std::string& list : lists) {
        size_t start = 0;
        while (true) {
            const size_t comma = list.find(',', start);
            names.push_back(
                list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
    }
    std::vector<const occsim::AlgorithmTraits*> out;
    for (const std::string& name : names) {
        if (name.empty())
            throw occsim::InputError("--algos: an empty algorithm name (a comma too many?)");
        const occsim::AlgorithmTraits* a = &algorithmNamed("--algos", name);
        if (std::find(out.begin(), out.end(), a) != out.end()) {
            throw occsim::InputError("--algos: '" + name + "' is listed twice");
        }
        out.push_back(a);
    }
    return out;
}

// "The following argument was not expected: --frame" gets the nearest flag of the program.
std::string withSuggestion(const CLI::App& app, const std::string& message) {
    const std::string marker = "not expected: ";
    const size_t at = message.find(marker);
    if (at == std::string::npos) return message;
    std::istringstream rest(message.substr(at + marker.size()));
    std::string word;
    while (rest >> word && word.rfind("--", 0) != 0) {
    }
    if (word.rfind("--", 0) != 0) return message;
    std::vector<std::string> flags;
    for (const CLI::App* sub : app.get_subcommands({})) {
        for (const CLI::Option* option : sub->get_options()) {
            for (const std::string& name : option->get_lnames()) flags.push_back("--" + name);
        }
    }
    if (const auto match = occsim::closestMatch(word, flags))
        return message + "; did you mean '" + *match + "'?";
    return message;
}

// Before a command's first frame: SIGINT and SIGTERM stop it after the frame in hand with what
// it has written (marked partial), and a crash names the configuration and frame in hand.
void watchFrames() {
    occsim::installStopHandlers();
    occsim::installCrashHandler();
}

// A run that ended early: its one line on stderr, after the partial outputs were written, and
// its exit code (128 + the signal, as a shell reports a process the signal ended; 1 when a
// configuration failed).
int partialRunEnded(const std::string& command, const occsim::BenchResult& result,
                    const std::filesystem::path& out_dir) {
    const occsim::PartialRun& p = *result.partial;
    std::fprintf(stderr, "occsim %s: %s; written to %s (marked partial)%s\n", command.c_str(),
                 occsim::partialLine(result).c_str(), out_dir.string().c_str(),
                 p.signal != 0 ? "; run the same command again for a whole run" : "");
    return p.signal != 0 ? 128 + p.signal : kExitFailure;
}

int runCommand(const RunRequest& request) {
    const CommonFlags& flags = request.flags;
    checkOutputFolder("--out", flags.out, flags.out_given);
    occsim::BenchOptions options = benchOptions(request);
    const std::filesystem::path out_dir =
        flags.out.empty()
            ? occsim::defaultOutputFolder(request.scenario.name, request.default_subdir)
            : std::filesystem::path(flags.out);
    // A run is one unit: its folder is locked, checked and staged before the first frame, every
    // file (pictures taken during the run included) goes into the staging folder, and the whole
    // set replaces the old folder at the end, or nothing does.
    const occsim::FolderLock lock(out_dir, flags.wait_lock);
    occsim::StagedRunFolder folder(out_dir);
    occsim::PictureRecorder pictures(folder.staging(), flags.capture, options.trace_frame);
    options.on_frame = [&pictures](const occsim::FrameEvent& e) { pictures.onFrame(e); };

    watchFrames();
    const occsim::BenchResult result = occsim::runBenchmark(request.scenario, options);
    const occsim::OutputFiles files = occsim::writeRunOutputs(
        result, {folder.staging(), flags.plots, pictures.birdsEyeFiles(), {}});
    folder.publish();

    std::printf("%s\n", occsim::runHeadline(result).c_str());
    std::printf("%s", occsim::formatComparisonTable(result.runs).c_str());
    std::printf("%s\n", occsim::costsLine(result).c_str());
    std::printf("written: %s/{frames.csv,summary.json,report.md}\n", out_dir.string().c_str());
    if (!pictures.birdsEyeFiles().empty()) {
        std::printf("bird's-eye pictures: %zu (birds-eye-*.png)\n",
                    pictures.birdsEyeFiles().size());
    }
    size_t plots = 0;
    for (const std::string& f : files.files) plots += f.rfind("plot-", 0) == 0;
    if (plots > 0) std::printf("plots: %zu files (plot-*.png, plot-*.svg)\n", plots);
    if (!files.plots_message.empty()) std::printf("%s\n", files.plots_message.c_str());
    if (result.partial) {
        std::fflush(stdout);  // the table before the line that says it is partial
        return partialRunEnded(request.command, result, out_dir);
    }
    return 0;
}

int regressCommand(const std::vector<std::string>& inputs, bool update, const std::string& junit,
                   const std::string& shard, const std::string& out,
                   const std::string& culling_file, const std::vector<std::string>& plugins,
                   const BackendFlags& backend, bool junit_given, const std::string& history,
                   const std::string& commit, bool allow_empty, bool wait_lock,
                   bool exit_zero_on_failed_checks) {
    checkOutputFile("--junit", junit, junit_given);
    checkOutputFolder("--out", out, true);
    occsim_cli::checkHistoryFlag(history);
    // Each scenario's folder under --out is one unit (runRegression); the lock covers them all.
    const occsim::FolderLock lock(out, wait_lock);
    loadPlugins(plugins);
    occsim::RegressOptions options;
    options.backend = backendChoice(backend);
    for (const std::string& plugin : plugins)
        options.rerun_flags.insert(options.rerun_flags.end(), {"--plugin", plugin});
    if (!culling_file.empty())
        options.rerun_flags.insert(options.rerun_flags.end(), {"--culling", culling_file});
    if (backend.backend != "auto")
        options.rerun_flags.insert(options.rerun_flags.end(), {"--backend", backend.backend});
    if (backend.device >= 0) {
        options.rerun_flags.insert(options.rerun_flags.end(),
                                   {"--device", std::to_string(backend.device)});
    }
    if (!culling_file.empty()) {
        options.adjust_scenario = [culling =
                                       occsim::readCullingFile(culling_file)](occsim::Scenario& s) {
            occsim::applyCullingFile(culling, s);
        };
    }
    for (const auto& input : inputs) options.inputs.emplace_back(input);
    try {
        options.shard =
            shard.empty() ? occsim::shardFromEnvironment(std::getenv) : occsim::parseShard(shard);
    } catch (const std::invalid_argument& e) {
        throw occsim::InputError(std::string("--shard: ") + e.what());
    }
    options.update = update;
    options.out_dir = out;
    options.progress = ::isatty(STDERR_FILENO) != 0;
    watchFrames();
    const occsim::RegressReport report = occsim::runRegression(options);
    std::printf("%s", report.table().c_str());
    size_t failed = 0, skipped = 0;
    for (const auto& s : report.scenarios) {
        failed += !s.passed();
        skipped += s.skipped;
        if (!s.note.empty() && !s.skipped) std::printf("%s\n", s.note.c_str());
        for (const auto& capture : s.captures)
            std::printf("picture of the worst frame: %s\n", capture.c_str());
    }
    if (!junit.empty()) {
        const std::filesystem::path junit_path(junit);
        if (junit_path.has_parent_path())
            std::filesystem::create_directories(junit_path.parent_path());
        occsim::writeFileAtomically(junit_path, occsim::junitXml(report));
    }
    // A stopped run's figures are no history: only its shard result is written (which merge
    // refuses, a scenario of the set being missing).
    if (!update) {
        occsim_cli::writeRegressResults(options, report, report.stop_signal ? "" : history, commit);
    }
    std::printf("regress: %zu scenarios (shard %u/%u), %zu failed, %zu skipped\n",
                report.scenarios.size(), options.shard.index, options.shard.count, failed, skipped);
    if (report.stop_signal) {
        std::fflush(stdout);
        std::fprintf(stderr,
                     "occsim regress: %s; written to %s%s; run the same command again for a "
                     "whole run\n",
                     report.stopped.c_str(), out.c_str(),
                     history.empty() ? "" : ", nothing appended to the history");
        return 128 + report.stop_signal;
    }
    // Green with nothing checked would let a CI job pass on a wrong path or a lost expect block.
    if (report.scenarios.size() == skipped && !allow_empty) {
        std::fprintf(
            stderr,
            "occsim regress: nothing was checked: %s (--allow-empty when that is expected)\n",
            report.scenarios.empty() ? "no scenario file found under the paths given"
                                     : "no scenario found has an expect block");
        return kExitFailure;
    }
    // A shard under a scheduler that retries failed tasks (a Kubernetes Indexed Job) must finish
    // so that the merge runs; the failed checks are in its results and the merge exits 1.
    if (!report.passed() && exit_zero_on_failed_checks) {
        std::printf(
            "regress: failed checks exit 0 (--exit-zero-on-failed-checks): merge reports them\n");
        return 0;
    }
    return report.passed() ? 0 : kExitFailure;
}

// `occsim devices`: every EGL device with what a context on it reports.
int devicesCommand() {
    std::printf("OSMesa: %s\n", occsim::osmesaAvailable()
                                    ? "in this build (--backend osmesa)"
                                    : "not in this build (OCCSIM_WITH_OSMESA=OFF)");
    const std::vector<occsim::EglDeviceInfo> devices = occsim::listEglDevices();
    std::printf("EGL devices: %zu\n", devices.size());
    for (const occsim::EglDeviceInfo& d : devices) {
        std::printf("device %u (%s): ", d.index, d.kind.c_str());
        if (!d.problem.empty()) {
            std::printf("unusable: %s\n", d.problem.c_str());
            continue;
        }
        const occsim::ContextInfo& c = d.context;
        std::printf("vendor %s, renderer %s, driver %s, OpenGL %s%s\n", c.vendor.c_str(),
                    c.renderer.c_str(), c.driver.c_str(), c.version.c_str(),
                    c.gpu_time_meaningful ? "" : " (software rasteriser: gpu ms not meaningful)");
    }
    return 0;
}

struct ViewFlags {
    std::string scenario, algorithm, size, script, out;
    bool error = false;
    std::vector<std::string> plugins;
};

int viewCommand(const ViewFlags& flags) {
    loadPlugins(flags.plugins);
    occsim::ViewOptions options;
    const occsim::Scenario scenario = occsim::parseScenarioFile(flags.scenario);
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

// Every command's flags, filled by CLI11, and the command each belongs to (set when it is added).
struct Commands {
    CLI::App* run = nullptr;
    CommonFlags run_flags;
    std::string run_algorithm;

    CLI::App* bench = nullptr;
    CommonFlags bench_flags;
    std::vector<std::string> bench_algorithms;  // split here, not by CLI11: it drops empty names

    CLI::App* regress = nullptr;
    std::vector<std::string> regress_inputs;
    bool regress_update = false, regress_allow_empty = false, regress_wait_lock = false,
         regress_exit_zero_on_failed_checks = false;
    std::string regress_junit, regress_shard, regress_out = "out/regress", regress_culling;
    std::vector<std::string> regress_plugins;
    BackendFlags regress_backend;
    std::string regress_history, regress_commit;

    CLI::App* merge = nullptr;
    occsim_cli::MergeFlags merge_flags;

    CLI::App* history = nullptr;
    occsim_cli::HistoryFlags history_flags;

    CLI::App* cullers = nullptr;
    bool cullers_markdown = false;
    std::vector<std::string> cullers_plugins;

    CLI::App* devices = nullptr;

    CLI::App* info = nullptr;
    std::string info_scenario;

    CLI::App* view = nullptr;
    ViewFlags view_flags;
};

void addRunAndBench(CLI::App& app, Commands& c) {
    c.run = app.add_subcommand(
        "run", "Run one algorithm over a scenario (summary, frames.csv, summary.json)");
    addCommonFlags(c.run, c.run_flags);
    c.run->add_option(
        "--algo", c.run_algorithm,
        "Culling algorithm (default: the scenario's): " + occsim::algorithmNameList());

    c.bench = app.add_subcommand(
        "bench", "Run several algorithms over the same frames, interleaved, in one table");
    addCommonFlags(c.bench, c.bench_flags);
    c.bench->add_option("--algos", c.bench_algorithms,
                        "Algorithms to compare (default: every registered one, plugins' included)");
    c.bench->add_option(
        "--sweep", c.bench_flags.sweep,
        "Sweep one option, [ALGORITHM:]KEY=V1,V2,...: one configuration per value, for "
        "each listed algorithm with that option (KEY: threshold_pixels, stale_results, "
        "or a key of a culler's options; occsim cullers lists them)");
    c.bench->add_option(
        "--ablate", c.bench_flags.ablate,
        "Run this algorithm also once with each mechanism its options switch on turned "
        "off (the ablation; occsim cullers marks them)");
}

void addRegress(CLI::App& app, Commands& c) {
    CLI::App* regress = c.regress = app.add_subcommand(
        "regress",
        "Run every scenario with an expect block (files or folders, recursively) and check it");
    regress->add_option("paths", c.regress_inputs, "Scenario files or folders")->required();
    regress->add_flag("--update", c.regress_update,
                      "Rewrite the baselines from this run (prints what changed)");
    regress->add_flag(
        "--allow-empty", c.regress_allow_empty,
        "Exit 0 even when no scenario found has an expect block (default: that fails)");
    regress->add_flag("--exit-zero-on-failed-checks", c.regress_exit_zero_on_failed_checks,
                      "Exit 0 when checks fail (they stay in the results, for merge to report); "
                      "bad input (2) and failures while running (1) still fail");
    regress->add_option("--junit", c.regress_junit, "Write JUnit XML results to this file");
    regress->add_option("--shard", c.regress_shard,
                        "Run shard i of n (i/n); default from Slurm or Kubernetes job variables");
    regress->add_option("--out", c.regress_out,
                        "Output folder for data and failure pictures (each scenario's folder "
                        "in it replaced as a whole)");
    regress->add_flag("--wait-lock", c.regress_wait_lock,
                      "Wait for another regress writing the same --out to finish (default: exit)");
    regress->add_option(
        "--culling", c.regress_culling,
        "Culling options from this file, overriding every scenario's (see run --help)");
    addPluginFlag(regress, c.regress_plugins);
    addBackendFlags(regress, c.regress_backend);
    regress->add_option(
        "--history", c.regress_history,
        "Append this run's figures to a history folder (occsim history DIR reports it)");
    regress->add_option("--commit", c.regress_commit,
                        "Commit recorded in the history (default: $OCCSIM_COMMIT, $GITHUB_SHA, "
                        "$CI_COMMIT_SHA or git rev-parse HEAD)");
}

void addMergeAndHistory(CLI::App& app, Commands& c) {
    occsim_cli::MergeFlags& merge_flags = c.merge_flags;
    CLI::App* merge = c.merge = app.add_subcommand(
        "merge",
        "Join the --out folders of the shards of one regress run into one report, checking that "
        "every scenario ran exactly once");
    merge->add_option("shards", merge_flags.dirs, "The shards' --out folders")->required();
    merge->add_option("--out", merge_flags.out,
                      "Folder for the merged report (default out/merged)");
    merge->add_option("--junit", merge_flags.junit, "Also write the merged JUnit XML to this file");
    merge->add_option("--history", merge_flags.history,
                      "Append the merged run's figures to a history folder");
    merge->add_option("--commit", merge_flags.commit,
                      "Commit recorded in the history (as for regress)");

    occsim_cli::HistoryFlags& history_flags = c.history_flags;
    CLI::App* history = c.history =
        app.add_subcommand("history",
                           "Report a history folder: plots over the runs, changes "
                           "beyond the run-to-run spread flagged");
    history->add_option("dir", history_flags.dir, "History folder (regress --history)")->required();
    history->add_option("--out", history_flags.out,
                        "Folder for report.md and the plots (default out/history)");
    history
        ->add_option("--window", history_flags.window,
                     "Compare the median of the last N runs with the N before (default 3)")
        ->check(integerIn(1, 1000));
    history
        ->add_option("--min-change", history_flags.min_change,
                     "Smallest relative change flagged, beside the spread (default 0.05)")
        ->check(CLI::Range(0.0, 10.0));
    history->add_flag("--fail-on-change", history_flags.fail_on_change,
                      "Exit with status 1 when a figure got worse beyond the spread");
}

// cullers, devices and info: what is registered, what can render, what a scenario builds.
void addListings(CLI::App& app, Commands& c) {
    c.cullers = app.add_subcommand(
        "cullers", "List the registered cullers, their traits and every option (docs/cullers.md)");
    c.cullers->add_flag("--markdown", c.cullers_markdown,
                        "As the Markdown tables of docs/cullers.md");
    addPluginFlag(c.cullers, c.cullers_plugins);

    c.devices = app.add_subcommand("devices",
                                   "List the EGL devices headless runs can use (--device "
                                   "N), with vendor, renderer and driver");

    c.info = app.add_subcommand(
        "info", "Print what a scenario builds (objects, triangles, BSP) without rendering");
    c.info->add_option("scenario", c.info_scenario, "Scenario file (JSON)")->required();
}

void addView(CLI::App& app, Commands& c) {
    ViewFlags& view_flags = c.view_flags;
    CLI::App* view = c.view = app.add_subcommand("view",
                                                 "Watch a scenario in a window: fly, switch "
                                                 "algorithms live, record a camera path "
                                                 "(docs/viewer.md)");
    view->add_option("scenario", view_flags.scenario, "Scenario file (JSON)")->required();
    view->add_option("--algo", view_flags.algorithm,
                     "Culling algorithm to start with (default: the scenario's): " +
                         occsim::algorithmNameList());
    view->add_flag("--error", view_flags.error,
                   "Render ground truth every frame and show error pixels (key g)");
    view->add_option(
        "--size", view_flags.size,
        "Window size WIDTHxHEIGHT (default: the scenario's viewport, enlarged when small)");
    view->add_option("--script", view_flags.script,
                     "Drive the window from a script file, then close it");
    addPluginFlag(view, view_flags.plugins);
    view->add_option(
        "--out", view_flags.out,
        "Folder for screenshots and recorded scenarios (default: out/<scenario>/view)");
}

// CLI11 would answer an unknown command with "A subcommand is required": false, the line
// printed, when argv[1] names none.
bool knownCommand(CLI::App& app, int argc, char** argv) {
    if (argc <= 1 || argv[1][0] == '-') return true;
    std::string commands;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) {
        commands += (commands.empty() ? "" : ", ") + sub->get_name();
        known |= sub->get_name() == argv[1];
    }
    if (!known) {
        std::fprintf(stderr,
                     "occsim: unknown command '%s'; expected one of: %s (see occsim --help)\n",
                     argv[1], commands.c_str());
    }
    return known;
}

int runOrBench(Commands& c, const std::string& command) {
    if (*c.run) {
        loadPlugins(c.run_flags.plugins);
        RunRequest request{
            "run",       command,
            c.run_flags, scenarioWithCulling(c.run_flags.scenario, c.run_flags.culling),
            {},          ""};
        const occsim::AlgorithmTraits& algorithm =
            c.run_algorithm.empty() ? *occsim::findAlgorithm(request.scenario.algorithm)
                                    : algorithmNamed("--algo", c.run_algorithm);
        request.algorithms = {&algorithm};
        request.default_subdir = "run-" + std::string(algorithm.name);
        return runCommand(request);
    }
    loadPlugins(c.bench_flags.plugins);
    RunRequest request{"bench",
                       command,
                       c.bench_flags,
                       scenarioWithCulling(c.bench_flags.scenario, c.bench_flags.culling),
                       {},
                       "bench"};
    request.algorithms =
        c.bench->count("--algos") > 0 ? algorithmsNamed(c.bench_algorithms) : occsim::algorithms();
    return runCommand(request);
}

int infoCommand(const std::string& scenario) {
    std::vector<std::string> warnings;
    const std::string text =
        occsim::describeScenario(occsim::parseScenarioFile(scenario), warnings);
    for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::printf("%s", text.c_str());
    return 0;
}

// The command that was given, run.
int runGivenCommand(Commands& c, const std::string& command) {
    if (*c.run || *c.bench) return runOrBench(c, command);
    if (*c.regress)
        return regressCommand(c.regress_inputs, c.regress_update, c.regress_junit, c.regress_shard,
                              c.regress_out, c.regress_culling, c.regress_plugins,
                              c.regress_backend, c.regress->count("--junit") > 0, c.regress_history,
                              c.regress_commit, c.regress_allow_empty, c.regress_wait_lock,
                              c.regress_exit_zero_on_failed_checks);
    if (*c.merge) return occsim_cli::mergeCommand(c.merge_flags);
    if (*c.history) return occsim_cli::historyCommand(c.history_flags);
    if (*c.cullers) {
        loadPlugins(c.cullers_plugins);
        std::printf(
            "%s", (c.cullers_markdown ? occsim::cullersMarkdown() : occsim::cullersText()).c_str());
        return 0;
    }
    if (*c.devices) return devicesCommand();
    if (*c.info) return infoCommand(c.info_scenario);
    if (*c.view) return viewCommand(c.view_flags);
    return kExitFailure;
}

// dispatch(), with every error a command can end in turned into its one line and exit code:
// bad input (whichever module found it) 2, a failure while running 1. Every command's output
// folder is --out's: a folder that cannot be used is bad input named by that flag, one that
// another run holds (try again later) a failure.
int dispatchReportingErrors(Commands& c, const std::string& command) {
    try {
        try {
            return runGivenCommand(c, command);
        } catch (const occsim::RunFolderError& e) {  // not an occsim run, or not writable
            throw occsim::givenBy("--out", e);
        } catch (const occsim::RunFolderBusy& e) {
            throw std::runtime_error(std::string("--out ") + e.what());
        }
    } catch (const occsim::InputError& e) {
        std::fprintf(stderr, "occsim: %s\n", e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "occsim: %s\n", e.what());
        return kExitFailure;
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "occsim: simulate dynamic scenes and measure occlusion culling against ground truth"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Help for every command");
    Commands c;
    addRunAndBench(app, c);
    addRegress(app, c);
    addMergeAndHistory(app, c);
    addListings(app, c);
    addView(app, c);

    if (!knownCommand(app, argc, argv)) return kExitBadInput;
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "occsim: %s (see occsim --help)\n",
                     withSuggestion(app, e.what()).c_str());
        return kExitBadInput;
    }
    c.run_flags.out_given = c.run->count("--out") > 0;
    c.bench_flags.out_given = c.bench->count("--out") > 0;
    return dispatchReportingErrors(c, commandLine(argc, argv));
}
