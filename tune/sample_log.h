// The sample log: one JSON line per measured run, rewritten whole (atomically) after every batch,
// so that an interrupted session leaves every finished batch and nothing half written, and
// `occtune --resume` continues from it.
//
// Line 1 holds the settings the samples were measured under; --resume refuses a log whose
// settings differ from the command's (other parameters, bounds, frames, design seed, or a changed
// scenario file). Each further line is one run of one batch: one of the batch's references (the
// paper's values, run twice per batch) or a sample, with its timing figures and the figures of
// every timed frame (for the cost model).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tune/frame_time_model.h"
#include "tune/parameters.h"

namespace occsim::tune {

struct LogSettings {
    std::string scenario_file;
    std::string scenario_name;
    uint64_t scenario_hash = 0;  // of the scenario file's text: a changed file is another scenario
    std::string algorithm = "statistical";  // the tuned culler
    std::vector<std::string> parameters;
    std::vector<Bounds> bounds;
    uint32_t frames = 0;
    uint32_t warmup_frames = 0;
    uint64_t seed = 0;             // of the space-filling design
    uint32_t initial_samples = 0;  // the space-filling design's size
};

struct LoggedRun {
    uint32_t batch = 0;
    bool reference = false;
    std::vector<double> values;  // the tuned parameters' values (the reference: the paper's)
    double mean_ms = 0.0;        // over the timed frames
    double p95_ms = 0.0;
    int64_t error_pixels = 0;         // over all frames
    std::vector<FrameCounts> frames;  // the timed frames
};

// A sample with its ratios to the references of its batch (their mean figure).
struct Sample {
    const LoggedRun* run = nullptr;
    double ratio_mean = 0.0;
    double ratio_p95 = 0.0;
};

class SampleLog {
  public:
    // A new log (nothing written until the first batch).
    SampleLog(std::filesystem::path file, LogSettings settings);
    // Reads an existing log. Throws TuneInputError naming the file and line when it is not one.
    static SampleLog read(const std::filesystem::path& file);

    const std::filesystem::path& file() const { return file_; }
    const LogSettings& settings() const { return settings_; }
    const std::vector<LoggedRun>& runs() const { return runs_; }
    uint32_t batches() const;
    // The samples (not the references) in the order measured.
    std::vector<Sample> samples() const;
    // The reference runs, each as a ratio to its batch's references: observations at the paper's
    // values, about 1, that anchor the response model there.
    std::vector<Sample> referenceSamples() const;

    // The spread of one run's figure when nothing differs: per batch with two references, the
    // ratio of the second to the first; 0 when no batch has two.
    double referenceNoise() const;

    // Appends a batch (its references and samples) and rewrites the file atomically.
    void appendBatch(const std::vector<LoggedRun>& batch);

    // An empty string when `other` may continue this log, else what differs (one line).
    std::string mismatch(const LogSettings& other) const;

  private:
    std::filesystem::path file_;
    LogSettings settings_;
    std::vector<LoggedRun> runs_;
    std::string text_;  // the file's contents
};

// FNV-1a, 64 bits: a fingerprint of a scenario file's text.
uint64_t textHash(const std::string& text);

}  // namespace occsim::tune
