#include "sim/output/markdown_report.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "sim/output/fixed_text.h"
#include "sim/output/moments.h"
#include "sim/output/report.h"
#include "sim/run/segment_summaries.h"

namespace occsim {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A caption for a plot file from its stem (plots.h names them).
std::string plotCaption(const std::string& file) {
    if (file.find("frame-time") != std::string::npos) return "Frame time per frame";
    if (file.find("time-vs-error") != std::string::npos) return "Time against error";
    if (file.find("queries-triangles") != std::string::npos)
        return "Queries and triangles per frame";
    return file;
}

void header(std::ostringstream& out, const BenchResult& result) {
    const RunMetadata& c = result.metadata;
    out << "# occsim " << c.command << ": " << c.scenario_name << "\n\n";
    if (result.partial) out << "**" << partialLine(result) << ".**\n\n";
    out << "| | |\n|---|---|\n";
    out << "| scenario | " << markdownCell(c.scenario_name) << " (`"
        << markdownCell(c.scenario_file) << "`), " << c.frames << " frames at " << c.width << "x"
        << c.height << " pixels |\n";
    char load[96];
    std::snprintf(load, sizeof load, ", load average %.2f before the run and %.2f after",
                  c.load_before[0], c.load_after[0]);
    out << "| machine | " << c.hardware_threads
        << " hardware threads, LP_NUM_THREADS=" << markdownCell(c.lp_num_threads)
        << ", freed memory " << markdownCell(c.heap) << ", renderer " << markdownCell(c.renderer)
        << load
        << (c.busyMachine() ? " (**busy: other work ran beside this run; timings are not results**)"
                            : "")
        << " |\n";
    out << "| backend | " << markdownCell(backendLabel(c)) << ": vendor "
        << markdownCell(c.gl_vendor) << ", renderer " << markdownCell(c.gl_renderer) << ", driver "
        << markdownCell(c.driver)
        << (c.gpu_time_meaningful ? "" : " (software rasteriser: GPU time not meaningful)")
        << (c.backend_fallback.empty()
                ? ""
                : "; auto fell back to OSMesa: " + markdownCell(c.backend_fallback))
        << " |\n";
    out << "| configurations | " << result.runs.size() << ", each run " << c.repetitions
        << (c.repetitions == 1 ? " time"
                               : " times (times and per-frame counts are medians over them; "
                                 "error counts sums over every repetition)")
        << " |\n";
    if (c.sweep) {
        out << "| sweep | " << markdownCell(c.sweep->parameter) << " =";
        for (size_t i = 0; i < c.sweep->values.size(); ++i) {
            char v[32];
            std::snprintf(v, sizeof v, "%g", c.sweep->values[i]);
            out << (i ? ", " : " ") << v;
        }
        out << " |\n";
    }
    out << "| query latency | "
        << (c.deterministic_latency
                ? "deterministic: a result is ready after " +
                      std::to_string(*c.deterministic_latency) + " later draw calls"
                : std::string("as the hardware reports it"))
        << " |\n";
    out << "| image error | "
        << (c.error_measured
                ? "measured against a ground-truth render of every frame (object IDs and depth, " +
                      c.depth_format + "; a tie is within " + std::to_string(kDepthTieSteps) +
                      " depth step)"
                : std::string("not measured (run with `--error`)"))
        << " |\n\n";
    out << "Command:\n\n```sh\n" << c.command_line << "\n```\n\n";
    const uint32_t timed = c.frames > c.warmup_frames ? c.frames - c.warmup_frames : 0;
    out << "The first " << c.warmup_frames << " frames are warm-up and are excluded from every "
        << "timing figure (" << timed << " frames timed); error and popping count all frames. "
        << "Ground-truth rendering, PNG writing and statistics I/O (CSV, JSON, this report, the "
        << "plots and the bird's-eye pictures) happen outside all timing.\n\n";
    out << costsLine(result) << ".\n\n";
}

// The comparison table of `runs` (the whole run's, or a segment's) as a Markdown table.
bool markdownTable(std::ostringstream& out, const std::vector<RunRecord>& runs) {
    const ComparisonTable t = comparisonTable(runs);
    const bool has_pareto = !t.header.empty() && t.header.back() == "pareto";
    if (nothingInView(runs)) {
        out << "**Warning:** the camera sees no object on any frame (none drawn, none visible): "
               "the speedups are n/a.\n\n";
    }
    out << "|";
    for (const std::string& h : t.header) out << ' ' << markdownCell(h) << " |";
    out << "\n|";
    for (size_t i = 0; i < t.header.size(); ++i) out << (i == 0 ? "---|" : "---:|");
    out << "\n";
    for (const auto& row : t.rows) {
        const bool pareto = has_pareto && row.back() == "*";
        out << "|";
        for (size_t i = 0; i < row.size(); ++i) {
            std::string v = markdownCell(row[i]);
            if (i == 0 && pareto) v = "**" + v + "**";
            if (has_pareto && i + 1 == row.size()) v = pareto ? "yes" : "";
            out << ' ' << v << " |";
        }
        out << "\n";
    }
    out << "\n";
    return has_pareto;
}

void table(std::ostringstream& out, const BenchResult& result) {
    out << "## Comparison\n\n";
    const bool has_pareto = markdownTable(out, result.runs);
    if (has_pareto) {
        out << "Configurations marked **yes** under `pareto` (and in bold) are on the "
            << "time-against-error Pareto front: no other configuration is both faster and at "
            << "most as wrong. The Ideal oracle is the bound, not a candidate.\n\n";
    }
}

// Every figure of the table again over each segment's frames.
void segments(std::ostringstream& out, const BenchResult& result) {
    const RunMetadata& m = result.metadata;
    if (m.segments.empty()) return;
    out << "## Segments\n\n"
        << "Each table is the comparison table over one segment's frames only: timing over its "
        << "frames after the warm-up (a segment inside the warm-up is not timed), error and "
        << "popping over all its frames, speedup and ratio to Ideal from the same frames.\n\n";
    for (size_t k = 0; k < m.segments.size(); ++k) {
        out << "### " << markdownCell(segmentHeading(m.segments[k], m)) << "\n\n";
        markdownTable(out, segmentRuns(result, k));
    }
}

// Each configuration's worst windows against the reference, with the picture of the worst frame
// of each where one was taken.
void worstWindows(std::ostringstream& out, const BenchResult& result, const ReportFiles& files) {
    bool any = false;
    for (const RunRecord& r : result.runs) any |= !r.worst_windows.empty();
    if (!any) return;
    const bool oracle = std::any_of(result.runs.begin(), result.runs.end(), [&](const auto& r) {
        return r.summary.label == result.window_reference && r.algorithm && r.algorithm->oracle;
    });
    out << "## Worst windows\n\n"
        << "Per configuration, the windows of " << kWorstWindowFrames
        << " consecutive timed frames where its frame time over " << result.window_reference
        << "'s was highest (up to " << kWorstWindowsPerConfiguration << ", none overlapping, worst "
        << "first; with repetitions each frame's figures are its medians over them)"
        << (oracle ? "" : ": no oracle ran, so against the speedup reference") << ". "
        << "Objects and triangles are per frame, the configuration's / " << result.window_reference
        << "'s.";
    if (!files.window_pictures.empty()) {
        out << " The picture under a window is its worst frame, the world replayed to it after the "
               "run and drawn whole (what the camera saw), with what the configuration did wrong "
               "on it in its first repetition: objects it missed tinted red with red boxes, "
               "objects it drew while ground truth saw none of them as yellow boxes.";
    }
    out << "\n\n";
    for (const RunRecord& r : result.runs) {
        if (r.worst_windows.empty()) continue;
        out << "### " << markdownCell(r.summary.label) << "\n\n";
        for (const WorstWindow& w : r.worst_windows) {
            out << "- "
                << markdownCell(describeWindow(w, result.window_reference, result.metadata.dt_s))
                << "\n";
            const std::string picture = windowPictureName(r.summary.label, w.worst_frame);
            const auto& taken = files.window_pictures;
            if (std::find(taken.begin(), taken.end(), picture) != taken.end())
                out << "\n  ![" << picture << "](" << picture << ")\n\n";
        }
        out << "\n";
    }
}

void pictures(std::ostringstream& out, const ReportFiles& c) {
    std::vector<std::string> pngs;
    for (const std::string& f : c.plot_files) {
        if (endsWith(f, ".png")) pngs.push_back(f);
    }
    if (!pngs.empty() || !c.plots_note.empty()) out << "## Plots\n\n";
    for (const std::string& f : pngs) {
        std::string svg = f.substr(0, f.size() - 4) + ".svg";
        const bool has_svg =
            std::find(c.plot_files.begin(), c.plot_files.end(), svg) != c.plot_files.end();
        out << "![" << plotCaption(f) << "](" << f << ")\n";
        if (has_svg)
            out << "\n("
                << "[SVG](" << svg << "))\n";
        out << "\n";
    }
    if (!c.plots_note.empty()) out << c.plots_note << "\n\n";
    if (c.birds_eye_files.empty()) return;
    out << "## Bird's-eye view\n\n"
        << "The scene from above: objects drawn this frame in yellow, the others grey (large ones, "
        << "such as a floor, outlined over a faint tint so that they hide nothing); BSP node "
        << "bounds outlined red where the view frustum culled them, blue where an occlusion query "
        << "culled them, green where they were drawn after a visible query, magenta where their "
        << "objects were drawn without a query, dim blue below an occluded node (never reached), "
        << "dim teal where the traversal passed through; the camera as a white dot with its view "
        << "wedge.\n\n";
    for (const std::string& f : c.birds_eye_files) out << "![" << f << "](" << f << ")\n\n";
}

void howToRead(std::ostringstream& out) {
    out << "## How to read this\n\n"
        << "Frame times are wall clock from frame start to `glFinish`, culled render only. "
        << "**gpu ms** is the GPU's own time for that render (a `GL_TIME_ELAPSED` query), shown "
        << "only where it means something: on a software rasteriser such as llvmpipe it reads "
        << "n/a, since its timer queries do not time rasterisation. **answer lat p50/p95** is how "
        << "many commands (draws and queries) had been submitted after a query by the time its "
        << "answer was ready, median and 95th percentile over every answer of the timed frames: "
        << "what decides how long a culler waits, comparable between a GPU and llvmpipe. "
        << "**speedup** is VFC's mean frame time over the configuration's (above 1x: faster than "
        << "frustum culling alone); **vs ideal** is the configuration's mean frame time over the "
        << "Ideal oracle's, which draws exactly the objects ground truth sees with no queries "
        << "(1x is the bound; the nearer, the better). **err px/fr** is the mean number of error "
        << "pixels per frame: pixels where ground truth shows a surface nearer than the culled "
           "frame "
        << "does (background counts as infinitely far), so something visible was left out (0 for "
        << "conservative culling); **p99 px** and **worst px** are its tail and **err px** its "
        << "total. **tie px** counts pixels where another object lies at the same depth (within "
           "one "
        << "step of the depth buffer) and the draw order decided which one the pixel shows: the "
           "same "
        << "surface, no error. **missed** counts, over the frames, objects ground truth saw that "
           "the "
        << "culler did not draw. **overdrawn/fr** and **overdrawn tris/fr** are over-draw: the "
        << "objects (and their triangles) the culler drew per frame that ground truth does not see "
        << "at all, the work culling was there to save. **pop max** is the longest run of "
           "consecutive frames one visible "
        << "object stayed missing (not drawn): short runs flicker (popping), long ones are holes. "
        << "In the time-against-error plot, down and to the left is better: a configuration that "
           "buys "
        << "time with error sits left of and above the conservative ones, and the Pareto line "
        << "joins those that no other configuration beats in both.\n";
}

}  // namespace

std::string markdownReport(const BenchResult& result, const ReportFiles& files) {
    std::ostringstream out;
    header(out, result);
    table(out, result);
    segments(out, result);
    worstWindows(out, result, files);
    out << files.extra_markdown;
    if (files.objects) out << objectHighlightsMarkdown(*files.objects);
    pictures(out, files);
    howToRead(out);
    return out.str();
}

}  // namespace occsim
