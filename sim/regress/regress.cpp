#include "sim/regress/regress.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "render/png_writer.h"
#include "sim/output/atomic_file.h"
#include "sim/output/error_picture.h"
#include "sim/output/fixed_text.h"
#include "sim/output/run_folder.h"
#include "sim/output/run_outputs.h"
#include "sim/output/shell_quote.h"
#include "sim/run/runner.h"
#include "sim/run/stop_request.h"
#include "sim/scenario/json_reader.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw BaselineError(file.string() + ": cannot open the baseline file");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

template <class T>
std::vector<T> readSeries(JsonObjectReader& trace, const char* key, uint32_t frames) {
    const JsonArrayReader array = trace.array(key);
    if (array.size() != frames) {
        trace.fail(key, "expected " + std::to_string(frames) + " values (one per frame), got " +
                            std::to_string(array.size()));
    }
    std::vector<T> values;
    for (size_t i = 0; i < array.size(); ++i) {
        const JsonValueReader v = array.at(i);
        if constexpr (std::is_signed_v<T>) {
            const double d = v.asNumber(NumberRange::atLeast(-1.0));
            if (d != std::floor(d)) v.failExpected("an integer");
            values.push_back(static_cast<T>(d));
        } else {
            values.push_back(static_cast<T>(v.asUnsigned()));
        }
    }
    return values;
}

// Compares one per-frame series against the baseline; describes the first difference.
template <class T>
CheckResult compareSeries(const std::string& what, const std::string& algorithm,
                          const std::vector<T>& expected, const std::vector<T>& got) {
    CheckResult c;
    c.check = what + " per frame = baseline: " + algorithm;
    c.passed = expected == got;
    if (c.passed) {
        c.expected = c.got = "identical over " + std::to_string(got.size()) + " frames";
        return c;
    }
    size_t frame = 0;
    while (frame < expected.size() && frame < got.size() && expected[frame] == got[frame]) ++frame;
    size_t differing = 0;
    for (size_t i = 0; i < std::min(expected.size(), got.size()); ++i)
        differing += expected[i] != got[i];
    if (frame < expected.size() && frame < got.size()) {
        c.expected = "frame " + std::to_string(frame) + ": " + std::to_string(expected[frame]);
        c.got = std::to_string(got[frame]) + " (" + std::to_string(differing) + " frames differ)";
    } else {
        c.expected = std::to_string(expected.size()) + " frames";
        c.got = std::to_string(got.size()) + " frames";
    }
    return c;
}

template <class T>
std::string describeChange(const char* what, const std::vector<T>& before,
                           const std::vector<T>& after) {
    if (before == after) return "";
    long long sum_before = 0, sum_after = 0;
    size_t changed = 0;
    for (size_t i = 0; i < std::max(before.size(), after.size()); ++i) {
        const long long b = i < before.size() ? static_cast<long long>(before[i]) : 0;
        const long long a = i < after.size() ? static_cast<long long>(after[i]) : 0;
        sum_before += b;
        sum_after += a;
        changed += a != b;
    }
    return std::string(what) + " changed on " + std::to_string(changed) + " frames (total " +
           std::to_string(sum_before) + " -> " + std::to_string(sum_after) + ")";
}

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

// The checks of one run: they go into the outcome, and a failed error check takes a picture of
// the worst error frame into the scenario's output folder.
struct ResultChecks {
    const BenchResult& result;
    const std::filesystem::path& out_dir;        // written now: the staging folder
    const std::filesystem::path& published_dir;  // where the pictures will be once published
    ScenarioOutcome& outcome;

    const RunRecord& runOf(const std::string& name) const {
        for (const RunRecord& r : result.runs) {
            if (r.summary.label == name) return r;
        }
        throw std::logic_error("no run for " + name);
    }

    void capture(const std::string& algorithm) {
        for (size_t a = 0; a < result.runs.size(); ++a) {
            if (result.runs[a].summary.label != algorithm) continue;
            const ErrorFrame& worst = result.worst_error_frames[a];
            if (worst.error_pixels == 0) return;
            const std::string name = "worst-error-" + safeFileName(algorithm) + "-frame-" +
                                     std::to_string(worst.frame) + ".png";
            const std::string published = (published_dir / name).string();
            // An algorithm that fails several error checks (zero error and its baseline) has
            // one worst frame: one picture, named once.
            const auto& taken = outcome.captures;
            if (std::find(taken.begin(), taken.end(), published) != taken.end()) return;
            const LabelledPicture picture = labelledErrorPicture(worst, result.metadata.width,
                                                                 result.metadata.height, algorithm);
            writeFileAtomically(out_dir / name,
                                encodePngBottomUp(picture.rgba, picture.width, picture.height));
            outcome.captures.push_back(published);
        }
    }
};

