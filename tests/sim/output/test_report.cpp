// What a person reads after a benchmark: report.md and its comparison table, the run's headline
// on the machine's load, and the gnuplot charts (written whole or not at all).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "sim/output/fixed_text.h"
#include "sim/output/markdown_report.h"
#include "sim/output/plots.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

RunRecord record(const std::string& label, const std::string& algorithm, double mean_ms,
                 double error_mean, bool pareto) {
    RunRecord r;
    r.algorithm = findCuller(algorithm);
    r.pareto = pareto;
    RunSummary& s = r.summary;
    s.label = label;
    s.frames = 30;
    s.timed_frames = 25;
    s.frame_ms = {mean_ms, mean_ms, mean_ms * 1.2, mean_ms * 0.8, mean_ms * 1.5};
    s.frame_ms_mean_min = s.frame_ms_mean_max = mean_ms;
    s.queries_mean = algorithm == "vfc" || algorithm == "ideal" ? 0 : 42;
    s.triangles_mean = 1000 * mean_ms;
    s.objects_mean = 10 * mean_ms;
    s.error_measured = true;
    s.error_pixels_mean = error_mean;
    s.error_pixels_total = static_cast<int64_t>(error_mean * 30);
    for (uint32_t f = 0; f < 30; ++f) {
        FrameStats fs;
        fs.frame = f;
        fs.frame_ms = mean_ms + (f % 5);
        fs.queries = static_cast<uint64_t>(s.queries_mean) + f;
        fs.triangles = static_cast<uint64_t>(s.triangles_mean) + 100 * f;
        r.frames.push_back(fs);
    }
    return r;
}

std::vector<RunRecord> sampleRuns() {
    return {record("vfc", "vfc", 20.0, 0.0, false),
            record("statistical threshold=4", "statistical", 12.0, 3.5, true),
            record("chc", "chc", 14.0, 0.0, true), record("ideal", "ideal", 6.0, 0.0, false)};
}

