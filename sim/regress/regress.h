// Scenario-driven regression runs (docs/regression.md). Every scenario with an `expect` block is
// run headless in deterministic-latency mode with the algorithms it names, and checked against:
// - its expectations: zero error pixels and no missed object on every frame for the algorithms
//   that must be conservative (ties in depth are no error: docs/error.md), per-frame error bounds
//   for approximate ones, and frame-time ratios between algorithms measured in the same run (never
//   absolute milliseconds), each with a tolerance;
// - its baseline file: per algorithm and frame, the exact query count, objects drawn and error
//   pixels and missed objects of the last accepted run. `--update` rewrites it (atomically) and
//   says what changed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "occsim/culling/contract/input_error.h"
#include "occsim/culling/registry/registry.h"
#include "sim/regress/scenario_identity.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim {

// What one run produced per algorithm and frame: the exact counts a baseline pins down.
struct AlgorithmTrace {
    std::vector<uint64_t> queries;
    std::vector<uint64_t> objects;
    std::vector<int64_t> error_pixels;
    std::vector<int64_t> missed_objects;
    // Tie pixels are not pinned: which of two objects at the same depth a pixel shows follows the
    // draw order, which a harmless change of traversal can change (docs/error.md).
};

struct Baseline {
    static constexpr int kFormatVersion = 2;  // 2: missed objects; error pixels exclude ties
    std::string scenario;
    uint32_t deterministic_latency = 0;
    uint32_t frames = 0;
    // Where it was made ("egl", "llvmpipe (LLVM 15.0.6, 256 bits)"); empty in baselines written
    // before backends were recorded. Deterministic counts should not depend on them, so a
    // difference is reported beside the checks rather than failing one.
    std::string backend, renderer;
    std::map<std::string, AlgorithmTrace> algorithms;
};

// A baseline file that cannot be used. Its message names the file and the key.
class BaselineError : public InputError {
  public:
    using InputError::InputError;
};

Baseline readBaseline(const std::filesystem::path& file);
std::string baselineJson(const Baseline& baseline);

struct CheckResult {
    std::string check;  // what was checked, e.g. "zero error pixels: statistical"
    std::string expected;
    std::string got;
    bool passed = false;
    // The configuration the check is about ("statistical"); empty for a check of several or of
    // the scenario. A failed check's JUnit entry lists that configuration's pictures only.
    std::string algorithm = {};
};

// The file name of a configuration's worst-error picture, "worst-error-<label>-frame-N.png"
// (the label made one path component), and whether `capture` (a path) is one of its pictures.
std::string worstErrorPictureName(const std::string& algorithm, uint32_t frame);
bool isPictureOf(const std::string& capture, const std::string& algorithm);

struct ScenarioOutcome {
    std::string scenario;  // path as given/found
    std::string id;        // its identity in the run: its folder's name (scenario_identity.h)
    std::string name;
    bool skipped = false;
    std::string note;  // why skipped, or what an update changed
    std::vector<CheckResult> checks;
    std::vector<std::string> captures;  // pictures written for failures (worstErrorPictureName)
    double seconds = 0.0;

    bool passed() const;
    // It was run (not skipped, a valid file), so its folder holds its summary.json.
    bool ran() const;
};

// The check a scenario file that does not parse fails (it runs nothing).
inline constexpr const char* kValidScenarioCheck = "valid scenario and expectations";
// The check a run that ended early fails (BenchResult::partial), instead of every other check.
inline constexpr const char* kEveryFrameCheck = "every frame run";

struct Shard {
    uint32_t index = 0;
    uint32_t count = 1;
};

// "i/n" with 0 <= i < n. Throws std::invalid_argument with a one-line reason.
Shard parseShard(const std::string& text);
// Slurm job arrays (SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT, SLURM_ARRAY_TASK_MIN) or
// Kubernetes indexed jobs (JOB_COMPLETION_INDEX with OCCSIM_SHARD_COUNT); 0/1 when neither is
// set. `get` reads a variable (std::getenv in production). Throws std::invalid_argument.
Shard shardFromEnvironment(const std::function<const char*(const char*)>& get);

// The scenario files under the inputs (collectScenarioFiles(), scenario_identity.h), then this
// shard's share: every count-th from index. Throws InputError as collectScenarioFiles() does.
std::vector<ScenarioFile> collectScenarios(const std::vector<std::filesystem::path>& inputs,
                                           const Shard& shard);

struct RegressOptions {
    std::vector<std::filesystem::path> inputs;
    Shard shard;
    bool update = false;
    // Each scenario's folder in it (named by its id, scenario_identity.h) is replaced as a whole
    // (run_folder.h) under a lock of its own; the caller holds the lock on out_dir.
    std::filesystem::path out_dir = "out/regress";
    bool wait_lock = false;  // wait for a run that holds a scenario folder's lock (else refuse)
    // On stderr: with a bar (a terminal) "[i/n] scenario" before each scenario, and each run's
    // frames as bench gives them (sim/run/progress.h).
    ProgressStyle progress = ProgressStyle::None;
    BackendChoice backend;  // --backend, --device
    // Makes the culler for an algorithm; default makeCuller(). Tests inject broken ones.
    std::function<std::unique_ptr<Culler>(const CullerRow&, const CullerOptions&)> make_culler;
    // The clock frames are timed with (BenchOptions::frame_clock_ms); empty: the steady clock.
    // Tests script it, so that a ratio check sees the same times whatever the machine's load.
    std::function<double()> frame_clock_ms;
    // Applied to each scenario after it is parsed (occsim regress --culling FILE).
    std::function<void(Scenario&)> adjust_scenario;
    // The flags that shaped each scenario's run (--culling FILE, --backend, --plugin, ...), for
    // the command its report.md and summary.json give to rerun that one scenario.
    std::vector<std::string> rerun_flags;
    // Each scenario's folder also gets objects.sqlite (sim/record/object_recorder.h).
    bool record_objects = false;
};

struct RegressReport {
    std::vector<ScenarioOutcome> scenarios;
    // Set when SIGINT or SIGTERM stopped the run (sim/run/stop_request.h): the signal, and one
    // line saying where; the scenario in hand fails its "every frame run" check and those after
    // it are not in `scenarios`.
    int stop_signal = 0;
    std::string stopped;
    bool passed() const;
    std::string table() const;  // scenario, check, expected, got, pass/fail
};

// Every scenario found is read and the run's places checked before any scenario runs: the
// scenario files' identities (collectScenarios()) and every baseline's place
// (checkBaselinePlaces(), baseline_places.h). A problem throws InputError, one line per problem.
RegressReport runRegression(const RegressOptions& options);

// JUnit XML: one testsuite per scenario, one testcase per check.
std::string junitXml(const RegressReport& report);
// `s` as junitXml() writes it once read back: the control characters XML 1.0 forbids (all below
// 0x20 but tab, newline and carriage return) as the text "\xNN".
std::string junitVisibleText(const std::string& s);

}  // namespace occsim
