// runRegression(): the scenarios found, each run in deterministic-latency mode and checked
// (run_checks.h), their folders written, and the report.
#include "sim/regress/regress.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "sim/output/atomic_file.h"
#include "sim/output/run_folder.h"
#include "sim/output/run_outputs.h"
#include "sim/output/shell_quote.h"
#include "sim/record/object_recorder.h"
#include "sim/regress/baseline_places.h"
#include "sim/regress/run_checks.h"
#include "sim/run/runner.h"
#include "sim/run/stop_request.h"
#include "sim/scenario/json_reader.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

// The checks as a section of the scenario's report.md.
std::string checksMarkdown(const ScenarioOutcome& outcome) {
    auto cell = [](const std::string& s) {
        std::string out;
        for (char c : s)
            out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
        return out;
    };
    size_t failed = 0;
    for (const CheckResult& c : outcome.checks) failed += !c.passed;
    std::ostringstream out;
    out << "## Checks\n\n"
        << outcome.checks.size() << " checks, " << failed << " failed.\n\n"
        << "| check | expected | got | result |\n|---|---|---|---|\n";
    for (const CheckResult& c : outcome.checks) {
        out << "| " << cell(c.check) << " | " << cell(c.expected) << " | " << cell(c.got) << " | "
            << (c.passed ? "pass" : "**FAIL**") << " |\n";
    }
    if (!outcome.note.empty()) out << "\n" << outcome.note << "\n";
    // The pictures lie beside report.md: linked by file name, so the folder can move.
    if (!outcome.captures.empty()) out << "\n## Worst frames\n";
    for (const std::string& capture : outcome.captures) {
        const std::string file = std::filesystem::path(capture).filename().string();
        out << "\n`" << file << "`: the culled frame, ground truth, and ground truth dimmed with "
            << "every error pixel in magenta, every tie pixel in yellow, every stray one in cyan "
            << "(occsim's docs/error.md), one above the other, each frame pixel a square.\n\n!["
            << file << "](" << file << ")\n";
    }
    out << "\n";
    return out.str();
}

// A scenario of the run as read before any of them runs: parsed (options.adjust_scenario
// applied), or its outcome already says all: skipped (no expect block) or failed (not a valid
// file).
struct ReadScenario {
    ScenarioFile file;
    std::optional<Scenario> scenario;
    ScenarioOutcome outcome;
};

ReadScenario readRegressScenario(const ScenarioFile& file, const RegressOptions& options) {
    ReadScenario read{file, std::nullopt, {}};
    ScenarioOutcome& outcome = read.outcome;
    outcome.scenario = file.file.string();
    outcome.id = file.id;
    outcome.name = file.file.stem().string();
    try {
        Scenario scenario = parseScenarioFile(file.file);
        if (options.adjust_scenario) options.adjust_scenario(scenario);
        outcome.name = scenario.name;
        if (!scenario.expect) {
            outcome.skipped = true;
            outcome.note = "no expect block";
            return read;
        }
        read.scenario = std::move(scenario);
    } catch (const ScenarioError& e) {
        outcome.checks.push_back({kValidScenarioCheck, "a valid file", e.what(), false});
    }
    return read;
}

// Every scenario of the set read, and every baseline's place checked (baseline_places.h), before
// any of them runs: a problem in any shard's share refuses every shard alike.
std::vector<ReadScenario> readAndCheck(const std::vector<ScenarioFile>& all,
                                       const RegressOptions& options) {
    std::vector<ReadScenario> read;
    std::vector<BaselinePlace> places;
    std::vector<std::filesystem::path> files;
    for (const ScenarioFile& f : all) {
        read.push_back(readRegressScenario(f, options));
        files.push_back(f.file);
        if (read.back().scenario)
            places.push_back(
                {f.file, read.back().scenario->expect->baseline, read.back().scenario->name});
    }
    const std::vector<std::string> problems = baselinePlaceProblems(places, files, options.update);
    if (!problems.empty()) {
        std::string message;
        for (const std::string& p : problems) message += (message.empty() ? "" : "\n") + p;
        throw InputError(message);
    }
    return read;
}

// The run the expectations ask for: their algorithms, deterministic latency, error measured.
BenchOptions regressBenchOptions(const std::filesystem::path& file, const Expectations& expect,
                                 const RegressOptions& options) {
    BenchOptions bench;
    for (const std::string& name : expect.algorithms) bench.algorithms.push_back(findCuller(name));
    bench.measure_error = true;
    bench.latency = {true, expect.deterministic_latency};
    bench.frames = expect.frames;
    bench.command = "regress";
    std::vector<std::string> rerun = {"occsim", "regress", file.string()};
    rerun.insert(rerun.end(), options.rerun_flags.begin(), options.rerun_flags.end());
    rerun.insert(rerun.end(), {"--out", options.out_dir.string()});
    bench.command_line = shellCommand(rerun);
    bench.keep_worst_error_frame = true;
    bench.make_culler = options.make_culler;
    bench.frame_clock_ms = options.frame_clock_ms;
    bench.backend = options.backend;
    bench.progress = options.progress;
    return bench;
}

std::filesystem::path scenarioFolder(const RegressOptions& options, const std::string& id) {
    return options.out_dir / id;
}

