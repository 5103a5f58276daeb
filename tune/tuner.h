// occtune's whole session: check the input (before any run), sample (a space-filling design,
// then where the fitted response is uncertain or promising; every batch interleaved with the
// paper's values in one run), fit the cost and response models (Ceres), choose, and confirm on the
// fitted frames and on a variant the fit never saw. docs/tuning.md explains the method.
// The session keeps its sample log (samples.jsonl, so that it can resume) and prints its progress
// line; what it found is returned, and the command line (tune/main.cpp) prints it and writes
// tuned.json, the report and charts (tune/session_files.h).
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "tune/options.h"
#include "tune/result.h"
#include "tune/tuned_file.h"

namespace occsim::tune {

// How a session ended, and what the command line needs to say so and to write its files.
struct TuneSession {
    enum class End { Finished, FitFailed, Interrupted };
    End end = End::Finished;

    // Interrupted (Ctrl-C): while sampling or during the confirmation; the log is whole.
    bool interrupted_confirming = false;
    size_t samples_logged = 0;
    std::filesystem::path log_file;

    // FitFailed: which model ("cost" or "response") did not converge, and Ceres' summary.
    std::string failed_model;
    std::string ceres_summary;

    // Finished: the result, the folder its files go to, and tuned.json's text (its verdict in
    // result.verdict). The result's samples point into the log, which the session keeps.
    std::filesystem::path out_dir;
    std::unique_ptr<const SampleLog> log;
    TuneResult result;
    TunedFile tuned_file;

    // kExitDone (tuned.json; its verdict accepted or "no change"), kExitRejected (the
    // confirmation rejected the values: tuned.rejected.json, no tuned.json), kExitFitFailed (a
    // fit did not converge: no tuned.json) or kExitInterrupted (the sample log is whole; no
    // tuned.json).
    int exitCode() const;
};

// Runs a session. Throws TuneInputError, ScenarioError or GltfError for bad input, before any
// run; std::runtime_error for failures while running.
TuneSession runTuner(const TuneOptions& options);

}  // namespace occsim::tune
