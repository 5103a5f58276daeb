// The checks of one regression run (docs/regression.md), each a CheckResult in the scenario's
// outcome: its expectations (zero error, error bounds, frame-time ratios) and its baseline file,
// compared or, with --update, rewritten. A failed error check takes a picture of the worst error
// frame into the scenario's output folder. Internal to the regress layer (regress.cpp).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/regress/regress.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim {

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

    // The worst error frame of `algorithm` as a picture, once.
    void capture(const std::string& algorithm);
};

// The scenario's segments on the frames a regression run runs (expect.frames cuts them).
std::vector<Segment> regressSegments(const Scenario& scenario, const Expectations& expect);

// Every check of the run, in the order the table lists them; `update` rewrites the baseline.
void checkRun(ResultChecks& checks, const Scenario& scenario, const Expectations& expect,
              bool update);

}  // namespace occsim
