#include "sim/output/plots.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include "sim/output/atomic_file.h"

extern char** environ;

namespace occsim {
namespace {

namespace fs = std::filesystem;

using Chart = GnuplotChart;

// A gnuplot double-quoted string.
std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// How configuration i looks in every chart: one colour per algorithm (the frustum-culling
// reference grey, the oracle black, so the references read alike in every report), and within an
// algorithm's sweep one dash type and point type per value, so that a family of configurations
// reads as one.
struct Style {
    std::string colour;
    int dash = 1;
    int point = 7;
};

std::vector<Style> stylesOf(const std::vector<RunRecord>& runs) {
    static const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                           "#8c564b", "#e377c2", "#17becf", "#bcbd22"};
    static const int kPoints[] = {7, 5, 9, 11, 13, 15};
    std::vector<const CullerRow*> algorithms;  // in order of first appearance
    std::vector<int> seen;                     // configurations so far per algorithm
    std::vector<Style> styles;
    size_t next_colour = 0;
    std::vector<std::string> colours;
    for (const RunRecord& r : runs) {
        auto it = std::find(algorithms.begin(), algorithms.end(), r.algorithm);
        if (it == algorithms.end()) {
            algorithms.push_back(r.algorithm);
            seen.push_back(0);
            const bool reference = r.algorithm && r.algorithm->speedup_reference;
            const bool oracle = r.algorithm && r.algorithm->oracle;
            colours.push_back(reference ? "#7f7f7f"
                              : oracle  ? "#000000"
                                        : kPalette[next_colour++ % std::size(kPalette)]);
            it = algorithms.end() - 1;
        }
        const size_t a = static_cast<size_t>(it - algorithms.begin());
        const int k = seen[a]++;
        styles.push_back({colours[a], k % 5 + 1, kPoints[k % std::size(kPoints)]});
    }
    return styles;
}

std::string lineStyle(const Style& s) {
    // Dotted and dash-dotted lines need more weight to read as well as solid ones.
    return "lc rgb '" + s.colour + "' dt " + std::to_string(s.dash) + " lw " +
           (s.dash >= 3 ? "2.2" : "1.6");
}

// One block per configuration (gnuplot `index i`): frame, frame ms, queries, triangles.
std::string framesData(const std::vector<RunRecord>& runs) {
    std::ostringstream out;
    for (size_t i = 0; i < runs.size(); ++i) {
        out << "# " << runs[i].summary.label << "\n# frame frame_ms queries triangles\n";
        for (const FrameStats& f : runs[i].frames) {
            out << f.frame << ' ' << num(f.frame_ms) << ' ' << f.queries << ' ' << f.triangles
                << '\n';
        }
        out << "\n\n";
    }
    return out.str();
}

std::string configsData(const std::vector<RunRecord>& runs) {
    std::ostringstream out;
    // Ties and missed objects beside the error the plot shows: a tie is no error (docs/error.md).
    out << "# configuration mean_frame_ms mean_error_pixels_per_frame pareto "
           "mean_tie_pixels_per_frame missed_objects\n";
    for (const RunRecord& r : runs) {
        out << quoted(r.summary.label) << ' ' << num(r.summary.frame_ms.mean) << ' '
            << num(r.summary.error_pixels_mean) << ' ' << (r.pareto ? 1 : 0) << ' '
            << num(r.summary.tie_pixels_mean) << ' ' << r.summary.missed_objects_total << '\n';
    }
    return out.str();
}

// The front's points in order of time, so that the line through them runs left to right.
std::string paretoData(const std::vector<RunRecord>& runs) {
    std::vector<const RunRecord*> front;
    for (const RunRecord& r : runs) {
        if (r.pareto) front.push_back(&r);
    }
    std::sort(front.begin(), front.end(), [](const RunRecord* a, const RunRecord* b) {
        return a->summary.frame_ms.mean < b->summary.frame_ms.mean;
    });
    std::ostringstream out;
    out << "# pareto front: configuration mean_frame_ms mean_error_pixels_per_frame "
           "mean_tie_pixels_per_frame missed_objects\n";
    for (const RunRecord* r : front) {
        out << quoted(r->summary.label) << ' ' << num(r->summary.frame_ms.mean) << ' '
            << num(r->summary.error_pixels_mean) << ' ' << num(r->summary.tie_pixels_mean) << ' '
            << r->summary.missed_objects_total << '\n';
    }
    return out.str();
}

// Fixed margins so that the key sits outside on the right and stacked panels line up.
const char* kMargins = "set lmargin at screen 0.08\nset rmargin at screen 0.74\n";

// Every configuration's column `y` (a gnuplot `using` expression) against the frame.
std::string perFramePlot(const std::vector<RunRecord>& runs, const std::string& y, bool key) {
    const std::vector<Style> styles = stylesOf(runs);
    std::ostringstream out;
    out << (key ? "set key outside right top Left reverse samplen 3\n" : "unset key\n");
    out << "plot ";
    for (size_t i = 0; i < runs.size(); ++i) {
        out << (i ? ", \\\n     " : "") << "'plot-frames.dat' index " << i << " using 1:" << y
            << " with lines " << lineStyle(styles[i]) << " title " << quoted(runs[i].summary.label);
    }
    out << "\n";
    return out.str();
}

// The warm-up frames (excluded from every timing figure) as a grey band.
std::string warmupBand(const std::vector<RunRecord>& runs) {
    const RunSummary& s = runs.front().summary;
    const uint32_t warmup = s.frames - s.timed_frames;
    if (warmup == 0) return "";
    return "set object 1 rect from -0.5, graph 0 to " + num(warmup - 0.5) +
           ", graph 1 fillcolor rgb '#e8e8e8' fillstyle solid 1.0 noborder behind\n"
           "set label 1 'warm-up' at " +
           num(0.5 * warmup - 0.5) + ", graph 0.96 center\n";
}

Chart frameTimeChart(const std::vector<RunRecord>& runs) {
    std::ostringstream b;
    b << "set title 'Frame time per frame (culled render to glFinish)'\n"
      << "set xlabel 'frame'\nset ylabel 'frame time (ms)'\nset grid\nset yrange [0:*]\n"
      << kMargins << warmupBand(runs) << perFramePlot(runs, "2", true);
    return {"plot-frame-time", 1100, 600, b.str()};
}

// One point per configuration, numbered on the chart and named in the key (long names would
// overlap where configurations crowd, typically at zero error); the front joins its points.
Chart timeErrorChart(const std::vector<RunRecord>& runs) {
    const std::vector<Style> styles = stylesOf(runs);
    std::ostringstream b;
    b << "set title 'Time against error (one point per configuration; lower left is better)'\n"
      << "set xlabel 'mean frame time (ms)'\nset ylabel 'mean error pixels per frame (ties are no "
         "error)'\n"
      << "set grid\nset key outside right top Left reverse samplen 1 spacing 1.1\n"
      << kMargins << "set xrange [0:*]\nset yrange [0:*]\n"
      << "set offsets graph 0, graph 0.08, graph 0.08, graph 0.02\n"
      << "plot 'plot-pareto.dat' using 2:3 with lines lw 2 lc rgb '#d62728' title 'Pareto front', "
         "\\\n"
      << "     'plot-pareto.dat' using 2:3 with points pt 6 ps 2.6 lw 1.5 lc rgb '#d62728' notitle";
    for (size_t i = 0; i < runs.size(); ++i) {
        b << ", \\\n     'plot-configs.dat' every ::" << i << "::" << i
          << " using 2:3 with points pt " << styles[i].point << " ps 1.4 lc rgb '"
          << styles[i].colour << "' title "
          << quoted(std::to_string(i + 1) + "  " + runs[i].summary.label);
    }
    b << ", \\\n     'plot-configs.dat' using 2:3:(sprintf('%d', $0 + 1)) with labels left "
         "offset char 0.7,0.7 font ',10' notitle\n";
    return {"plot-time-vs-error", 1100, 650, b.str()};
}

Chart queriesTrianglesChart(const std::vector<RunRecord>& runs) {
    std::ostringstream b;
    b << "set multiplot layout 2,1 title 'Queries and triangles per frame'\n"
      << kMargins << "set grid\nset xlabel 'frame'\n"
      << warmupBand(runs) << "set ylabel 'occlusion queries per frame'\nset yrange [0:*]\n"
      << perFramePlot(runs, "3", true) << "set ylabel 'triangles drawn per frame (thousands)'\n"
      << perFramePlot(runs, "($4 / 1000.0)", false) << "unset multiplot\n";
    return {"plot-queries-triangles", 1100, 850, b.str()};
}

std::string tempName(const std::string& file) {
    return "." + file + ".tmp-" + std::to_string(::getpid());
}

// Each chart twice: PNG (pngcairo where gnuplot has it) and SVG, to temporary names.
std::string script(const std::vector<Chart>& charts, const std::string& name) {
    std::ostringstream out;
    out << "# Written by occsim (sim/output/plots.cpp); run with: gnuplot " << name << "\n"
        << "# Outputs go to temporary names that occsim renames once gnuplot succeeded.\n"
        << "set encoding utf8\n"
        << "has_cairo = strstrt(GPVAL_TERMINALS, 'pngcairo') > 0\n";
    for (const Chart& c : charts) {
        const std::string size =
            " size " + std::to_string(c.width) + "," + std::to_string(c.height);
        out << "\nreset\nif (has_cairo) {\n    set terminal pngcairo" << size
            << " noenhanced font 'sans,11' background rgb 'white'\n} else {\n    set terminal png"
            << size << " noenhanced background rgb 'white'\n}\n"
            << "set output " << quoted(tempName(c.name + ".png")) << "\n"
            << c.body << "unset output\n"
            << "\nreset\nset terminal svg" << size
            << " dynamic noenhanced font 'sans,12' background rgb 'white'\n"
            << "set output " << quoted(tempName(c.name + ".svg")) << "\n"
            << c.body << "unset output\n";
    }
    return out.str();
}

// The lines of gnuplot's stderr that say what went wrong, joined into one line.
std::string errorSummary(const std::string& text) {
    std::istringstream in(text);
    std::string line, out;
    while (std::getline(in, line)) {
        const auto first = line.find_first_not_of(" \t^");
        if (first == std::string::npos) continue;
        if (line.find("arning") != std::string::npos) continue;  // warnings are not the failure
        out += (out.empty() ? "" : " | ") + line.substr(first);
    }
    if (out.size() > 300) out = out.substr(0, 297) + "...";
    return out.empty() ? "no message" : out;
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs `gnuplot <script>` in dir with stderr captured; returns "" on success, else why not.
std::string runGnuplot(const fs::path& gnuplot, const fs::path& dir,
                       const std::string& script_name) {
    const std::string err_name = tempName("gnuplot-stderr.txt");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_name.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::string program = gnuplot.string(), arg = script_name;
    char* argv[] = {program.data(), arg.data(), nullptr};
    pid_t pid = 0;
    const int spawn_error = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawn_error != 0) return "cannot start " + program + ": " + std::strerror(spawn_error);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const std::string stderr_text = readFile(dir / err_name);
    std::error_code ec;
    fs::remove(dir / err_name, ec);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
    return "gnuplot failed (" +
           (WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                              : std::string("signal")) +
           "): " + errorSummary(stderr_text);
}

bool nonEmptyFile(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec) && fs::file_size(p, ec) > 0 && !ec;
}

