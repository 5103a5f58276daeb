#include "tune/session_files.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "sim/output/atomic_file.h"
#include "tune/charts.h"
#include "tune/confirmation_file.h"
#include "tune/report.h"

namespace occsim::tune {
namespace {

std::string costModelJson(const FrameTimeModelFit& f) {
    const FrameTimeModel& m = f.model;
    const nlohmann::json j = {
        {"model",
         "frame_ms = constant_ms + query_ms*queries + kilotriangle_ms*triangles/1000 + "
         "draw_ms*objects_drawn + "
         "wait_factor*wait_ms"},
        {"constant_ms", m.constant_ms},
        {"query_ms", m.query_ms},
        {"triangle_ms", m.triangleMs()},
        {"kilotriangle_ms", m.kilotriangle_ms},
        {"draw_ms", m.draw_call_ms},
        {"wait_factor", m.wait_factor},
        {"frames", f.frames},
        {"runs", f.groups},
        {"residual_rms_ms", f.residual_rms_ms},
        {"heldout_rms_ms",
         std::isnan(f.heldout_rms_ms) ? nlohmann::json(nullptr) : nlohmann::json(f.heldout_rms_ms)},
        {"ceres", f.fit.ceres_summary}};
    return j.dump(2) + "\n";
}

}  // namespace

PlotResult writeSessionFiles(TuneSession& session) {
    TuneResult& r = session.result;
    const std::filesystem::path& out_dir = session.out_dir;
    writeFileAtomically(out_dir / "cost_model.json", costModelJson(r.cost));
    r.files.push_back("cost_model.json");
    const PlotResult charts =
        writeTuneCharts({r.space, r.samples, r.objective, r.references, r.reference_objective,
                         objectiveName(r.options->objective), r.response, r.tuned_unit,
                         r.kept_at_paper, r.cost.model, r.log->runs()},
                        out_dir);
    r.charts_message = charts.message;
    r.files.insert(r.files.end(), charts.files.begin(), charts.files.end());
    writeFileAtomically(out_dir / "report.md", reportMarkdown(r));
    writeFileAtomically(out_dir / "confirmation.json", confirmationJson(r));
    r.files.push_back("confirmation.json");
    std::filesystem::remove(out_dir / (r.verdict.kind == Verdict::Kind::Rejected
                                           ? "tuned.json"
                                           : "tuned.rejected.json"));
    writeFileAtomically(out_dir / r.verdict.fileName(), session.tuned_file.text);
    return charts;
}

}  // namespace occsim::tune
