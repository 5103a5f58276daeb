#include "sim/output/run_outputs.h"

#include "sim/output/atomic_file.h"
#include "sim/output/markdown_report.h"
#include "sim/output/moments.h"
#include "sim/output/plots.h"
#include "sim/output/report.h"

namespace occsim {

OutputFiles writeRunOutputs(const BenchResult& result, const OutputRequest& request) {
    OutputFiles out;
    std::filesystem::create_directories(request.out_dir);
    writeFileAtomically(request.out_dir / "frames.csv", framesCsv(result.runs));
    writeFileAtomically(request.out_dir / "summary.json", summaryJson(result).dump(2) + "\n");
    out.files = {"frames.csv", "summary.json"};

    ReportFiles report;
    report.birds_eye_files = request.birds_eye_files;
    // The worst windows' pictures the run took (PictureRecorder::onWindowFrame), by their names.
    for (const RunRecord& r : result.runs) {
        for (const WorstWindow& w : r.worst_windows) {
            const std::string name = windowPictureName(r.summary.label, w.worst_frame);
            if (std::filesystem::exists(request.out_dir / name))
                report.window_pictures.push_back(name);
        }
    }
    report.extra_markdown = request.extra_markdown;
    report.objects = request.objects;
    if (request.plots) {
        const PlotResult plots = writePlots(result.runs, request.out_dir);
        report.plot_files = plots.files;
        report.plots_note = plots.message;
        out.plots_message = plots.message;
        out.files.insert(out.files.end(), plots.files.begin(), plots.files.end());
    }
    writeFileAtomically(request.out_dir / "report.md", markdownReport(result, report));
    out.files.push_back("report.md");
    return out;
}

}  // namespace occsim
