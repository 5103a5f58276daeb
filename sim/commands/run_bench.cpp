#include "sim/commands/run_bench.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "occsim/culling/contract/input_error.h"
#include "occsim/culling/registry/registry.h"
#include "sim/commands/algorithm_entries.h"
#include "sim/commands/exit_codes.h"
#include "sim/commands/flag_checks.h"
#include "sim/output/console_colour.h"
#include "sim/output/console_table.h"
#include "sim/output/moments.h"
#include "sim/output/pictures.h"
#include "sim/output/report.h"
#include "sim/output/run_folder.h"
#include "sim/output/run_outputs.h"
#include "sim/record/object_recorder.h"
#include "sim/record/object_schema.h"
#include "sim/run/run_config.h"
#include "sim/run/runner.h"
#include "sim/scenario/culling_file.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/view_overrides.h"

namespace occsim_cli {
namespace {

// A note on stderr, within the console's 100 columns.
void printNote(const std::string& line) {
    std::fputs(occsim::wrappedText("note: " + line + "\n").c_str(), stderr);
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
    cmd->add_option("--segments", flags.segments,
                    "Name stretches of the run, NAME=FROM:TO in seconds or NAME=fFROM:TO in "
                    "frames, FROM inclusive, TO exclusive, comma-separated (corner=4.0:4.6): every "
                    "figure is also given per segment, beside the scenario's segments");
    addPluginFlag(cmd, flags.plugins);
    cmd->add_flag("--quiet", flags.quiet,
                  "No progress on stderr (default: a bar on a terminal, else a line every 10 s)");
    cmd->add_flag("--wide", flags.wide,
                  "Print the full comparison table, every figure (default: a compact table of "
                  "at most 100 columns and a verdict; report.md and summary.json have all)");
    cmd->add_option("--record", flags.record, kRecordHelp)->delimiter(',');
    cmd->add_option("--sun", flags.sun,
                    "ELEVATION,AZIMUTH[,SHADOW_MAP]: one shadow-casting sun, degrees above the "
                    "horizon and round from +x toward +z (map 2048 texels unless given), in place "
                    "of every light the scene names (docs/views.md)")
        ->each([&flags](const std::string&) { flags.sun_given = true; });
    cmd->add_option("--stereo", flags.stereo,
                    "SEPARATION[,MODE]: two eyes this many metres apart, the camera midway, "
                    "culled by one pass over a frustum enclosing both (MODE enclosing, the "
                    "default) or per eye (per_eye), in place of the scenario's stereo "
                    "(docs/views.md)")
        ->each([&flags](const std::string&) { flags.stereo_given = true; });
    cmd->add_option("--shadow-casters", flags.shadow_casters,
                    "Which casters a shadow pass draws: frustum (every object in the light's "
                    "box, the default), receivers (those that may shadow what the camera's "
                    "pass drew; the camera's pass first, then a shading pass), culler (those "
                    "each configuration's culler draws in the light's view) or culler+receivers "
                    "(of those, the ones that may shadow what the camera's pass drew; "
                    "docs/views.md)");
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
    std::vector<AlgorithmEntry> entries;               // as given: cullers, and NAME@FILE
    std::vector<const occsim::CullerRow*> algorithms;  // the plain cullers among them
    std::string default_subdir;
};

// The plugins loaded first, then the scenario (which may name their cullers) parsed once; the
// algorithms and the default folder are the command's to fill in.
RunRequest requestOf(const std::string& command, const std::string& command_line,
                     const CommonFlags& flags) {
    loadPlugins(flags.plugins);
    RunRequest request{
        command, command_line, flags, scenarioWithCulling(flags.scenario, flags.culling),
        {},      {},           ""};
    if (flags.sun_given) {
        try {
            occsim::replaceLightsWith(request.scenario, occsim::parseSun(flags.sun));
        } catch (const std::invalid_argument& e) {
            throw occsim::InputError(std::string("--sun: ") + e.what());
        }
    }
    if (flags.stereo_given) {
        try {
            request.scenario.stereo = occsim::parseStereo(flags.stereo);
        } catch (const std::invalid_argument& e) {
            throw occsim::InputError(std::string("--stereo: ") + e.what());
        }
    }
    return request;
}

// The scenario's segments and --segments', placed on the frames this run runs, before any work; a
// scenario segment that a shorter --frames cuts is said on stderr.
std::vector<occsim::Segment> runSegments(const occsim::Scenario& scenario,
                                         const std::vector<std::string>& flag, uint32_t frames) {
    std::vector<occsim::SegmentSpec> extra;
    if (!flag.empty()) {
        std::string text;
        for (const std::string& item : flag) text += (text.empty() ? "" : ",") + item;
        try {
            extra = occsim::parseSegmentList(text);
        } catch (const std::invalid_argument& e) {
            throw occsim::InputError(std::string("--segments: ") + e.what());
        }
    }
    occsim::PlannedSegments plan =
        occsim::planSegments(scenario.segments, scenario.frames, extra, frames, scenario.dt_s);
    for (const std::string& note : plan.notes) printNote(note + " (--frames)");
    return plan.segments;
}

occsim::BenchOptions benchOptions(const RunRequest& request) {
    const CommonFlags& flags = request.flags;
    occsim::BenchOptions o;
    for (const AlgorithmEntry& e : request.entries) {
        if (std::find(o.algorithms.begin(), o.algorithms.end(), e.algorithm) == o.algorithms.end())
            o.algorithms.push_back(e.algorithm);
    }
    o.command = request.command;
    o.command_line = request.command_line;
    // Objects need ground truth's pixels: recording them measures error, as --error does.
    o.record_objects = recordsObjects(flags.record);
    o.measure_error = flags.error || o.record_objects;
    o.backend = backendChoice(flags.backend);
    if (flags.frames > 0) o.frames = flags.frames;
    o.repetitions = flags.repetitions;
    const std::optional<occsim::FrameOrder> order = occsim::parseFrameOrder(flags.frame_order);
    if (!order) {
        throw occsim::InputError("--frame-order: expected balanced, rotated or fixed, got '" +
                                 flags.frame_order + "'");
    }
    o.frame_order = *order;
    if (!flags.sweep.empty()) {
        try {
            o.sweep = occsim::parseSweep(flags.sweep, request.algorithms);
        } catch (const std::invalid_argument& e) {
            throw occsim::InputError(std::string("--sweep: ") + e.what());
        }
    }
    o.ablate = flags.ablate;
    if (flags.shadow_casters == "receivers") {
        o.shadow_casters = occsim::ShadowCasterCulling::ReceiverMask;
    } else if (flags.shadow_casters == "culler") {
        o.shadow_casters = occsim::ShadowCasterCulling::Culler;
    } else if (flags.shadow_casters == "culler+receivers") {
        o.shadow_casters = occsim::ShadowCasterCulling::CullerWithReceiverMask;
    } else if (flags.shadow_casters != "frustum") {
        throw occsim::InputError(
            "--shadow-casters: expected frustum, receivers, culler or culler+receivers, got '" +
            flags.shadow_casters + "'");
    }
    // The configurations are planned once here, before any work, so that a swept value that makes
    // options invalid or repeats an ablation row is bad input, named by its flag.
    // A NAME@FILE entry makes the configurations explicit: each plain culler's as planned, each
    // file's beside them, in the order given.
    if (o.sweep || !o.ablate.empty() || anyCullingFile(request.entries)) {
        try {
            if (anyCullingFile(request.entries)) {
                o.configs = entryConfigs(request.entries, request.scenario, o.sweep, o.ablate);
            } else {
                occsim::planConfigs(request.algorithms, request.scenario.culler, o.sweep, o.ablate);
            }
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
    o.segments = runSegments(request.scenario, flags.segments, frames);
    o.progress = occsim::stderrProgressStyle(flags.quiet);
    return o;
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

// The console's text, coloured only where a person reads it (sim/output/console_colour.h).
void printConsole(const std::string& text) {
    std::printf("%s",
                (occsim::stdoutWantsColour() ? occsim::colouredConsoleText(text) : text).c_str());
}

// --wide: the full table and every line as long as it is.
void printWide(const occsim::BenchResult& result) {
    std::string text = occsim::runHeadline(result) + "\n";
    text += occsim::formatComparisonTable(result.runs);
    if (const std::string line = occsim::aggregationLine(result); !line.empty())
        text += line + "\n";
    text += occsim::costsLine(result) + "\n";
    text += occsim::segmentTablesText(result, true);
    text += occsim::worstWindowsText(result, true);
    printConsole(text);
}

// The default: the compact table and the verdict, every line within 100 columns. The compact
// table has no pareto column, so the line on how it was decided goes; the line on how
// repetitions were joined stays.
void printCompact(const occsim::BenchResult& result, const std::string& out_dir,
                  bool objects_recorded) {
    std::string text = occsim::runHeadline(result) + "\n";
    text += occsim::formatCompactTable(result.runs);
    for (const std::string& line : occsim::verdictStatements(result, out_dir, objects_recorded))
        text += line + "\n";
    if (result.metadata.repetitions > 1) text += occsim::aggregationLine(result) + "\n";
    text += occsim::costsLine(result) + "\n";
    text += occsim::segmentTablesText(result) + occsim::worstWindowsText(result);
    printConsole(occsim::wrappedText(text));
}

int runAndReport(const RunRequest& request) {
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
    std::unique_ptr<occsim::ObjectRecorder> objects;
    if (options.record_objects)
        objects = std::make_unique<occsim::ObjectRecorder>(folder.staging());
    options.on_frame = [&pictures, &objects](const occsim::FrameEvent& e) {
        pictures.onFrame(e);
        if (objects) objects->onFrame(e);
    };
    options.on_window_frame = [&pictures](const occsim::ReplayedFrame& f) {
        pictures.onWindowFrame(f);
    };
    options.on_note = printNote;

    watchFrames();
    const occsim::BenchResult result = occsim::runBenchmark(request.scenario, options);
    std::optional<occsim::ObjectHighlights> highlights;
    if (objects) highlights = objects->finish(result);
    const occsim::OutputFiles files = occsim::writeRunOutputs(
        result, {folder.staging(), flags.plots, pictures.birdsEyeFiles(), {}, highlights});
    folder.publish();

    if (flags.wide) {
        printWide(result);
    } else {
        printCompact(result, out_dir.string(), objects != nullptr);
    }
    std::printf("written: %s/{frames.csv,summary.json,report.md}\n", out_dir.string().c_str());
    if (objects) {
        std::printf("objects: %s/%s (occsim why %s --object ID|NAME, --overdraw, --missed)\n",
                    out_dir.string().c_str(), occsim::kObjectsDatabaseFile,
                    out_dir.string().c_str());
    }
    if (!pictures.birdsEyeFiles().empty()) {
        std::printf("bird's-eye pictures: %zu (birds-eye-*.png)\n",
                    pictures.birdsEyeFiles().size());
    }
    if (!pictures.windowFiles().empty()) {
        std::printf("worst-window pictures: %zu (worst-window-*-frame-*.png)\n",
                    pictures.windowFiles().size());
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

}  // namespace

CLI::App* addRun(CLI::App& app, RunFlags& flags) {
    CLI::App* run = app.add_subcommand(
        "run", "Run one algorithm over a scenario (summary, frames.csv, summary.json)");
    addCommonFlags(run, flags.common);
    run->add_option("--algo", flags.algorithm,
                    "Culling algorithm (default: the scenario's), or NAME@FILE with a culling "
                    "file's options (occtune's tuned.json): " +
                        occsim::cullerNameList());
    return run;
}

CLI::App* addBench(CLI::App& app, BenchFlags& flags) {
    CLI::App* bench = app.add_subcommand(
        "bench", "Run several algorithms over the same frames, interleaved, in one table");
    addCommonFlags(bench, flags.common);
    bench->add_option("--algos", flags.algorithms,
                      "Algorithms to compare (default: every registered one, plugins' included); "
                      "NAME@FILE runs NAME with a culling file's options (occtune's tuned.json) "
                      "as a row of its own, NAME@<file stem>");
    bench->add_option(
        "--sweep", flags.common.sweep,
        "Sweep one option, [ALGORITHM:]KEY=V1,V2,...: one configuration per value, for "
        "each listed algorithm with that option (KEY: threshold_pixels, stale_results, "
        "or a key of a culler's options; occsim cullers lists them)");
    bench->add_option(
        "--ablate", flags.common.ablate,
        "Run this algorithm also once with each mechanism its options switch on turned "
        "off (the ablation; occsim cullers marks them)");
    bench->add_option("--frame-order", flags.common.frame_order,
                      "The order each frame renders the configurations in: balanced (the "
                      "default: each after each other equally often), rotated, or fixed (as "
                      "--algos gives them; biased: the one after a heavy configuration pays for "
                      "it)");
    return bench;
}

int runCommand(const RunFlags& flags, const std::string& command_line) {
    RunRequest request = requestOf("run", command_line, flags.common);
    if (flags.algorithm.empty()) {
        request.entries = {{occsim::findCuller(request.scenario.algorithm),
                            request.scenario.algorithm, std::nullopt}};
    } else {
        request.entries = algorithmEntries("--algo", {flags.algorithm});
        // One culler: "a,b" is no algorithm's name.
        if (request.entries.size() != 1) algorithmNamed("--algo", flags.algorithm);
    }
    request.algorithms = plainAlgorithms(request.entries);
    request.default_subdir = "run-" + request.entries.front().label;
    return runAndReport(request);
}

int benchCommand(const BenchFlags& flags, const std::string& command_line) {
    RunRequest request = requestOf("bench", command_line, flags.common);
    if (flags.algorithms_given) {
        request.entries = algorithmEntries("--algos", flags.algorithms);
    } else {
        for (const occsim::CullerRow* a : occsim::cullerRows())
            request.entries.push_back({a, a->name, std::nullopt});
    }
    request.algorithms = plainAlgorithms(request.entries);
    request.default_subdir = "bench";
    return runAndReport(request);
}

}  // namespace occsim_cli