void checkZeroError(ResultChecks& checks, const Expectations& expect) {
    for (const std::string& name : expect.zero_error) {
        const RunSummary& s = checks.runOf(name).summary;
        CheckResult c{"zero error pixels: " + name, "0 on every frame", "",
                      s.error_pixels_total == 0};
        // Ties (another object at the same depth) are no error; shown so a reader sees them apart.
        const std::string ties = " (" + std::to_string(s.tie_pixels_total) + " tie px)";
        c.got = c.passed ? "0" + ties
                         : std::to_string(s.error_pixels_total) + " px on " +
                               std::to_string(s.frames_with_error) + " frames (worst frame " +
                               std::to_string(s.error_worst_frame) + ": " +
                               std::to_string(s.error_pixels_worst) + " px)" + ties;
        if (!c.passed) checks.capture(name);
        checks.outcome.checks.push_back(c);
        CheckResult m{"no missed objects: " + name, "0 on every frame", "",
                      s.missed_objects_total == 0};
        m.got = std::to_string(s.missed_objects_total) + " (visible in ground truth, not drawn)";
        checks.outcome.checks.push_back(m);
    }
}

void checkMaxErrorPixels(ResultChecks& checks, const Expectations& expect) {
    for (const auto& [name, bound] : expect.max_error_pixels) {
        const RunSummary& s = checks.runOf(name).summary;
        CheckResult c{"error pixels per frame: " + name, "<= " + std::to_string(bound),
                      std::to_string(s.error_pixels_worst) + " (frame " +
                          std::to_string(s.error_worst_frame) + ")",
                      s.error_pixels_worst <= bound};
        if (!c.passed) checks.capture(name);
        checks.outcome.checks.push_back(c);
    }
}

void checkRatios(ResultChecks& checks, const Expectations& expect, const Scenario& scenario) {
    for (const RatioExpectation& r : expect.ratios) {
        const RunSummary& sa = checks.runOf(r.algorithm).summary;
        const RunSummary& sb = checks.runOf(r.reference).summary;
        const double a = sa.frame_ms.mean, b = sb.frame_ms.mean;
        const double limit = r.max * (1.0 + r.tolerance);
        CheckResult c{"frame time " + r.algorithm + " / " + r.reference,
                      "<= " + fixed(r.max, 2) + " (+" + fixed(100 * r.tolerance, 0) +
                          "% = " + fixed(limit, 2) + ")",
                      "", false};
        // A ratio of nothing (every frame warm-up, or a reference that took no time) cannot
        // judge anything: it fails rather than read 0/0 as a pass.
        if (sa.timed_frames == 0 || sb.timed_frames == 0 || !(b > 0)) {
            c.got = "nothing timed: " + std::to_string(std::min(sa.timed_frames, sb.timed_frames)) +
                    " frames after warm-up (" +
                    std::to_string(expect.frames.value_or(scenario.frames)) +
                    " frames, warmup_frames " + std::to_string(scenario.warmup_frames) +
                    "); raise expect.frames";
        } else {
            const double ratio = a / b;
            c.got = fixed(ratio, 3) + " (" + fixed(a, 2) + " / " + fixed(b, 2) + " ms)";
            c.passed = ratio <= limit;
        }
        checks.outcome.checks.push_back(c);
    }
}

// This run's counts, frame by frame, as a baseline file holds them.
Baseline baselineOf(const Scenario& scenario, const Expectations& expect,
                    const BenchResult& result) {
    Baseline now;
    now.scenario = scenario.name;
    now.deterministic_latency = expect.deterministic_latency;
    now.frames = static_cast<uint32_t>(result.runs.front().frames.size());
    now.backend = result.metadata.backend;
    now.renderer = result.metadata.gl_renderer;
    for (const RunRecord& r : result.runs) {
        AlgorithmTrace& t = now.algorithms[r.summary.label];
        for (const FrameStats& f : r.frames) {
            t.queries.push_back(f.queries);
            t.objects.push_back(f.objects_drawn);
            t.error_pixels.push_back(f.error_pixels);
            t.missed_objects.push_back(f.missed_objects);
        }
    }
    return now;
}

// The baseline file as found: read, or what is wrong with it (missing, unreadable).
struct OldBaseline {
    std::optional<Baseline> baseline;
    std::string problem;
    bool existed = false;
};