TEST(MarkdownReport, HasTheHeaderTheTableRowsThePictureLinksAndHowToRead) {
    BenchResult result;
    result.runs = sampleRuns();
    RunMetadata& c = result.metadata;
    c.scenario_name = "teapots-small";
    c.scenario_file = "scenarios/small/teapots-small.json";
    c.frames = 30;
    c.warmup_frames = 5;
    c.error_measured = true;
    c.hardware_threads = 2;
    c.renderer = "llvmpipe (test)";
    c.width = 200;
    c.height = 150;
    c.command_line = "occsim bench scenarios/small/teapots-small.json --error --plots";
    c.sweep = Sweep{"", "threshold", {0, 4}};
    ReportFiles files;
    files.plot_files = {"plot-frame-time.png", "plot-frame-time.svg", "plot-time-vs-error.png"};
    files.birds_eye_files = {"birds-eye-chc-frame-00020.png"};
    const std::string md = markdownReport(result, files);

    EXPECT_NE(md.find("# occsim bench: teapots-small"), std::string::npos);
    EXPECT_NE(md.find(c.command_line), std::string::npos);
    EXPECT_NE(md.find("2 hardware threads"), std::string::npos);
    EXPECT_NE(md.find("llvmpipe (test)"), std::string::npos);
    EXPECT_NE(md.find("threshold = 0, 4"), std::string::npos);
    EXPECT_NE(md.find("first 5 frames are warm-up"), std::string::npos);
    EXPECT_NE(md.find("Ground-truth rendering, PNG writing and statistics I/O"), std::string::npos);
    // The table: same columns as the text table, one row per configuration, Pareto marked.
    const ComparisonTable t = comparisonTable(result.runs);
    std::string header = "|";
    for (const auto& h : t.header) header += " " + h + " |";
    EXPECT_NE(md.find(header), std::string::npos) << md;
    EXPECT_NE(md.find("| vfc | 20.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| **statistical threshold=4** | 12.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| **chc** | 14.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| ideal | 6.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("1.67x"), std::string::npos) << "speedup of statistical over VFC";
    // Pictures: the PNGs as images, the SVG linked; only the files named.
    EXPECT_NE(md.find("![Frame time per frame](plot-frame-time.png)"), std::string::npos);
    EXPECT_NE(md.find("(plot-frame-time.svg)"), std::string::npos);
    EXPECT_NE(md.find("![Time against error](plot-time-vs-error.png)"), std::string::npos);
    EXPECT_EQ(md.find("plot-queries-triangles"), std::string::npos);
    EXPECT_NE(md.find("](birds-eye-chc-frame-00020.png)"), std::string::npos);
    EXPECT_NE(md.find("## How to read this"), std::string::npos);
    EXPECT_NE(md.find("popping"), std::string::npos);
}

// One error pixel in 240 frames is an error: no cell of the table (console and report.md alike)
// prints a figure that is not zero as 0.0.
TEST(ComparisonTable, ANonZeroFigureNeverPrintsAsZero) {
    EXPECT_EQ(fixedNonZero(1.0 / 240, 1), "<0.1");
    EXPECT_EQ(fixedNonZero(0.3, 0), "<1");
    EXPECT_EQ(fixedNonZero(-0.001, 2), ">-0.01");
    EXPECT_EQ(fixedNonZero(0.0, 1), "0.0");
    EXPECT_EQ(fixedNonZero(0.06, 1), "0.1");
    EXPECT_EQ(fixedNonZero(2.25, 1), fixed(2.25, 1));
    BenchResult result;
    result.runs = {record("vfc", "vfc", 20.0, 0.0, false),
                   record("async", "async", 10.0, 0.0, true)};
    RunSummary& s = result.runs[1].summary;
    s.frames = 240;
    s.error_pixels_total = 1;
    s.error_pixels_worst = 1;
    s.error_pixels_mean = 1.0 / 240;
    s.queries_mean = 0.02;
    const ComparisonTable t = comparisonTable(result.runs);
    auto column = [&](const std::string& name) {
        return static_cast<size_t>(std::find(t.header.begin(), t.header.end(), name) -
                                   t.header.begin());
    };
    ASSERT_LT(column("err px/fr"), t.header.size());
    EXPECT_EQ(t.rows[1][column("err px/fr")], "<0.1");
    EXPECT_EQ(t.rows[1][column("queries/fr")], "<0.1");
    EXPECT_EQ(t.rows[0][column("err px/fr")], "0.0") << "zero stays zero";
    EXPECT_NE(formatComparisonTable(result.runs).find("<0.1"), std::string::npos);
    EXPECT_NE(markdownReport(result, ReportFiles{}).find("| <0.1 |"), std::string::npos);
}

fs::path freshDir(const std::string& name) {
    const fs::path p = fs::temp_directory_path() /
                       ("occsim-report-outputs-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    return p;
}

// Sets PATH for the scope of a test and puts the old value back.
class ScopedPath {
  public:
    explicit ScopedPath(const std::string& value) {
        if (const char* old = std::getenv("PATH")) old_ = old;
        ::setenv("PATH", value.c_str(), 1);
    }
    ~ScopedPath() {
        if (old_)
            ::setenv("PATH", old_->c_str(), 1);
        else
            ::unsetenv("PATH");
    }
    ScopedPath(const ScopedPath&) = delete;
    ScopedPath& operator=(const ScopedPath&) = delete;

  private:
    std::optional<std::string> old_;
};

void writeExecutable(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
    ::chmod(path.c_str(), 0755);
}

std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> out;
    if (!fs::exists(dir)) return out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

// A run records the load average before and after it; one on a machine busier than its hardware
// threads says so on the console, in report.md and in summary.json.
TEST(RunHeadline, SaysTheLoadAndWarnsWhenTheMachineWasBusy) {
    BenchResult result;
    result.runs = sampleRuns();
    RunMetadata& m = result.metadata;
    m.scenario_name = "teapots-small";
    m.frames = 40;
    m.hardware_threads = 2;
    m.load_before = {0.5, 0.4, 0.3};
    m.load_after = {1.25, 0.6, 0.4};
    EXPECT_NE(runHeadline(result).find(
                  "machine: 2 hardware threads, load average 0.50 before the run, 1.25 after"),
              std::string::npos)
        << runHeadline(result);
    EXPECT_EQ(runHeadline(result).find("busy machine"), std::string::npos);
    EXPECT_FALSE(m.busyMachine());
    m.load_after = {3.5, 3.0, 1.0};
    EXPECT_FALSE(m.busyMachine()) << "after a run its own threads count in the load";
    m.load_after = {5.5, 3.0, 1.0};
    EXPECT_TRUE(m.busyMachine());
    m.load_after = {1.0, 1.0, 1.0};
    m.load_before = {2.5, 1.0, 1.0};
    EXPECT_TRUE(m.busyMachine()) << "other work when the run began";
    m.load_after = {5.5, 3.0, 1.0};
    EXPECT_NE(runHeadline(result).find("busy machine: other work ran beside this run"),
              std::string::npos);
    EXPECT_NE(markdownReport(result, {}).find("**busy: other work ran beside this run"),
              std::string::npos);
    const nlohmann::json summary = summaryJson(result);
    EXPECT_EQ(summary["machine"]["busy"], true);
    EXPECT_EQ(summary["machine"]["load_average_after"][0], 5.5);
    EXPECT_EQ(summary["machine"]["load_average_before"].size(), 3u);
}

TEST(Plots, WithoutGnuplotOnPathSaysSoAndWritesNothing) {
    const fs::path empty_bin = freshDir("empty-bin");
    fs::create_directories(empty_bin);
    const fs::path out = freshDir("no-gnuplot");
    PlotResult r;
    {
        ScopedPath path(empty_bin.string());
        r = writePlots(sampleRuns(), out);
    }
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.message,
              "plots skipped: gnuplot not found; install the Debian package gnuplot-nox");
    EXPECT_TRUE(r.files.empty());
    EXPECT_FALSE(fs::exists(out)) << "nothing written, not even the folder";
}

TEST(Plots, AFailingGnuplotLeavesNoPictureNotEvenAHalfWrittenOne) {
    const fs::path bin = freshDir("failing-bin");
    fs::create_directories(bin);
    // Writes a partial file under every temporary name the script asks for, then fails.
    writeExecutable(bin / "gnuplot",
                    "#!/bin/sh\n"
                    "for f in $(grep -o '\\.plot-[a-z-]*\\.[a-z]*\\.tmp-[0-9]*' \"$1\"); do\n"
                    "  printf partial > \"$f\"\n"
                    "done\n"
                    "echo '\"plots.gp\" line 9: something broke' >&2\n"
                    "exit 1\n");
    const fs::path out = freshDir("failing");
    PlotResult r;
    {
        ScopedPath path(bin.string() + ":/usr/bin:/bin");
        r = writePlots(sampleRuns(), out);
    }
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.message.find("plots failed"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("something broke"), std::string::npos) << r.message;
    EXPECT_TRUE(r.files.empty());
    for (const std::string& f : filesIn(out)) {
        EXPECT_TRUE(f.ends_with(".dat") || f == "plots.gp") << "left behind: " << f;
    }
}

TEST(Plots, WithGnuplotWritesNonEmptyPngAndSvgOfEveryChart) {
    if (!findOnPath("gnuplot"))
        GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
    const fs::path out = freshDir("real");
    const PlotResult r = writePlots(sampleRuns(), out);
    ASSERT_TRUE(r.ok) << r.message;
    const std::vector<std::string> want = {
        "plot-frame-time.png",    "plot-frame-time.svg",        "plot-time-vs-error.png",
        "plot-time-vs-error.svg", "plot-queries-triangles.png", "plot-queries-triangles.svg"};
    EXPECT_EQ(r.files, want);
    for (const std::string& f : want) {
        ASSERT_TRUE(fs::exists(out / f)) << f;
        EXPECT_GT(fs::file_size(out / f), 1000u) << f;
        std::ifstream in(out / f, std::ios::binary);
        std::string head(8, '\0');
        in.read(head.data(), 8);
        if (f.ends_with(".png"))
            EXPECT_EQ(head.substr(1, 3), "PNG") << f;
        else
            EXPECT_TRUE(head.starts_with("<?xml") || head.starts_with("<svg")) << f;
    }
    for (const std::string& f : filesIn(out)) EXPECT_EQ(f.find(".tmp-"), std::string::npos) << f;
}

}  // namespace
}  // namespace occsim
