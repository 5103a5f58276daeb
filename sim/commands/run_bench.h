// `occsim run` and `occsim bench`: one culler, or several interleaved over the same frames, over a
// scenario; the table on stdout, the run folder (frames.csv, summary.json, report.md, pictures,
// plots) published as a whole at the end.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/commands/shared_flags.h"

namespace occsim_cli {

// The flags run and bench share.
struct CommonFlags {
    BackendFlags backend;
    std::string scenario;
    uint32_t repetitions = 1;
    std::string sweep;
    bool error = false;
    std::string out;
    uint32_t frames = 0;
    std::vector<uint32_t> capture;
    int deterministic_latency = -1;
    bool plots = false;
    int64_t birds_eye = -1;
    std::string culling;
    bool out_given = false;  // --out on the command line (an empty one is refused)
    bool wait_lock = false;
    std::vector<std::string> plugins;
    std::string ablate;
    std::vector<std::string> record;         // --record: "objects"
    std::vector<std::string> segments;       // --segments, each as given (joined by ',')
    bool quiet = false;                      // no progress on stderr
    bool wide = false;                       // --wide: the full table instead of the compact one
    std::string frame_order = "balanced";    // --frame-order (bench)
    std::string sun;                         // --sun ELEVATION,AZIMUTH[,SHADOW_MAP]
    bool sun_given = false;                  // --sun on the command line (an empty one is refused)
    std::string stereo;                      // --stereo SEPARATION[,MODE]
    bool stereo_given = false;               // --stereo on the command line
    std::string shadow_casters = "frustum";  // --shadow-casters frustum|receivers
};

struct RunFlags {
    CommonFlags common;
    std::string algorithm;
};

struct BenchFlags {
    CommonFlags common;
    std::vector<std::string> algorithms;  // split here, not by CLI11: it drops empty names
    bool algorithms_given = false;        // --algos on the command line
};

CLI::App* addRun(CLI::App& app, RunFlags& flags);
CLI::App* addBench(CLI::App& app, BenchFlags& flags);

// The command run; `command_line` as typed (summary.json records it). Returns the exit code.
int runCommand(const RunFlags& flags, const std::string& command_line);
int benchCommand(const BenchFlags& flags, const std::string& command_line);

}  // namespace occsim_cli