OldBaseline readOldBaseline(const std::filesystem::path& file) {
    OldBaseline old;
    old.existed = std::filesystem::exists(file);
    if (old.existed) {
        try {
            old.baseline = readBaseline(file);
        } catch (const BaselineError& e) {
            old.problem = e.what();
        }
    } else {
        old.problem = file.string() + ": no baseline file (create it with --update)";
    }
    return old;
}

// What --update changes, one line per algorithm and series that differs.
std::vector<std::string> baselineChanges(const Baseline& now, const std::optional<Baseline>& old) {
    std::vector<std::string> changes;
    for (const auto& [name, trace] : now.algorithms) {
        const AlgorithmTrace* before = nullptr;
        if (old && old->algorithms.count(name)) before = &old->algorithms.at(name);
        if (!before) {
            changes.push_back(name + ": new");
            continue;
        }
        for (const std::string& d :
             {describeChange("queries", before->queries, trace.queries),
              describeChange("objects", before->objects, trace.objects),
              describeChange("error pixels", before->error_pixels, trace.error_pixels),
              describeChange("missed objects", before->missed_objects, trace.missed_objects)}) {
            if (!d.empty()) changes.push_back(name + ": " + d);
        }
    }
    if (old) {
        for (const auto& [name, trace] : old->algorithms) {
            if (!now.algorithms.count(name)) changes.push_back(name + ": removed");
        }
    }
    return changes;
}

void updateBaseline(ScenarioOutcome& outcome, const std::filesystem::path& file,
                    const Baseline& now, const OldBaseline& old) {
    const std::vector<std::string> changes = baselineChanges(now, old.baseline);
    writeFileAtomically(file, baselineJson(now));
    outcome.note = file.string() + (changes.empty() ? ": unchanged" : ": updated");
    // An unreadable old file (another format version) is replaced, not compared: say so, or
    // every algorithm would read as new.
    if (old.existed && !old.baseline) {
        outcome.note += " (the old file was not compared: " + old.problem + ")";
    }
    for (const auto& c : changes) outcome.note += "\n    " + c;
}

// Deterministic counts should not depend on where they were rendered; if a check fails, this
// says what differed besides the code. Empty when the baseline was made on this backend.
std::string renderedElsewhere(const Baseline& old, const Baseline& now) {
    if ((!old.backend.empty() && old.backend != now.backend) ||
        (!old.renderer.empty() && old.renderer != now.renderer)) {
        return "baseline made on " + old.backend + " (" + old.renderer + "), this run on " +
               now.backend + " (" + now.renderer + ")";
    }
    return "";
}

// Every series of every algorithm against the baseline's, frame by frame.
void compareWithBaseline(ResultChecks& checks, const Baseline& old, const Baseline& now,
                         const std::string& elsewhere) {
    std::vector<CheckResult>& out = checks.outcome.checks;
    if (old.deterministic_latency != now.deterministic_latency || old.frames != now.frames) {
        out.push_back({"baseline settings",
                       std::to_string(old.frames) + " frames, latency " +
                           std::to_string(old.deterministic_latency),
                       std::to_string(now.frames) + " frames, latency " +
                           std::to_string(now.deterministic_latency),
                       false});
        return;
    }
    for (const auto& [name, trace] : now.algorithms) {
        const auto it = old.algorithms.find(name);
        if (it == old.algorithms.end()) {
            out.push_back(
                {"baseline has " + name, "present", "missing (run with --update)", false});
            continue;
        }
        out.push_back(compareSeries("queries", name, it->second.queries, trace.queries));
        out.push_back(compareSeries("objects", name, it->second.objects, trace.objects));
        out.push_back(
            compareSeries("error pixels", name, it->second.error_pixels, trace.error_pixels));
        if (!out.back().passed) checks.capture(name);
        out.push_back(
            compareSeries("missed objects", name, it->second.missed_objects, trace.missed_objects));
        // A count check that fails against a baseline made on another backend says so.
        if (!elsewhere.empty()) {
            for (size_t k = out.size() - 4; k < out.size(); ++k) {
                if (!out[k].passed) out[k].got += " [" + elsewhere + "]";
            }
        }
    }
}

