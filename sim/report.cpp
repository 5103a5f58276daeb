#include "sim/report.h"

#include <cstdio>
#include <sstream>

namespace occsim {
namespace {

const RunSummary* find(const std::vector<RunRecord>& runs, const std::string& algorithm) {
    for (const RunRecord& r : runs) {
        if (r.summary.algorithm == algorithm) return &r.summary;
    }
    return nullptr;
}

std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

}  // namespace

double speedupOverVfc(const std::vector<RunRecord>& runs, const RunSummary& s) {
    const RunSummary* vfc = find(runs, "vfc");
    return vfc && s.frame_ms.mean > 0 ? vfc->frame_ms.mean / s.frame_ms.mean : 0.0;
}

double ratioToIdeal(const std::vector<RunRecord>& runs, const RunSummary& s) {
    const RunSummary* ideal = find(runs, "ideal");
    return ideal && ideal->frame_ms.mean > 0 ? s.frame_ms.mean / ideal->frame_ms.mean : 0.0;
}

std::string formatComparisonTable(const std::vector<RunRecord>& runs) {
    const std::vector<std::string> header = {"algorithm",  "mean ms",   "median ms", "p95 ms",
                                             "queries/fr", "wait ms/fr", "tris/fr",  "objs/fr",
                                             "err px",     "worst px",  "speedup",   "vs ideal"};
    std::vector<std::vector<std::string>> rows;
    for (const RunRecord& r : runs) {
        const RunSummary& s = r.summary;
        const double speedup = speedupOverVfc(runs, s), ideal = ratioToIdeal(runs, s);
        rows.push_back({s.algorithm, fixed(s.frame_ms.mean, 2), fixed(s.frame_ms.median, 2),
                        fixed(s.frame_ms.p95, 2), fixed(s.queries_mean, 1), fixed(s.wait_ms_mean, 3),
                        fixed(s.triangles_mean, 0), fixed(s.objects_mean, 1),
                        s.error_measured ? std::to_string(s.error_pixels_total) : "-",
                        s.error_measured ? std::to_string(s.error_pixels_worst) : "-",
                        speedup > 0 ? fixed(speedup, 2) + "x" : "-",
                        ideal > 0 ? fixed(ideal, 2) + "x" : "-"});
    }
    std::vector<size_t> width(header.size());
    for (size_t c = 0; c < header.size(); ++c) {
        width[c] = header[c].size();
        for (const auto& row : rows) width[c] = std::max(width[c], row[c].size());
    }
    std::ostringstream out;
    auto line = [&](const std::vector<std::string>& cells) {
        for (size_t c = 0; c < cells.size(); ++c) {
            const std::string pad(width[c] - cells[c].size(), ' ');
            out << (c == 0 ? cells[c] + pad : pad + cells[c]) << (c + 1 < cells.size() ? "  " : "\n");
        }
    };
    line(header);
    for (const auto& row : rows) line(row);
    return out.str();
}

std::string framesCsv(const std::vector<RunRecord>& runs) {
    std::ostringstream out;
    out << "algorithm,frame,time_s,frame_ms,cull_cpu_ms,wait_ms,update_ms,queries,objects_drawn,"
           "triangles,moved_objects,node_changes,error_pixels,missed_objects,visible_objects\n";
    for (const RunRecord& r : runs) {
        for (const FrameStats& f : r.frames) {
            out << r.summary.algorithm << ',' << f.frame << ',' << fixed(f.time_s, 6) << ','
                << fixed(f.frame_ms, 4) << ',' << fixed(f.cull_cpu_ms, 4) << ','
                << fixed(f.wait_ms, 4) << ',' << fixed(f.update_ms, 4) << ',' << f.queries << ','
                << f.objects_drawn << ',' << f.triangles << ',' << f.moved_objects << ','
                << f.node_changes << ',' << f.error_pixels << ',' << f.missed_objects << ','
                << f.visible_objects << '\n';
        }
    }
    return out.str();
}

nlohmann::json summaryJson(const std::vector<RunRecord>& runs) {
    nlohmann::json algorithms = nlohmann::json::array();
    for (const RunRecord& r : runs) {
        const RunSummary& s = r.summary;
        nlohmann::json j = {
            {"algorithm", s.algorithm},
            {"frames", s.frames},
            {"timed_frames", s.timed_frames},
            {"frame_ms", {{"mean", s.frame_ms.mean}, {"median", s.frame_ms.median},
                          {"p95", s.frame_ms.p95}, {"min", s.frame_ms.min}, {"max", s.frame_ms.max}}},
            {"cull_cpu_ms_mean", s.cull_cpu_ms_mean},
            {"wait_ms_mean", s.wait_ms_mean},
            {"update_ms_mean", s.update_ms_mean},
            {"queries_per_frame", s.queries_mean},
            {"objects_per_frame", s.objects_mean},
            {"triangles_per_frame", s.triangles_mean},
        };
        if (s.error_measured) {
            j["error"] = {{"pixels_total", s.error_pixels_total},
                          {"pixels_worst_frame", s.error_pixels_worst},
                          {"worst_frame", s.error_worst_frame},
                          {"frames_with_error", s.frames_with_error},
                          {"missed_objects_total", s.missed_objects_total}};
        }
        if (const double v = speedupOverVfc(runs, s); v > 0) j["speedup_over_vfc"] = v;
        if (const double v = ratioToIdeal(runs, s); v > 0) j["ratio_to_ideal"] = v;
        algorithms.push_back(j);
    }
    return {{"algorithms", algorithms}};
}

}  // namespace occsim
