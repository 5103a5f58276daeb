#include "sim/output/report.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "sim/output/console_table.h"
#include "sim/output/fixed_text.h"
#include "sim/output/moments.h"
#include "sim/output/version.h"
#include "sim/run/stop_request.h"
#include "sim/scenario/option_json.h"

namespace occsim {
namespace {}  // namespace

ComparisonTable comparisonTable(const std::vector<RunRecord>& runs) {
    bool error = false, repeated = false;
    for (const RunRecord& r : runs) {
        error |= r.summary.error_measured;
        repeated |= r.summary.repetitions > 1;
    }
    std::vector<std::string> header = {"configuration", repeated ? "mean ms [min-max]" : "mean ms",
                                       "median ms",     "p95 ms",
                                       "gpu ms",        "queries/fr",
                                       "wait ms/fr",    "answer lat p50/p95",
                                       "tris/fr",       "objs/fr"};
    // Submitted and executed apart where a culler draws under conditions the device decides.
    bool conditional = false;
    for (const RunRecord& r : runs)
        conditional |= r.algorithm && (r.algorithm->device_needs & kConditionalRendering) != 0;
    if (conditional) {
        header.push_back("exec tris/fr");
        header.push_back("exec objs/fr");
    }
    if (error) {
        for (const char* h : {"err px/fr", "p99 px", "worst px", "err px", "tie px", "missed",
                              "pop max", "overdrawn/fr", "overdrawn tris/fr"}) {
            header.push_back(h);
        }
    }
    for (const char* h : {"speedup", "vs ideal"}) header.push_back(h);
    if (error) header.push_back("pareto");

    const bool nothing_in_view = nothingInView(runs);
    // Every figure through fixedNonZero: 1 error pixel in 240 frames reads "<0.1", never 0.0.
    std::vector<std::vector<std::string>> rows;
    for (const RunRecord& r : runs) {
        const RunSummary& s = r.summary;
        const double speedup = speedupOverReference(runs, s), ideal = ratioToOracle(runs, s);
        std::string mean = fixedNonZero(s.frame_ms.mean, 2);
        if (repeated)
            mean += " [" + fixedNonZero(s.frame_ms_mean_min, 2) + "-" +
                    fixedNonZero(s.frame_ms_mean_max, 2) + "]";
        // GPU time only where it was measured: never on a software rasteriser, whose timer
        // queries do not time rasterisation (see the console's backend line).
        const std::string gpu = s.gpu_ms_mean >= 0 ? fixedNonZero(s.gpu_ms_mean, 2) : "n/a";
        const std::string latency = s.answer_latency_median >= 0
                                        ? fixedNonZero(s.answer_latency_median, 0) + "/" +
                                              fixedNonZero(s.answer_latency_p95, 0)
                                        : "-";
        std::vector<std::string> row = {s.label,
                                        mean,
                                        fixedNonZero(s.frame_ms.median, 2),
                                        fixedNonZero(s.frame_ms.p95, 2),
                                        gpu,
                                        fixedNonZero(s.queries_mean, 1),
                                        fixedNonZero(s.wait_ms_mean, 3),
                                        latency,
                                        fixedNonZero(s.triangles_mean, 0),
                                        fixedNonZero(s.objects_mean, 1)};
        if (conditional) {
            row.push_back(fixedNonZero(s.executed_triangles_mean, 0));
            row.push_back(fixedNonZero(s.executed_objects_mean, 1));
        }
        // Every frame was warm-up: there is no figure to show, and 0.00 would read as measured.
        if (s.timed_frames == 0) std::fill(row.begin() + 1, row.end(), "not timed");
        if (error) {
            row.push_back(fixedNonZero(s.error_pixels_mean, 1));
            row.push_back(fixedNonZero(s.error_pixels_p99, 0));
            row.push_back(std::to_string(s.error_pixels_worst));
            row.push_back(std::to_string(s.error_pixels_total));
            row.push_back(std::to_string(s.tie_pixels_total));
            row.push_back(std::to_string(s.missed_objects_total));
            row.push_back(std::to_string(s.popping_max_frames));
            row.push_back(fixedNonZero(s.overdrawn_objects_mean, 1));
            row.push_back(fixedNonZero(s.overdrawn_triangles_mean, 0));
        }
        // Ratios of empty frames mean nothing: n/a, and the headline says why.
        const std::string none = nothing_in_view ? "n/a" : "-";
        row.push_back(speedup > 0 ? fixed(speedup, 2) + "x" : none);
        row.push_back(ideal > 0 ? fixed(ideal, 2) + "x" : none);
        if (error) row.push_back(r.pareto ? "*" : "");
        rows.push_back(row);
    }
    return {header, rows};
}

std::string formatComparisonTable(const std::vector<RunRecord>& runs) {
    const ComparisonTable table = comparisonTable(runs);
    std::vector<std::vector<std::string>> lines = {table.header};
    lines.insert(lines.end(), table.rows.begin(), table.rows.end());
    return alignColumns(lines, {0});
}

std::string framesCsv(const std::vector<RunRecord>& runs) {
    std::ostringstream out;
    out << "configuration,repetition,frame,time_s,frame_ms,cull_cpu_ms,wait_ms,update_ms,queries,"
           "objects_drawn,triangles,moved_objects,node_changes,error_pixels,tie_pixels,"
           "missed_objects,tied_away_objects,visible_objects,gpu_ms,answers,answer_latency_"
           "median,stray_pixels,overdrawn_objects,overdrawn_triangles,executed_objects,"
           "executed_triangles,phase1_cpu_ms,test_cpu_ms,phase2_cpu_ms,phase1_gpu_ms,test_gpu_ms,"
           "phase2_gpu_ms,read_backs,shadow_cpu_ms,shadow_gpu_ms,shading_cpu_ms,shading_gpu_ms,"
           "shadow_casters,shadow_triangles,"
           "shadow_error_pixels,missed_casters,shadow_seen_casters,shadow_tie_pixels,shadow_"
           "queries,left_error_pixels,right_error_pixels\n";
    for (const RunRecord& r : runs) {
        for (size_t rep = 0; rep <= r.later_repetitions.size(); ++rep) {
            const auto& frames = rep == 0 ? r.frames : r.later_repetitions[rep - 1];
            for (const FrameStats& f : frames) {
                out << r.summary.label << ',' << rep << ',' << f.frame << ',' << fixed(f.time_s, 6)
                    << ',' << fixed(f.frame_ms, 4) << ',' << fixed(f.cull_cpu_ms, 4) << ','
                    << fixed(f.wait_ms, 4) << ',' << fixed(f.update_ms, 4) << ',' << f.queries
                    << ',' << f.objects_drawn << ',' << f.triangles << ',' << f.moved_objects << ','
                    << f.node_changes << ',' << f.error_pixels << ',' << f.tie_pixels << ','
                    << f.missed_objects << ',' << f.tied_away_objects << ',' << f.visible_objects
                    << ','
                    // Empty where not measured (gpu_ms on a software rasteriser; no answers).
                    << (f.gpu_ms >= 0 ? fixed(f.gpu_ms, 4) : "") << ',' << f.answers << ','
                    << (f.answer_latency_median >= 0 ? fixed(f.answer_latency_median, 1) : "")
                    << ',' << f.stray_pixels << ',' << f.overdrawn_objects << ','
                    << f.overdrawn_triangles << ',' << f.executed_objects << ','
                    << f.executed_triangles;
                // GPU-driven cullers' phases; empty for the others (never the last column: a
                // row ends in a number, which naive CSV splitters keep).
                for (const auto* phases : {&f.phase_cpu_ms, &f.phase_gpu_ms}) {
                    for (const double ms : *phases) out << ',' << (ms >= 0 ? fixed(ms, 4) : "");
                }
                out << ',' << f.read_backs;
                // The shadow pass: times empty, counts -1 on a frame without one.
                for (const double ms :
                     {f.shadow_cpu_ms, f.shadow_gpu_ms, f.shading_cpu_ms, f.shading_gpu_ms}) {
                    out << ',' << (ms >= 0 ? fixed(ms, 4) : "");
                }
                out << ',' << f.shadow_casters << ',' << f.shadow_triangles << ','
                    << f.shadow_error_pixels << ',' << f.missed_casters << ','
                    << f.shadow_seen_casters << ',' << f.shadow_tie_pixels << ','
                    << f.shadow_queries << ',' << f.left_error_pixels << ',' << f.right_error_pixels
                    << '\n';
            }
        }
    }
    return out.str();
}

namespace {

nlohmann::json phasesJson(const RunSummary& s) {
    if (s.phase_cpu_ms_mean[0] < 0) return nullptr;
    nlohmann::json j;
    const char* names[3] = {"phase1", "test", "phase2"};
    for (size_t p = 0; p < 3; ++p) {
        j[names[p]] = {{"cpu_ms", s.phase_cpu_ms_mean[p]}, {"gpu_ms", s.phase_gpu_ms_mean[p]}};
    }
    return j;
}

// The shadow pass over the timed frames (docs/views.md); null without one.
nlohmann::json shadowJson(const RunSummary& s) {
    if (s.shadow_casters_mean < 0) return nullptr;
    nlohmann::json j = {
        {"casters_per_frame", s.shadow_casters_mean},
        {"queries_per_frame", s.shadow_queries_mean},
        {"cpu_ms_mean", s.shadow_cpu_ms_mean},
        {"gpu_ms_mean", s.shadow_gpu_ms_mean >= 0 ? nlohmann::json(s.shadow_gpu_ms_mean)
                                                  : nlohmann::json(nullptr)}};
    // Receiver-masked caster culling's shading pass, when it ran.
    if (s.shading_cpu_ms_mean >= 0) {
        j["shading_pass"] = {
            {"cpu_ms_mean", s.shading_cpu_ms_mean},
            {"gpu_ms_mean", s.shading_gpu_ms_mean >= 0 ? nlohmann::json(s.shading_gpu_ms_mean)
                                                       : nlohmann::json(nullptr)}};
    }
    if (s.shadow_error_pixels_total >= 0) {
        j["error_pixels_total"] = s.shadow_error_pixels_total;
        j["missed_casters_total"] = s.missed_casters_total;
        j["seen_casters_per_frame"] = s.shadow_seen_casters_mean;
        j["tie_pixels_total"] = s.shadow_tie_pixels_total;
    }
    return j;
}

// Milliseconds per query box, per triangle and per draw call, as culling.cost_model names them.
nlohmann::json costModelJson(const CostModel& cost) {
    return {{"query_box_ms", cost.query_box_ms},
            {"triangle_ms", cost.triangle_ms},
            {"draw_call_ms", cost.draw_call_ms}};
}

// Error against ground truth over a configuration's frames (docs/error.md).
nlohmann::json errorJson(const RunSummary& s) {
    return {{"pixels_total", s.error_pixels_total},
            {"pixels_worst_frame", s.error_pixels_worst},
            {"worst_frame", s.error_worst_frame},
            {"frames_with_error", s.frames_with_error},
            {"pixels_per_frame_mean", s.error_pixels_mean},
            {"pixels_per_frame_p99", s.error_pixels_p99},
            {"tie_pixels_total", s.tie_pixels_total},
            {"tie_pixels_per_frame_mean", s.tie_pixels_mean},
            {"frames_with_ties", s.frames_with_ties},
            {"stray_pixels_total", s.stray_pixels_total},
            {"missed_objects_total", s.missed_objects_total},
            {"tied_away_objects_total", s.tied_away_objects_total},
            {"overdrawn_objects_per_frame_mean", s.overdrawn_objects_mean},
            {"overdrawn_triangles_per_frame_mean", s.overdrawn_triangles_mean},
            {"popping_events", s.popping_events},
            {"popping_mean_frames", s.popping_mean_frames},
            {"popping_max_frames", s.popping_max_frames}};
}

}  // namespace

nlohmann::json configurationJson(const RunRecord& r, const std::vector<RunRecord>& runs) {
    const RunSummary& s = r.summary;
    nlohmann::json j = {
        {"configuration", s.label},
        {"algorithm", r.algorithm ? std::string(r.algorithm->name) : s.label},
        {"repetitions", s.repetitions},
        {"frame_ms_mean_over_repetitions",
         {{"median", s.frame_ms.mean}, {"min", s.frame_ms_mean_min}, {"max", s.frame_ms_mean_max}}},
        {"frames", s.frames},
        {"timed_frames", s.timed_frames},
        {"frame_ms",
         {{"mean", s.frame_ms.mean},
          {"median", s.frame_ms.median},
          {"p95", s.frame_ms.p95},
          {"min", s.frame_ms.min},
          {"max", s.frame_ms.max}}},
        {"cull_cpu_ms_mean", s.cull_cpu_ms_mean},
        {"wait_ms_mean", s.wait_ms_mean},
        {"update_ms_mean", s.update_ms_mean},
        {"queries_per_frame", s.queries_mean},
        {"objects_per_frame", s.objects_mean},
        {"triangles_per_frame", s.triangles_mean},
        // Of the draws submitted, those the device executed (conditional draws it skipped are
        // not); equal to the submitted counts for every culler that draws no conditional draw.
        {"executed_objects_per_frame", s.executed_objects_mean},
        {"executed_triangles_per_frame", s.executed_triangles_mean},
        {"read_backs_per_frame", s.read_backs_mean},
        // GPU-driven cullers (hzb, raster): mean ms of phase 1, the test and phase 2, submitted on
        // the CPU and timed on the GPU (a software rasteriser's "GPU" time is its threads' CPU
        // time: machine.gpu_time_meaningful); null for the other cullers.
        {"gpu_driven_phases", phasesJson(s)},
        // The shadow pass, with its error when error is measured; null without one.
        {"shadow_pass", shadowJson(s)},
        // null where not measured: see machine.gpu_time_meaningful.
        {"gpu_ms", s.gpu_ms_mean >= 0
                       ? nlohmann::json{{"mean", s.gpu_ms_mean}, {"p95", s.gpu_ms_p95}}
                       : nlohmann::json(nullptr)},
        {"answer_latency_commands", s.answer_latency_median >= 0
                                        ? nlohmann::json{{"answers", s.answers},
                                                         {"median", s.answer_latency_median},
                                                         {"p95", s.answer_latency_p95}}
                                        : nlohmann::json(nullptr)},
    };
    if (s.error_measured) {
        j["error"] = errorJson(s);
        j["pareto"] = r.pareto;
    }
    // Every option of the culler as it ran: what a reader needs to rerun the configuration.
    j["options"] = nlohmann::json(optionValuesJson(r.options));
    j["approximation"] = {{"threshold_pixels", r.approximation.threshold_pixels},
                          {"stale_results", r.approximation.stale_results}};
    if (!r.culling_file.empty()) j["culling_file"] = r.culling_file;
    if (r.cost_model) j["cost_model"] = costModelJson(*r.cost_model);
    if (const double v = speedupOverReference(runs, s); v > 0) j["speedup_over_vfc"] = v;
    if (const double v = ratioToOracle(runs, s); v > 0) j["ratio_to_ideal"] = v;
    return j;
}

namespace {

nlohmann::json scenarioJson(const RunMetadata& m) {
    nlohmann::json j = {{"name", m.scenario_name}, {"file", m.scenario_file},
                        {"frames", m.frames},      {"warmup_frames", m.warmup_frames},
                        {"dt_s", m.dt_s},          {"seed", m.seed},
                        {"objects", m.objects},    {"triangles", m.triangles},
                        {"movers", m.movers}};
    // Stereo: null without; the eyes' separation and how they were culled.
    j["stereo"] = nullptr;
    if (m.stereo) {
        j["stereo"] = {
            {"eye_separation_m", m.stereo->eye_separation_m},
            {"culling", m.stereo->culling == StereoCulling::PerEye ? "per_eye" : "enclosing"}};
    }
    if (!m.scenario_id.empty()) j["id"] = m.scenario_id;  // what merge and history file it under
    return j;
}

nlohmann::json machineJson(const RunMetadata& m) {
    return {{"hardware_threads", m.hardware_threads},
            {"load_average_before", m.load_before},
            {"load_average_after", m.load_after},
            {"busy", m.busyMachine()},
            {"llvmpipe_threads", m.lp_num_threads},
            {"freed_memory", m.heap},
            {"renderer", m.renderer},
            {"backend", m.backend},
            {"device", m.device ? nlohmann::json(*m.device) : nlohmann::json(nullptr)},
            {"gl_vendor", m.gl_vendor},
            {"gl_renderer", m.gl_renderer},
            {"gl_version", m.gl_version},
            {"driver", m.driver},
            {"gpu_time_meaningful", m.gpu_time_meaningful},
            {"contexts_apart", m.contexts_apart},
            {"resolution", std::to_string(m.width) + "x" + std::to_string(m.height)}};
}

// What the simulator itself spent, beside the frame time it measured.
nlohmann::json simulatorCostsJson(const RunCosts& c) {
    return {{"wall_ms_after_setup", c.wall_ms},
            {"frame_ms_total", c.frame_ms_total},
            {"wall_over_frame_time", c.frame_ms_total > 0 ? c.wall_ms / c.frame_ms_total : 0.0},
            {"world_advances", c.world_advances},
            {"world_steps", c.world_steps},
            {"world_update_ms_total", c.world_update_ms_total},
            {"ground_truth_renders", c.ground_truth_renders},
            {"ground_truth_ms_total", c.ground_truth_ms_total},
            {"error_read_backs", c.error_read_backs},
            {"window_frames_replayed", c.window_frames_replayed},
            {"window_replay_ms", c.window_replay_ms},
            {"occluder_meshes_tried", c.occluder_meshes_tried},
            {"occluder_meshes_made", c.occluder_meshes_made},
            {"occluder_meshes_ms", c.occluder_meshes_ms}};
}

// null for a complete run; else why it ended early, how far it got, and the console's line.
nlohmann::json partialJson(const BenchResult& result) {
    if (!result.partial) return nullptr;
    const PartialRun& p = *result.partial;
    return {{"reason", p.reason},
            {"signal", p.signal != 0 ? nlohmann::json(signalName(p.signal)) : nullptr},
            {"repetition", p.repetition},
            {"frames_reached", p.frames_reached},
            {"message", partialLine(result)}};
}

}  // namespace

nlohmann::json summaryJson(const BenchResult& result) {
    const std::vector<RunRecord>& runs = result.runs;
    nlohmann::json algorithms = nlohmann::json::array();
    for (const RunRecord& r : runs) algorithms.push_back(configurationJson(r, runs));
    const RunMetadata& m = result.metadata;
    nlohmann::json summary = {{"algorithms", algorithms}};
    summary["scenario"] = scenarioJson(m);
    summary["machine"] = machineJson(m);
    summary["command"] = m.command_line;
    summary["occsim"] = {{"version", occsimVersion()}, {"commit", occsimCommit()}};
    summary["nothing_in_view"] =
        nothingInView(runs);  // true: no speedup is given, none means anything
    summary["repetitions"] = m.repetitions;
    summary["frame_order"] = m.frame_order;
    // How each figure joins the repetitions (aggregateRepetitions), so no reader takes a sum for
    // a median or the other way round.
    summary["aggregation"] = {
        {"timings",
         "median over repetitions (frame_ms, cull_cpu_ms_mean, wait_ms_mean, "
         "update_ms_mean, gpu_ms, answer latency); frame_ms_mean_over_repetitions "
         "gives the spread"},
        {"per_frame_counts", "median over repetitions (queries, objects, triangles per frame)"},
        {"error_counts",
         "sum over every repetition's frames (error.pixels_total, "
         "missed_objects_total, frames_with_error, tie, stray and popping counts); "
         "per-frame error means over those frames; worst frame, p99 and longest "
         "popping run the worst repetition's"},
        {"pareto", m.repetitions > 1 ? "times whose spreads over repetitions overlap tie"
                                     : "one repetition: times compared by their means"}};
    summary["error_measured"] = m.error_measured;
    if (m.error_measured) {
        // What decides error against tie (docs/error.md), so a reader of the file knows.
        summary["error_definition"] = {{"depth_format", m.depth_format},
                                       {"tie_tolerance_depth_steps", kDepthTieSteps}};
    }
    summary["deterministic_latency"] = m.deterministic_latency
                                           ? nlohmann::json(*m.deterministic_latency)
                                           : nlohmann::json(nullptr);
    if (!m.backend_fallback.empty()) summary["machine"]["backend_fallback"] = m.backend_fallback;
    if (m.sweep)
        summary["sweep"] = {{"parameter", m.sweep->parameter}, {"values", m.sweep->values}};
    summary["simulator_costs"] = simulatorCostsJson(result.costs);
    summary["partial"] = partialJson(result);
    summary["segments"] = segmentsJson(result);
    summary["worst_windows"] = worstWindowsJson(result);
    if (m.cost_model) {
        summary["cost_model"] = costModelJson(*m.cost_model);
        summary["cost_model"]["source"] = m.cost_model_source;
    }
    return summary;
}

std::string costsLine(const BenchResult& result) {
    const RunCosts& c = result.costs;
    std::string line = "simulator: " + fixed(c.wall_ms, 1) + " ms wall clock after set-up for " +
                       fixed(c.frame_ms_total, 1) + " ms of frame time";
    if (c.frame_ms_total > 0) line += " (" + fixed(c.wall_ms / c.frame_ms_total, 2) + "x)";
    line += "; world update " + fixed(c.world_update_ms_total, 1) + " ms over " +
            std::to_string(c.world_advances) + " frames, once per frame for " +
            std::to_string(result.runs.size()) +
            (result.runs.size() == 1 ? " configuration" : " configurations");
    if (c.ground_truth_renders == 0) {
        line += "; no ground truth rendered";
    } else {
        line += "; ground truth " + std::to_string(c.ground_truth_renders) + " renders, " +
                fixed(c.ground_truth_ms_total, 1) +
                " ms (render and read-back, outside the frame timing)";
    }
    if (c.occluder_meshes_tried > 0) {
        line += "; inscribed occluder meshes " + std::to_string(c.occluder_meshes_made) + " of " +
                std::to_string(c.occluder_meshes_tried) + " made, " +
                fixed(c.occluder_meshes_ms, 1) + " ms (before the first frame, outside its timing)";
    }
    return line;
}

std::string aggregationLine(const BenchResult& result) {
    const RunMetadata& m = result.metadata;
    if (m.repetitions > 1) {
        const std::string n = std::to_string(m.repetitions);
        return "repetitions: " + n +
               "; times and per-frame counts are medians over them, error counts (err px, tie "
               "px, missed) sums over all " +
               n + (m.error_measured ? ", pareto with their spread (overlapping times tie)" : "");
    }
    if (m.error_measured && result.runs.size() > 2) {
        return "pareto: from one repetition, times within the run-to-run spread are not told "
               "apart (--repetitions 3 measures the spread)";
    }
    return "";
}

std::string busyMachineLine(const RunMetadata& m) {
    if (!m.busyMachine()) return "";
    // What was seen: the reading over its bound (the run's own threads count in the one after).
    char seen[160];
    if (m.load_before[0] > m.hardware_threads) {
        std::snprintf(seen, sizeof seen,
                      "load average %.2f before it, above its %u hardware threads",
                      m.load_before[0], m.hardware_threads);
    } else {
        std::snprintf(seen, sizeof seen,
                      "load average %.2f after it, above twice its %u hardware threads",
                      m.load_after[0], m.hardware_threads);
    }
    std::string line = std::string("busy machine: other work ran beside this run (") + seen +
                       "); these timings are not results: rerun when nothing else runs (a build "
                       "just ended counts: wait a minute)";
    if (!m.command_line.empty()) line += ": " + m.command_line;
    return line;
}

namespace {

// The configurations that rendered in a GL context of their own, and why (one line).
std::string contextsApartLine(const std::vector<std::string>& labels) {
    std::string names;
    for (size_t i = 0; i < labels.size(); ++i) names += (i ? ", " : "") + labels[i];
    return "own GL context: " + names +
           " (conditional rendering slows what renders after it on llvmpipe: "
           "docs/conditional.md)";
}

}  // namespace

std::string runHeadline(const BenchResult& result) {
    const RunMetadata& m = result.metadata;
    const uint32_t timed = result.runs.empty() ? 0 : result.runs.front().summary.timed_frames;
    // A stopped run counts the frames it reports (those of its first repetition).
    const uint32_t frames = result.partial && result.partial->repetition == 0
                                ? result.partial->frames_reached
                                : m.frames;
    char line[512];
    std::snprintf(line, sizeof line, "%s: %u frames (%u timed after %u warm-up), %s",
                  m.scenario_name.c_str(), frames, timed, frames - timed, m.renderer.c_str());
    std::string headline = line;
    if (result.partial) headline += "\n" + partialLine(result);
    char load[256];
    std::snprintf(load, sizeof load,
                  "\nmachine: %u hardware threads, load average %.2f before the run, %.2f after",
                  m.hardware_threads, m.load_before[0], m.load_after[0]);
    headline += load;
    if (m.busyMachine()) headline += "\n" + busyMachineLine(m);
    headline += "\nbackend: " + backendLabel(m) + ", vendor " + m.gl_vendor + ", driver " +
                m.driver +
                (m.gpu_time_meaningful ? "" : " (software rasteriser: gpu ms not meaningful)");
    if (!m.backend_fallback.empty())
        headline += "\nbackend auto fell back to OSMesa: " + m.backend_fallback;
    if (!m.occluder_roles.empty()) headline += "\noccluders: " + m.occluder_roles;
    if (!m.contexts_apart.empty()) headline += "\n" + contextsApartLine(m.contexts_apart);
    if (nothingInView(result.runs)) {
        headline +=
            "\nwarning: the camera sees no object on any frame (none drawn, none visible): "
            "speedups are n/a; aim the camera at the scene";
    }
    if (timed == 0) {
        headline += "\nnothing was timed: all " + std::to_string(m.frames) +
                    " frames are warm-up (the scenario's warmup_frames); run more frames than that "
                    "to measure time";
    }
    return headline;
}

}  // namespace occsim