// The baseline: written (--update), or compared with this run's counts.
void checkBaseline(ResultChecks& checks, const Expectations& expect, const Baseline& now,
                   bool update) {
    ScenarioOutcome& outcome = checks.outcome;
    const OldBaseline old = readOldBaseline(expect.baseline);
    if (update) {
        updateBaseline(outcome, expect.baseline, now, old);
        return;
    }
    if (!old.problem.empty()) {
        outcome.checks.push_back(
            {"baseline", "a readable baseline of this format", old.problem, false});
        return;
    }
    const std::string elsewhere = renderedElsewhere(*old.baseline, now);
    if (!elsewhere.empty()) outcome.note = expect.baseline.string() + ": " + elsewhere;
    compareWithBaseline(checks, *old.baseline, now, elsewhere);
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
    const BenchResult result = runBenchmark(scenario, regressBenchOptions(file, expect, options));

    if (result.partial) {
        // Checks of frames that were never run would pass or fail by accident, and an update
        // would write a baseline of half a run: the partial frames are written, and fail.
        outcome.checks.push_back(
            {kEveryFrameCheck,
             std::to_string(result.metadata.frames) + " frames of every configuration",
             partialLine(result), false});
        writeRunOutputs(result,
                        OutputRequest{folder.staging(), false, {}, checksMarkdown(outcome)});
        folder.publish();
        outcome.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        return outcome;
    }
    ResultChecks checks{result, folder.staging(), folder.target(), outcome};
    checkZeroError(checks, expect);
    checkMaxErrorPixels(checks, expect);
    checkRatios(checks, expect, scenario);
    checkBaseline(checks, expect, baselineOf(scenario, expect, result), options.update);

    writeRunOutputs(result, OutputRequest{folder.staging(), false, {}, checksMarkdown(outcome)});
    folder.publish();
    outcome.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return outcome;
}

std::string xmlEscape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

}  // namespace

Baseline readBaseline(const std::filesystem::path& file) {
    const std::string name = file.string();
    try {
        const Json root = parseStrictJson(readText(file), name);
        JsonObjectReader top(root, "", name);
        if (top.string("format", "") != "occsim-baseline") {
            top.fail("format", "expected \"occsim-baseline\": this is not an occsim baseline file");
        }
        const JsonValueReader version = top.required("version");
        if (!(version.json().is_number_integer() && version.json() == Baseline::kFormatVersion)) {
            throw BaselineError(name + ": /version: baseline format version " +
                                version.json().dump() + "; this program reads version " +
                                std::to_string(Baseline::kFormatVersion) +
                                " (rewrite it with --update)");
        }
        Baseline b;
        b.scenario = top.string("scenario", "");
        b.deterministic_latency =
            static_cast<uint32_t>(top.requiredUnsignedInteger("deterministic_latency"));
        b.frames = static_cast<uint32_t>(top.requiredUnsignedInteger("frames", 1));
        b.backend = top.string("backend", "");
        b.renderer = top.string("renderer", "");
        const JsonValueReader algorithms_value = top.required("algorithms");
        JsonObjectReader algorithms = algorithms_value.asObject();
        for (const auto& item : algorithms_value.json().items()) {
            const std::string algorithm = item.key();
            JsonObjectReader trace = algorithms.required(algorithm).asObject();
            AlgorithmTrace t;
            t.queries = readSeries<uint64_t>(trace, "queries", b.frames);
            t.objects = readSeries<uint64_t>(trace, "objects", b.frames);
            t.error_pixels = readSeries<int64_t>(trace, "error_pixels", b.frames);
            t.missed_objects = readSeries<int64_t>(trace, "missed_objects", b.frames);
            trace.finish();
            b.algorithms[algorithm] = std::move(t);
        }
        algorithms.finish();
        top.finish();
        return b;
    } catch (const ScenarioError& e) {
        throw BaselineError(e.what());
    }
}

std::string baselineJson(const Baseline& b) {
    // One line per series keeps diffs of a baseline readable in review.
    std::ostringstream out;
    out << "{\n  \"format\": \"occsim-baseline\",\n  \"version\": " << Baseline::kFormatVersion
        << ",\n  \"scenario\": " << Json(b.scenario).dump()
        << ",\n  \"deterministic_latency\": " << b.deterministic_latency
        << ",\n  \"frames\": " << b.frames;
    if (!b.backend.empty()) out << ",\n  \"backend\": " << Json(b.backend).dump();
    if (!b.renderer.empty()) out << ",\n  \"renderer\": " << Json(b.renderer).dump();
    out << ",\n  \"algorithms\": {";
    bool first = true;
    for (const auto& [name, t] : b.algorithms) {
        out << (first ? "" : ",") << "\n    " << Json(name).dump()
            << ": {\n      \"queries\": " << Json(t.queries).dump()
            << ",\n      \"objects\": " << Json(t.objects).dump()
            << ",\n      \"error_pixels\": " << Json(t.error_pixels).dump()
            << ",\n      \"missed_objects\": " << Json(t.missed_objects).dump() << "\n    }";
        first = false;
    }
    out << "\n  }\n}\n";
    return out.str();
}