// Renames every temporary picture into place, or removes them all when one is missing.
std::string publish(const std::vector<Chart>& charts, const fs::path& dir, bool gnuplot_ok,
                    std::vector<std::string>& files) {
    std::vector<std::string> names;
    for (const Chart& c : charts) {
        names.push_back(c.name + ".png");
        names.push_back(c.name + ".svg");
    }
    std::string missing;
    for (const std::string& n : names) {
        if (!nonEmptyFile(dir / tempName(n))) missing = n;
    }
    std::error_code ec;
    if (!gnuplot_ok || !missing.empty()) {
        for (const std::string& n : names) fs::remove(dir / tempName(n), ec);
        return gnuplot_ok ? "gnuplot wrote no " + missing : "";
    }
    for (const std::string& n : names) {
        fs::rename(dir / tempName(n), dir / n, ec);
        if (ec) return "cannot rename " + (dir / tempName(n)).string() + ": " + ec.message();
        files.push_back(n);
    }
    return "";
}

}  // namespace

std::optional<fs::path> findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (!path) return std::nullopt;
    std::istringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        // An empty PATH entry means the current directory.
        const fs::path candidate = (dir.empty() ? fs::path(".") : fs::path(dir)) / program;
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0)
            return candidate;
    }
    return std::nullopt;
}

