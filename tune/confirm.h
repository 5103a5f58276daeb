// The confirmation: the tuned setting against the reference (the culler's defaults; for
// `statistical`, the paper's values), interleaved frame by frame in the same run, repeated, on the
// frames they were fitted on and on a variant the fit never saw. A setting is its options and the
// cost model it runs with (Setting): what tuned.json will carry is what is confirmed.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "occsim/culling/registry/culler_options.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"
#include "tune/measure.h"

namespace occsim::tune {

struct Spread {
    double median = 0.0, min = 0.0, max = 0.0;
};

struct ConfirmationRow {
    std::string variant;  // what was run, e.g. "fitted (seed 2005)"
    uint64_t seed = 0;
    uint32_t frames = 0;
    uint32_t repetitions = 0;
    std::string renderer;  // the run's renderer, backend, device, vendor and driver
    // Per repetition: the tuned run's figure over the paper's, from the same interleaved run.
    Spread mean_ratio;
    Spread p95_ratio;
    double tuned_mean_ms = 0.0, paper_mean_ms = 0.0;  // medians over repetitions
    double tuned_queries = 0.0, paper_queries = 0.0;  // per frame
    double tuned_objects = 0.0, paper_objects = 0.0;  // drawn per frame
    // Over every frame of every repetition (docs/error.md): error pixels, tie pixels (another
    // object at the same depth: no error) and objects ground truth saw that were not drawn.
    int64_t tuned_error_pixels = 0, paper_error_pixels = 0;
    int64_t tuned_tie_pixels = 0, paper_tie_pixels = 0;
    int64_t tuned_missed_objects = 0, paper_missed_objects = 0;
    // The tuned and the paper's values issued as many queries and drew as many objects on every
    // frame of every repetition: the same decisions, so any difference in time is noise.
    bool same_decisions = false;
    // The two settings were the same: the same options and the same cost model (Setting).
    bool same_setting = false;
};

// What the confirmation says of the tuned values as a whole, for the console and the exit status.
struct Verdict {
    enum class Kind { Accepted, NoChange, Rejected };
    Kind kind = Kind::Accepted;
    std::string reason;  // one line
    // "accepted", "no change", "REJECTED"
    const char* name() const;
    // tuned.json, or tuned.rejected.json for a result its own confirmation rejects.
    const char* fileName() const {
        return kind == Kind::Rejected ? "tuned.rejected.json" : "tuned.json";
    }
};

// How many times the noise of a median ratio two settings that must time the same may stand apart
// before the confirmation says the machine could not decide.
inline constexpr double kUndecidedNoises = 3.0;

// Rejected when any variant shows more error pixels or missed objects with the tuned setting, is
// slower in every one of at least two repetitions, or has a median ratio above 1 beyond the
// noise; "no change", the machine could not decide, when a variant whose two settings must take
// the same time (the same setting, or the same decisions) timed them apart by more than
// kUndecidedNoises times the noise of its median (and at least 2 %); "no change" when the two
// settings were the same (ConfirmationRow::same_setting), made
// the same decisions on every variant, or when any variant's median ratio is not below 1 beyond
// the noise; accepted only when every variant (the fitted frames and the held-out ones) is
// faster beyond it. The noise of a variant's median ratio is run_noise * sqrt(2 / repetitions),
// run_noise being the session's measured noise of one run's mean frame time (a relative standard
// deviation, SampleLog::referenceNoise()). `reference` names the reference in the reason: "the
// paper's values" or "the defaults" (referenceName()).
Verdict judgeConfirmation(const std::vector<ConfirmationRow>& rows, double run_noise,
                          const std::string& reference = "the paper's values");

// `reference` first, then `tuned`: the same order as every sampling batch.
ConfirmationRow confirm(const Scenario& scenario, const CullerRow& algorithm,
                        const std::string& variant, const Setting& tuned, const Setting& reference,
                        uint32_t repetitions, SessionRuns& session,
                        const std::function<void(const FrameEvent&)>& on_frame);

Spread spreadOf(std::vector<double> values);

}  // namespace occsim::tune
