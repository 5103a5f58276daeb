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

// The scenario of a regression run (options.adjust_scenario applied), or nothing when the
// outcome already says all: skipped (no expect block) or failed (not a valid file).
std::optional<Scenario> readRegressScenario(const std::filesystem::path& file,
                                            const RegressOptions& options,
                                            ScenarioOutcome& outcome) {
    Scenario scenario;
    try {
        scenario = parseScenarioFile(file);
        if (options.adjust_scenario) options.adjust_scenario(scenario);
        outcome.name = scenario.name;
        if (!scenario.expect) {
            outcome.skipped = true;
            outcome.note = "no expect block";
            return std::nullopt;
        }
    } catch (const ScenarioError& e) {
        outcome.checks.push_back({kValidScenarioCheck, "a valid file", e.what(), false});
        return std::nullopt;
    }
    return scenario;
}

// The run the expectations ask for: their algorithms, deterministic latency, error measured.
BenchOptions regressBenchOptions(const std::filesystem::path& file, const Expectations& expect,
                                 const RegressOptions& options) {
    BenchOptions bench;
    for (const std::string& name : expect.algorithms)
        bench.algorithms.push_back(findAlgorithm(name));
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
    bench.backend = options.backend;
    return bench;
}

std::filesystem::path scenarioFolder(const RegressOptions& options,
                                     const std::filesystem::path& file) {
    return options.out_dir / safeFileName(file.stem().string());
}

ScenarioOutcome runOne(const std::filesystem::path& file, const RegressOptions& options) {
    ScenarioOutcome outcome;
    outcome.scenario = file.string();
    outcome.name = file.stem().string();
    const auto start = Clock::now();
    const std::optional<Scenario> read = readRegressScenario(file, options, outcome);
    if (!read) return outcome;
    const Scenario& scenario = *read;
    const Expectations& expect = *scenario.expect;

    // The scenario's folder is one unit, staged before the run and replaced as a whole after.
    StagedRunFolder folder(scenarioFolder(options, file));
    BenchOptions bench = regressBenchOptions(file, expect, options);
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

std::vector<std::filesystem::path> collectScenarios(
    const std::vector<std::filesystem::path>& inputs, const Shard& shard) {
    std::set<std::filesystem::path> found;
    auto isScenario = [](const std::filesystem::path& p) {
        const std::string name = p.filename().string();
        return p.extension() == ".json" && !name.ends_with(".baseline.json");
    };
    for (const auto& input : inputs) {
        if (std::filesystem::is_directory(input)) {
            for (const auto& entry : std::filesystem::recursive_directory_iterator(input)) {
                if (entry.is_regular_file() && isScenario(entry.path())) found.insert(entry.path());
            }
        } else {
            found.insert(input);  // a missing file is reported when it is parsed
        }
    }
    std::vector<std::filesystem::path> mine;
    size_t i = 0;
    for (const auto& path : found) {
        if (i++ % shard.count == shard.index) mine.push_back(path);
    }
    return mine;
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
    const auto files = collectScenarios(options.inputs, options.shard);
    // A folder that is not an occsim run is refused before any scenario runs.
    for (const auto& file : files) checkRunFolder(scenarioFolder(options, file));
    for (size_t i = 0; i < files.size(); ++i) {
        if (options.progress) {
            std::fprintf(stderr, "[%zu/%zu] %s\n", i + 1, files.size(), files[i].string().c_str());
        }
        report.scenarios.push_back(runOne(files[i], options));
        if (const int signal = stopSignal()) {
            report.stop_signal = signal;
            report.stopped = std::string("interrupted by ") + signalName(signal) + " in " +
                             files[i].string() + "; " + std::to_string(i + 1) + " of " +
                             std::to_string(files.size()) + " scenarios ran";
            const std::vector<CheckResult>& last = report.scenarios.back().checks;
            if (!last.empty() && last.back().check == kEveryFrameCheck)
                report.stopped += ", the last one partly";
            break;
        }
    }
    return report;
}

}  // namespace occsim