bool ScenarioOutcome::passed() const {
    return std::all_of(checks.begin(), checks.end(), [](const CheckResult& c) { return c.passed; });
}

bool ScenarioOutcome::ran() const {
    return !skipped && !(checks.size() == 1 && checks.front().check == kValidScenarioCheck);
}

Shard parseShard(const std::string& text) {
    const auto slash = text.find('/');
    auto number = [&](const std::string& part) -> long {
        if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos ||
            part.size() > 6) {
            throw std::invalid_argument("expected a shard as i/n with 0 <= i < n, got '" + text +
                                        "'");
        }
        return std::stol(part);
    };
    if (slash == std::string::npos) {
        throw std::invalid_argument("expected a shard as i/n with 0 <= i < n, got '" + text + "'");
    }
    const long i = number(text.substr(0, slash)), n = number(text.substr(slash + 1));
    if (n < 1 || i >= n)
        throw std::invalid_argument("expected a shard as i/n with 0 <= i < n, got '" + text + "'");
    return {static_cast<uint32_t>(i), static_cast<uint32_t>(n)};
}

Shard shardFromEnvironment(const std::function<const char*(const char*)>& get) {
    auto value = [&](const char* name) -> std::optional<long> {
        const char* v = get(name);
        if (v == nullptr || *v == '\0') return std::nullopt;
        const std::string s(v);
        if (s.find_first_not_of("0123456789") != std::string::npos || s.size() > 9) {
            throw std::invalid_argument(std::string(name) +
                                        ": expected a non-negative integer, got '" + s + "'");
        }
        return std::stol(s);
    };
    if (const auto id = value("SLURM_ARRAY_TASK_ID")) {
        const auto count = value("SLURM_ARRAY_TASK_COUNT");
        if (!count)
            throw std::invalid_argument(
                "SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not");
        const long first = value("SLURM_ARRAY_TASK_MIN").value_or(0);
        return parseShard(std::to_string(*id - first) + "/" + std::to_string(*count));
    }
    if (const auto index = value("JOB_COMPLETION_INDEX")) {
        const auto count = value("OCCSIM_SHARD_COUNT");
        if (!count) {
            throw std::invalid_argument(
                "JOB_COMPLETION_INDEX is set but OCCSIM_SHARD_COUNT is not "
                "(set it to the Job's completions)");
        }
        return parseShard(std::to_string(*index) + "/" + std::to_string(*count));
    }
    return {};
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

std::string junitXml(const RegressReport& report) {
    size_t tests = 0, failures = 0, skipped = 0;
    double seconds = 0;
    for (const ScenarioOutcome& s : report.scenarios) {
        tests += s.skipped ? 1 : s.checks.size();
        skipped += s.skipped;
        for (const CheckResult& c : s.checks) failures += !c.passed;
        seconds += s.seconds;
    }
    std::ostringstream out;
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"occsim regress\" "
           "tests=\""
        << tests << "\" failures=\"" << failures << "\" skipped=\"" << skipped << "\" time=\""
        << fixed(seconds, 3) << "\">\n";
    for (const ScenarioOutcome& s : report.scenarios) {
        size_t f = 0;
        for (const CheckResult& c : s.checks) f += !c.passed;
        out << "  <testsuite name=\"" << xmlEscape(s.name) << "\" file=\"" << xmlEscape(s.scenario)
            << "\" tests=\"" << (s.skipped ? 1 : s.checks.size()) << "\" failures=\"" << f
            << "\" skipped=\"" << (s.skipped ? 1 : 0) << "\" time=\"" << fixed(s.seconds, 3)
            << "\">\n";
        if (s.skipped) {
            out << "    <testcase classname=\"" << xmlEscape(s.name) << "\" name=\"scenario\">"
                << "<skipped message=\"" << xmlEscape(s.note) << "\"/></testcase>\n";
        }
        for (const CheckResult& c : s.checks) {
            out << "    <testcase classname=\"" << xmlEscape(s.name) << "\" name=\""
                << xmlEscape(c.check) << "\"";
            if (c.passed) {
                out << "/>\n";
            } else {
                std::string detail = "expected " + c.expected + ", got " + c.got;
                for (const auto& capture : s.captures) detail += "\ncapture: " + capture;
                out << "><failure message=\""
                    << xmlEscape("expected " + c.expected + ", got " + c.got) << "\">"
                    << xmlEscape(detail) << "</failure></testcase>\n";
            }
        }
        out << "  </testsuite>\n";
    }
    out << "</testsuites>\n";
    return out.str();
}

}  // namespace occsim
