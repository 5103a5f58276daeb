#include "sim/output/moments.h"

#include <algorithm>
#include <cstdio>

#include "sim/output/atomic_file.h"
#include "sim/output/console_table.h"
#include "sim/output/fixed_text.h"
#include "sim/output/report.h"
#include "sim/run/segment_summaries.h"

namespace occsim {
namespace {

std::string frameRange(uint32_t first, uint32_t end) {
    return first + 1 == end ? "frame " + std::to_string(first)
                            : "frames " + std::to_string(first) + " to " + std::to_string(end - 1);
}

std::string secondsRange(uint32_t first, uint32_t end, double dt) {
    return fixed(first * dt, 3) + " to " + fixed(end * dt, 3) + " s";
}

// "ideal", or "vfc (ideal did not run)": what the windows were measured against.
std::string referenceWords(const BenchResult& result) {
    for (const RunRecord& r : result.runs) {
        if (r.summary.label == result.window_reference && r.algorithm && !r.algorithm->oracle)
            return result.window_reference + " (no oracle ran)";
    }
    return result.window_reference;
}

bool anyWindow(const BenchResult& result) {
    return std::any_of(result.runs.begin(), result.runs.end(),
                       [](const RunRecord& r) { return !r.worst_windows.empty(); });
}

}  // namespace

std::string segmentHeading(const Segment& s, const RunMetadata& m) {
    const uint32_t warm = s.first_frame < m.warmup_frames
                              ? std::min(s.end_frame, m.warmup_frames) - s.first_frame
                              : 0;
    std::string h = s.name + ": " + frameRange(s.first_frame, s.end_frame) + ", " +
                    secondsRange(s.first_frame, s.end_frame, m.dt_s) + " (" +
                    std::to_string(s.frames()) + " frames, " + std::to_string(s.frames() - warm) +
                    " timed";
    if (warm > 0) h += "; " + std::to_string(warm) + " warm-up, not timed";
    h += ")";
    if (s.origin == "--segments") h += ", from --segments";
    if (!s.note.empty()) h += "; " + s.note;
    return h;
}

std::string segmentTablesText(const BenchResult& result, bool wide) {
    std::string out;
    for (size_t k = 0; k < result.metadata.segments.size(); ++k) {
        out += "\nsegment " + segmentHeading(result.metadata.segments[k], result.metadata) + "\n";
        const std::vector<RunRecord> runs = segmentRuns(result, k);
        out += wide ? formatComparisonTable(runs) : formatCompactTable(runs);
    }
    return out;
}

std::string describeWindow(const WorstWindow& w, const std::string& reference, double dt) {
    std::string text = frameRange(w.first_frame, w.first_frame + w.frames) + " (" +
                       secondsRange(w.first_frame, w.first_frame + w.frames, dt) +
                       "): " + fixed(w.ratio, 2) + "x " + reference + " (" +
                       fixed(w.frame_ms_mean, 2) + " / " + fixed(w.reference_frame_ms_mean, 2) +
                       " ms per frame); objects " + fixed(w.objects_mean, 1) + " / " +
                       fixed(w.reference_objects_mean, 1) + ", triangles " +
                       fixed(w.triangles_mean, 0) + " / " + fixed(w.reference_triangles_mean, 0) +
                       " per frame; " + fixed(w.queries_mean, 1) + " queries, " +
                       fixed(w.wait_ms_mean, 3) + " ms waiting per frame";
    if (w.error_pixels >= 0) {
        text += "; " + std::to_string(w.error_pixels) + " error px, " +
                std::to_string(w.missed_objects) + " missed";
    }
    const double worst =
        w.worst_reference_frame_ms > 0 ? w.worst_frame_ms / w.worst_reference_frame_ms : 0.0;
    return text + "; worst frame " + std::to_string(w.worst_frame) + " (" + fixed(worst, 2) + "x)";
}

std::string worstWindowsText(const BenchResult& result, bool wide) {
    if (result.window_reference.empty() || !anyWindow(result)) return "";
    const std::string reference = referenceWords(result);
    std::string out =
        wide ? "\nworst windows against " + reference + " (" + std::to_string(kWorstWindowFrames) +
                   " timed frames, the highest frame time over the reference's; report.md "
                   "lists up to " +
                   std::to_string(kWorstWindowsPerConfiguration) + " per configuration):\n"
             : "\nworst windows against " + reference + " (" + std::to_string(kWorstWindowFrames) +
                   " timed frames; up to " + std::to_string(kWorstWindowsPerConfiguration) +
                   " a configuration in report.md):\n(ratio of times; ms and objects a frame, "
                   "this / the reference's; the frame that lost most)\n";
    size_t width = 0;
    for (const RunRecord& r : result.runs) {
        if (!r.worst_windows.empty()) width = std::max(width, r.summary.label.size());
    }
    for (const RunRecord& r : result.runs) {
        if (r.worst_windows.empty()) continue;
        const WorstWindow& w = r.worst_windows.front();
        out += "  " + r.summary.label + std::string(width - r.summary.label.size(), ' ') + "  " +
               (wide ? describeWindow(w, result.window_reference, result.metadata.dt_s)
                     : describeWindowBriefly(w)) +
               "\n";
    }
    return out;
}

std::string describeWindowBriefly(const WorstWindow& w) {
    std::string text = "frames " + std::to_string(w.first_frame) + "-" +
                       std::to_string(w.first_frame + w.frames - 1) + ": " + fixed(w.ratio, 2) +
                       "x, " + fixed(w.frame_ms_mean, 1) + " / " +
                       fixed(w.reference_frame_ms_mean, 1) + " ms, " + fixed(w.objects_mean, 0) +
                       " / " + fixed(w.reference_objects_mean, 0) + " objects";
    if (w.error_pixels > 0 || w.missed_objects > 0) {
        text += ", " + std::to_string(w.error_pixels) + " error px, " +
                std::to_string(w.missed_objects) + " missed";
    }
    const double worst =
        w.worst_reference_frame_ms > 0 ? w.worst_frame_ms / w.worst_reference_frame_ms : 0.0;
    return text + ", worst frame " + std::to_string(w.worst_frame) + " (" + fixed(worst, 2) + "x)";
}

nlohmann::json segmentsJson(const BenchResult& result) {
    nlohmann::json list = nlohmann::json::array();
    const RunMetadata& m = result.metadata;
    for (size_t k = 0; k < m.segments.size(); ++k) {
        const Segment& s = m.segments[k];
        const std::vector<RunRecord> runs = segmentRuns(result, k);
        nlohmann::json algorithms = nlohmann::json::array();
        for (const RunRecord& r : runs) {
            nlohmann::json j = configurationJson(r, runs);
            // What the configuration ran with is the whole run's: see "algorithms".
            for (const char* key : {"options", "approximation", "cost_model"}) j.erase(key);
            algorithms.push_back(j);
        }
        list.push_back({{"name", s.name},
                        {"first_frame", s.first_frame},
                        {"last_frame", s.end_frame - 1},
                        {"frames", s.frames()},
                        {"from_s", s.first_frame * m.dt_s},
                        {"to_s", s.end_frame * m.dt_s},
                        {"origin", s.origin},
                        {"note", s.note},
                        {"algorithms", algorithms}});
    }
    return list;
}

nlohmann::json worstWindowsJson(const BenchResult& result) {
    if (result.window_reference.empty()) return nullptr;
    nlohmann::json configurations = nlohmann::json::array();
    const double dt = result.metadata.dt_s;
    for (const RunRecord& r : result.runs) {
        if (r.worst_windows.empty()) continue;
        nlohmann::json windows = nlohmann::json::array();
        for (const WorstWindow& w : r.worst_windows) {
            windows.push_back(
                {{"first_frame", w.first_frame},
                 {"last_frame", w.first_frame + w.frames - 1},
                 {"from_s", w.first_frame * dt},
                 {"to_s", (w.first_frame + w.frames) * dt},
                 {"ratio", w.ratio},
                 {"frame_ms_mean", w.frame_ms_mean},
                 {"reference_frame_ms_mean", w.reference_frame_ms_mean},
                 {"objects_per_frame", w.objects_mean},
                 {"reference_objects_per_frame", w.reference_objects_mean},
                 {"triangles_per_frame", w.triangles_mean},
                 {"reference_triangles_per_frame", w.reference_triangles_mean},
                 {"queries_per_frame", w.queries_mean},
                 {"wait_ms_per_frame", w.wait_ms_mean},
                 {"error_pixels",
                  w.error_pixels >= 0 ? nlohmann::json(w.error_pixels) : nlohmann::json(nullptr)},
                 {"missed_objects", w.missed_objects >= 0 ? nlohmann::json(w.missed_objects)
                                                          : nlohmann::json(nullptr)},
                 {"worst_frame", w.worst_frame},
                 {"worst_frame_ms", w.worst_frame_ms},
                 {"worst_reference_frame_ms", w.worst_reference_frame_ms}});
        }
        configurations.push_back({{"configuration", r.summary.label}, {"windows", windows}});
    }
    return {{"reference", result.window_reference},
            {"window_frames", kWorstWindowFrames},
            {"configurations", configurations}};
}

std::string windowPictureName(const std::string& configuration, uint32_t frame) {
    char number[16];
    std::snprintf(number, sizeof number, "%05u", frame);
    return "worst-window-" + safeFileName(configuration) + "-frame-" + number + ".png";
}

}  // namespace occsim