PlotResult writePlots(const std::vector<RunRecord>& runs, const fs::path& out_dir) {
    PlotResult result;
    const std::optional<fs::path> gnuplot = findOnPath("gnuplot");
    if (!gnuplot) {
        result.message = "plots skipped: gnuplot not found; install the Debian package gnuplot-nox";
        return result;
    }
    if (runs.empty()) {
        result.message = "plots skipped: no runs";
        return result;
    }
    bool error_measured = false;
    for (const RunRecord& r : runs) error_measured |= r.summary.error_measured;

    std::vector<Chart> charts = {frameTimeChart(runs)};
    if (error_measured) charts.push_back(timeErrorChart(runs));
    charts.push_back(queriesTrianglesChart(runs));

    fs::create_directories(out_dir);
    writeFileAtomically(out_dir / "plot-frames.dat", framesData(runs));
    writeFileAtomically(out_dir / "plot-configs.dat", configsData(runs));
    writeFileAtomically(out_dir / "plot-pareto.dat", paretoData(runs));

    result = renderCharts(charts, out_dir, "plots.gp");
    if (result.ok && !error_measured)
        result.message = "no time-against-error plot: run with --error";
    return result;
}

PlotResult renderCharts(const std::vector<GnuplotChart>& charts, const fs::path& out_dir,
                        const std::string& script_name) {
    PlotResult result;
    const std::optional<fs::path> gnuplot = findOnPath("gnuplot");
    if (!gnuplot) {
        result.message = "plots skipped: gnuplot not found; install the Debian package gnuplot-nox";
        return result;
    }
    fs::create_directories(out_dir);
    writeFileAtomically(out_dir / script_name, script(charts, script_name));

    const std::string run_error = runGnuplot(*gnuplot, out_dir, script_name);
    const std::string publish_error = publish(charts, out_dir, run_error.empty(), result.files);
    if (!run_error.empty() || !publish_error.empty()) {
        result.files.clear();
        result.message = "plots failed: " + (run_error.empty() ? publish_error : run_error) +
                         " (script: " + (out_dir / script_name).string() + ")";
        return result;
    }
    result.ok = true;
    return result;
}

}  // namespace occsim
