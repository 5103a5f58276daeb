#include "sim/regress/run_checks.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "render/png_writer.h"
#include "sim/output/atomic_file.h"
#include "sim/output/error_picture.h"
#include "sim/output/fixed_text.h"
#include "sim/output/run_folder.h"

namespace occsim {
namespace {

// Compares one per-frame series against the baseline; describes the first difference.
template <class T>
CheckResult compareSeries(const std::string& what, const std::string& algorithm,
                          const std::vector<T>& expected, const std::vector<T>& got) {
    CheckResult c;
    c.check = what + " per frame = baseline: " + algorithm;
    c.algorithm = algorithm;
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

void checkZeroError(ResultChecks& checks, const Expectations& expect) {
    for (const std::string& name : expect.zero_error) {
        const RunSummary& s = checks.runOf(name).summary;
        CheckResult c{"zero error pixels: " + name, "0 on every frame", "",
                      s.error_pixels_total == 0, name};
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
                      s.missed_objects_total == 0, name};
        m.got = std::to_string(s.missed_objects_total) + " (visible in ground truth, not drawn)";
        checks.outcome.checks.push_back(m);
        if (s.shadow_error_pixels_total < 0) continue;  // no shadow pass (docs/views.md)
        CheckResult sh{"zero shadow error pixels: " + name, "0 on every frame",
                       std::to_string(s.shadow_error_pixels_total) + " (" +
                           std::to_string(s.shadow_tie_pixels_total) + " shadow tie px)",
                       s.shadow_error_pixels_total == 0, name};
        checks.outcome.checks.push_back(sh);
        CheckResult mc{"no missed casters: " + name, "0 on every frame",
                       std::to_string(s.missed_casters_total) +
                           " (their shadow on a visible pixel in ground truth, not drawn)",
                       s.missed_casters_total == 0, name};
        checks.outcome.checks.push_back(mc);
    }
}

void checkMaxErrorPixels(ResultChecks& checks, const Expectations& expect) {
    for (const auto& [name, bound] : expect.max_error_pixels) {
        const RunSummary& s = checks.runOf(name).summary;
        CheckResult c{"error pixels per frame: " + name, "<= " + std::to_string(bound),
                      std::to_string(s.error_pixels_worst) + " (frame " +
                          std::to_string(s.error_worst_frame) + ")",
                      s.error_pixels_worst <= bound, name};
        if (!c.passed) checks.capture(name);
        checks.outcome.checks.push_back(c);
    }
}

// The segment of the run a check names (the parser checked it is one of the scenario's, whole
// within the run).
size_t segmentIndex(const ResultChecks& checks, const std::string& name) {
    const std::vector<Segment>& segments = checks.result.metadata.segments;
    for (size_t k = 0; k < segments.size(); ++k) {
        if (segments[k].name == name) return k;
    }
    throw std::logic_error("no segment " + name);
}

// An algorithm's summary over the whole run (segment empty) or over one segment.
const RunSummary& summaryIn(const ResultChecks& checks, const std::string& algorithm,
                            const std::string& segment) {
    const RunRecord& r = checks.runOf(algorithm);
    return segment.empty() ? r.summary : r.segments.at(segmentIndex(checks, segment));
}

// zero_error and max_error_pixels over one segment's frames. A failure pictures the run's worst
// error frame when it lies in the segment (the run keeps one worst frame per algorithm).
void checkSegmentErrors(ResultChecks& checks, const Expectations& expect) {
    for (const SegmentErrorExpectation& e : expect.segment_errors) {
        const Segment& seg = checks.result.metadata.segments.at(segmentIndex(checks, e.segment));
        const RunSummary& s = summaryIn(checks, e.algorithm, e.segment);
        const std::string frames = "frames " + std::to_string(seg.first_frame) + " to " +
                                   std::to_string(seg.end_frame - 1);
        const std::string worst = std::to_string(s.error_pixels_worst) + " (frame " +
                                  std::to_string(s.error_worst_frame) + ")";
        CheckResult c;
        if (e.max_pixels) {
            c = {"error pixels per frame in segment " + e.segment + ": " + e.algorithm,
                 "<= " + std::to_string(*e.max_pixels) + " on " + frames, worst,
                 s.error_pixels_worst <= *e.max_pixels};
        } else {
            c = {"zero error pixels in segment " + e.segment + ": " + e.algorithm, "0 on " + frames,
                 "", s.error_pixels_total == 0};
            c.got = c.passed ? "0"
                             : std::to_string(s.error_pixels_total) + " px on " +
                                   std::to_string(s.frames_with_error) + " frames (worst frame " +
                                   worst + ")";
        }
        if (!c.passed) {
            const uint32_t pictured = checks.runOf(e.algorithm).summary.error_worst_frame;
            if (seg.contains(pictured)) {
                checks.capture(e.algorithm);
            } else {
                c.got += "; no picture: the run's worst error frame, " + std::to_string(pictured) +
                         ", lies outside the segment";
            }
        }
        checks.outcome.checks.push_back(c);
        if (e.max_pixels) continue;
        checks.outcome.checks.push_back(
            {"no missed objects in segment " + e.segment + ": " + e.algorithm, "0 on " + frames,
             std::to_string(s.missed_objects_total) + " (visible in ground truth, not drawn)",
             s.missed_objects_total == 0});
    }
}

void checkRatios(ResultChecks& checks, const Expectations& expect, const Scenario& scenario) {
    for (const RatioExpectation& r : expect.ratios) {
        const RunSummary& sa = summaryIn(checks, r.algorithm, r.segment);
        const RunSummary& sb = summaryIn(checks, r.reference, r.segment);
        const double a = sa.frame_ms.mean, b = sb.frame_ms.mean;
        const double limit = r.max * (1.0 + r.tolerance);
        const std::string in = r.segment.empty() ? "" : " in segment " + r.segment;
        CheckResult c{"frame time " + r.algorithm + " / " + r.reference + in,
                      "<= " + fixed(r.max, 2) + " (+" + fixed(100 * r.tolerance, 0) +
                          "% = " + fixed(limit, 2) + ")",
                      "", false};
        // A ratio of nothing (every frame warm-up, or a reference that took no time) cannot
        // judge anything: it fails rather than read 0/0 as a pass.
        if (sa.timed_frames == 0 || sb.timed_frames == 0 || !(b > 0)) {
            c.got = "nothing timed: " + std::to_string(std::min(sa.timed_frames, sb.timed_frames)) +
                    " frames after warm-up (" +
                    std::to_string(expect.frames.value_or(scenario.frames)) +
                    " frames, warmup_frames " + std::to_string(scenario.warmup_frames) + ")" +
                    (r.segment.empty() ? "; raise expect.frames"
                                       : " in the segment; move it past the warm-up");
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

}  // namespace

std::string worstErrorPictureName(const std::string& algorithm, uint32_t frame) {
    return "worst-error-" + safeFileName(algorithm) + "-frame-" + std::to_string(frame) + ".png";
}

bool isPictureOf(const std::string& capture, const std::string& algorithm) {
    const std::string name = std::filesystem::path(capture).filename().string();
    return !algorithm.empty() &&
           name.rfind("worst-error-" + safeFileName(algorithm) + "-frame-", 0) == 0;
}

void ResultChecks::capture(const std::string& algorithm) {
    for (size_t a = 0; a < result.runs.size(); ++a) {
        if (result.runs[a].summary.label != algorithm) continue;
        const ErrorFrame& worst = result.worst_error_frames[a];
        if (worst.error_pixels == 0) return;
        const std::string name = worstErrorPictureName(algorithm, worst.frame);
        const std::string published = (published_dir / name).string();
        // An algorithm that fails several error checks (zero error and its baseline) has
        // one worst frame: one picture, named once.
        const auto& taken = outcome.captures;
        if (std::find(taken.begin(), taken.end(), published) != taken.end()) return;
        const LabelledPicture picture =
            labelledErrorPicture(worst, result.metadata.width, result.metadata.height, algorithm);
        writeFileAtomically(out_dir / name,
                            encodePngBottomUp(picture.rgba, picture.width, picture.height));
        outcome.captures.push_back(published);
    }
}

std::vector<Segment> regressSegments(const Scenario& scenario, const Expectations& expect) {
    return planSegments(scenario.segments, scenario.frames, {},
                        expect.frames.value_or(scenario.frames), scenario.dt_s)
        .segments;
}

void checkRun(ResultChecks& checks, const Scenario& scenario, const Expectations& expect,
              bool update) {
    checkZeroError(checks, expect);
    checkMaxErrorPixels(checks, expect);
    checkSegmentErrors(checks, expect);
    checkRatios(checks, expect, scenario);
    checkBaseline(checks, expect, baselineOf(scenario, expect, checks.result), update);
}

}  // namespace occsim
