#include "tune/confirm.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tune/measure.h"

namespace occsim::tune {
namespace {

std::string fixedText(double v, int digits) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

}  // namespace

Spread spreadOf(std::vector<double> v) {
    if (v.empty()) return {};
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    return {median, v.front(), v.back()};
}

const char* Verdict::name() const {
    switch (kind) {
        case Kind::Accepted:
            return "accepted";
        case Kind::NoChange:
            return "no change";
        case Kind::Rejected:
            return "REJECTED";
    }
    return "";
}

Verdict judgeConfirmation(const std::vector<ConfirmationRow>& rows, double run_noise,
                          const std::string& reference) {
    for (const ConfirmationRow& r : rows) {
        if (r.tuned_error_pixels > r.paper_error_pixels) {
            return {Verdict::Kind::Rejected, r.variant +
                                                 ": the tuned setting showed more error pixels "
                                                 "than " +
                                                 reference};
        }
        if (r.tuned_missed_objects > r.paper_missed_objects) {
            return {Verdict::Kind::Rejected,
                    r.variant + ": the tuned setting missed more objects than " + reference};
        }
    }
    auto all = [&](bool ConfirmationRow::*flag) {
        return !rows.empty() && std::all_of(rows.begin(), rows.end(),
                                            [&](const ConfirmationRow& r) { return r.*flag; });
    };
    // A gain is a median ratio below 1 by more than the noise of that median: each repetition's
    // ratio is of two runs (log noise s * sqrt(2)), and the median of R of them about that over
    // sqrt(R) (docs/tuning.md "The verdict").
    auto margin = [&](const ConfirmationRow& r) {
        return run_noise * std::sqrt(2.0 / std::max<double>(1.0, r.repetitions));
    };
    // Two settings that must take the same time (the same setting, or the same decisions on every
    // frame) timed apart by more than kUndecidedNoises times that noise (and 2 %): the machine's
    // timing moved under the session, and no verdict on time can stand. tuned.json holds the
    // reference, and the reason says why.
    for (const ConfirmationRow& r : rows) {
        if (!r.same_setting && !r.same_decisions) continue;
        const double apart = std::abs(std::log(r.mean_ratio.median));
        const double allowed = std::max(kUndecidedNoises * margin(r), std::log(1.02));
        if (apart > allowed) {
            return {Verdict::Kind::NoChange,
                    "the machine could not decide: " + r.variant + " timed " +
                        (r.same_setting ? "the same setting"
                                        : "two settings making the same "
                                          "decisions") +
                        " at " + fixedText(r.tuned_mean_ms, 2) + " and " +
                        fixedText(r.paper_mean_ms, 2) + " ms (median ratio " +
                        fixedText(r.mean_ratio.median, 3) + "), beyond the " +
                        fixedText(100.0 * (std::exp(allowed) - 1.0), 1) +
                        " % its noise allows; rerun on a quiet machine: tuned.json holds " +
                        reference};
        }
    }
    if (all(&ConfirmationRow::same_setting)) {
        return {Verdict::Kind::NoChange, "every parameter kept at " + reference +
                                             " and no cost model applied: tuned.json holds " +
                                             reference};
    }
    if (all(&ConfirmationRow::same_decisions)) {
        return {Verdict::Kind::NoChange,
                "the tuned setting made the same decisions as " + reference +
                    " on every confirmation frame (their difference in time is noise): "
                    "tuned.json holds " +
                    reference};
    }
    for (const ConfirmationRow& r : rows) {
        if (r.repetitions >= 2 && r.mean_ratio.min > 1.0) {
            return {Verdict::Kind::Rejected, r.variant + ": slower in every repetition"};
        }
        if (std::log(r.mean_ratio.median) > margin(r)) {
            return {Verdict::Kind::Rejected, r.variant +
                                                 ": slower beyond the noise (median ratio " +
                                                 fixedText(r.mean_ratio.median, 3) + ", noise " +
                                                 fixedText(100.0 * margin(r), 1) + " %)"};
        }
    }
    for (const ConfirmationRow& r : rows) {
        if (r.same_decisions) {
            return {Verdict::Kind::NoChange,
                    r.variant + ": the same decisions as " + reference +
                        " on every frame, so no gain there: tuned.json holds " + reference};
        }
        if (std::log(r.mean_ratio.median) >= -margin(r)) {
            return {Verdict::Kind::NoChange, r.variant + ": not faster than " + reference +
                                                 " beyond the noise (median ratio " +
                                                 fixedText(r.mean_ratio.median, 3) + ", noise " +
                                                 fixedText(100.0 * margin(r), 1) +
                                                 " %): tuned.json holds " + reference};
        }
    }
    return {Verdict::Kind::Accepted,
            "faster than " + reference + " beyond the noise on every variant, no more error"};
}

ConfirmationRow confirm(const Scenario& scenario, const CullerRow& algorithm,
                        const std::string& variant, const Setting& tuned, const Setting& reference,
                        uint32_t repetitions, SessionRuns& session,
                        const std::function<void(const FrameEvent&)>& on_frame) {
    // The reference first: the same order as every sampling batch.
    const BenchResult result =
        runInterleaved(scenario, algorithm, {reference, tuned}, repetitions, session, on_frame);
    const occsim::RunRecord& p = result.runs[0];
    const occsim::RunRecord& t = result.runs[1];

    ConfirmationRow row;
    row.variant = variant;
    row.seed = scenario.seed;
    row.frames = result.metadata.frames;
    // Where it rendered, as occsim's console names it: tuned values carry over only to the same
    // kind of renderer (docs/headless-gpu.md).
    row.renderer = result.metadata.renderer + " through " + backendLabel(result.metadata) +
                   " (vendor " + result.metadata.gl_vendor + ", driver " + result.metadata.driver +
                   ")";
    row.repetitions = static_cast<uint32_t>(t.repetitions.size());
    std::vector<double> mean_ratios, p95_ratios;
    for (size_t r = 0; r < t.repetitions.size(); ++r) {
        mean_ratios.push_back(t.repetitions[r].frame_ms.mean / p.repetitions[r].frame_ms.mean);
        p95_ratios.push_back(t.repetitions[r].frame_ms.p95 / p.repetitions[r].frame_ms.p95);
        row.tuned_error_pixels += t.repetitions[r].error_pixels_total;
        row.paper_error_pixels += p.repetitions[r].error_pixels_total;
        row.tuned_tie_pixels += t.repetitions[r].tie_pixels_total;
        row.paper_tie_pixels += p.repetitions[r].tie_pixels_total;
        row.tuned_missed_objects += t.repetitions[r].missed_objects_total;
        row.paper_missed_objects += p.repetitions[r].missed_objects_total;
    }
    auto sameDecisions = [](const std::vector<FrameStats>& a, const std::vector<FrameStats>& b) {
        if (a.size() != b.size()) return false;
        for (size_t f = 0; f < a.size(); ++f) {
            if (a[f].queries != b[f].queries || a[f].objects_drawn != b[f].objects_drawn)
                return false;
        }
        return true;
    };
    row.same_decisions = sameDecisions(t.frames, p.frames) &&
                         t.later_repetitions.size() == p.later_repetitions.size();
    for (size_t r = 0; row.same_decisions && r < t.later_repetitions.size(); ++r) {
        row.same_decisions = sameDecisions(t.later_repetitions[r], p.later_repetitions[r]);
    }
    row.same_setting = tuned.sameSettingAs(reference);
    row.mean_ratio = spreadOf(mean_ratios);
    row.p95_ratio = spreadOf(p95_ratios);
    row.tuned_mean_ms = t.summary.frame_ms.mean;
    row.paper_mean_ms = p.summary.frame_ms.mean;
    row.tuned_queries = t.summary.queries_mean;
    row.paper_queries = p.summary.queries_mean;
    row.tuned_objects = t.summary.objects_mean;
    row.paper_objects = p.summary.objects_mean;
    return row;
}

}  // namespace occsim::tune