ScenarioOutcome runOne(const ReadScenario& read, const RegressOptions& options) {
    ScenarioOutcome outcome = read.outcome;
    if (!read.scenario) return outcome;
    const std::filesystem::path& file = read.file.file;
    const auto start = Clock::now();
    const Scenario& scenario = *read.scenario;
    const Expectations& expect = *scenario.expect;

    // The scenario's folder is one unit, staged before the run and replaced as a whole after
    // (its lock is held by runRegression).
    StagedRunFolder folder(scenarioFolder(options, read.file.id));
    BenchOptions bench = regressBenchOptions(file, expect, options);
    bench.scenario_id = read.file.id;
    bench.segments = regressSegments(scenario, expect);
    std::unique_ptr<ObjectRecorder> objects;
    if (options.record_objects) {
        objects = std::make_unique<ObjectRecorder>(folder.staging());
        bench.record_objects = true;
        bench.on_frame = [&objects](const FrameEvent& e) { objects->onFrame(e); };
    }
    const BenchResult result = runBenchmark(scenario, bench);
    std::optional<ObjectHighlights> highlights;
    if (objects) highlights = objects->finish(result);

    if (result.partial) {
        // Checks of frames that were never run would pass or fail by accident, and an update
        // would write a baseline of half a run: the partial frames are written, and fail.
        outcome.checks.push_back(
            {kEveryFrameCheck,
             std::to_string(result.metadata.frames) + " frames of every configuration",
             partialLine(result), false});
        writeRunOutputs(
            result,
            OutputRequest{folder.staging(), false, {}, checksMarkdown(outcome), highlights});
        folder.publish();
        outcome.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        return outcome;
    }
    ResultChecks checks{result, folder.staging(), folder.target(), outcome};
    checkRun(checks, scenario, expect, options.update);

    writeRunOutputs(
        result, OutputRequest{folder.staging(), false, {}, checksMarkdown(outcome), highlights});
    folder.publish();
    outcome.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return outcome;
}

}  // namespace

bool ScenarioOutcome::passed() const {
    return std::all_of(checks.begin(), checks.end(), [](const CheckResult& c) { return c.passed; });
}

bool ScenarioOutcome::ran() const {
    return !skipped && !(checks.size() == 1 && checks.front().check == kValidScenarioCheck);
}

std::vector<ScenarioFile> collectScenarios(const std::vector<std::filesystem::path>& inputs,
                                           const Shard& shard) {
    return shardOf(collectScenarioFiles(inputs), shard);
}

bool RegressReport::passed() const {
    return std::all_of(scenarios.begin(), scenarios.end(),
                       [](const ScenarioOutcome& s) { return s.passed(); });
}

std::string RegressReport::table() const {
    std::vector<std::vector<std::string>> rows = {
        {"scenario", "check", "expected", "got", "result"}};
    for (const ScenarioOutcome& s : scenarios) {
        if (s.skipped) {
            rows.push_back({s.name, "-", "-", "-", "skipped: " + s.note});
            continue;
        }
        for (const CheckResult& c : s.checks) {
            rows.push_back({s.name, c.check, c.expected, c.got, c.passed ? "pass" : "FAIL"});
        }
    }
    std::vector<size_t> width(5, 0);
    for (const auto& row : rows) {
        for (size_t c = 0; c < 5; ++c) width[c] = std::max(width[c], row[c].size());
    }
    std::ostringstream out;
    for (const auto& row : rows) {
        for (size_t c = 0; c < 5; ++c) {
            out << row[c] << (c + 1 < 5 ? std::string(width[c] - row[c].size() + 2, ' ') : "\n");
        }
    }
    return out.str();
}

RegressReport runRegression(const RegressOptions& options) {
    RegressReport report;
    const std::vector<ScenarioFile> all = collectScenarioFiles(options.inputs);
    const std::vector<ReadScenario> read = readAndCheck(all, options);
    std::vector<const ReadScenario*> mine;  // this shard's share: every count-th from index
    for (size_t i = options.shard.index; i < read.size(); i += options.shard.count)
        mine.push_back(&read[i]);
    claimRegressFolder(options.out_dir);
    // A folder that is not an occsim run is refused before any scenario runs, and each scenario's
    // folder is locked for the whole run: a `run --out` into one of them is refused (or waits)
    // instead of replacing it, or its staging folder, under this run.
    std::vector<std::unique_ptr<FolderLock>> locks;
    for (const ReadScenario* r : mine) {
        checkRunFolder(scenarioFolder(options, r->file.id));
        locks.push_back(
            std::make_unique<FolderLock>(scenarioFolder(options, r->file.id), options.wait_lock));
    }
    for (size_t i = 0; i < mine.size(); ++i) {
        const std::string file = mine[i]->file.file.string();
        if (options.progress == ProgressStyle::Bar)
            std::fprintf(stderr, "[%zu/%zu] %s\n", i + 1, mine.size(), file.c_str());
        report.scenarios.push_back(runOne(*mine[i], options));
        const std::vector<CheckResult>& last = report.scenarios.back().checks;
        const bool cut_short = !last.empty() && last.back().check == kEveryFrameCheck;
        // A signal after the last frame of the last scenario loses nothing: the run is whole.
        if (const int signal = stopSignal(); signal && (cut_short || i + 1 < mine.size())) {
            report.stop_signal = signal;
            report.stopped = std::string("interrupted by ") + signalName(signal) + " in " + file +
                             "; " + std::to_string(i + 1) + " of " + std::to_string(mine.size()) +
                             " scenarios ran";
            if (cut_short) report.stopped += ", the last one partly";
            break;
        }
    }
    return report;
}

}  // namespace occsim
