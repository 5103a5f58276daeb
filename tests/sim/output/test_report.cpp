// The run's tables and lines (sim/output/report.h): the comparison table (no figure that is not
// zero printed as zero), the headline on the machine's load, the line that says a run ended
// early, and the overdraw and executed-draw columns from real runs. report.md and the charts:
// test_markdown_report.cpp and test_plots.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "sample_runs.h"
#include "sim/output/fixed_text.h"
#include "sim/output/markdown_report.h"
#include "sim/output/report.h"
#include "small_bench.h"

namespace occsim {
namespace {

using testing::benchSmall;
using testing::kSmall;
using testing::record;
using testing::sampleRuns;
using testing::traitsOf;

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
    // What it saw, and the command to rerun for a quiet figure.
    m.command_line = "occsim bench scenarios/teapots.json --error";
    EXPECT_NE(runHeadline(result).find("busy machine: other work ran beside this run (load "
                                       "average 2.50 before it, above its 2 hardware threads)"),
              std::string::npos)
        << runHeadline(result);
    EXPECT_NE(
        runHeadline(result).find("wait a minute): occsim bench scenarios/teapots.json --error"),
        std::string::npos);
    m.load_before = {1.0, 1.0, 1.0};
    m.load_after = {5.5, 3.0, 1.0};
    EXPECT_NE(runHeadline(result).find("(load average 5.50 after it, above twice its 2 hardware "
                                       "threads)"),
              std::string::npos);
    EXPECT_NE(markdownReport(result, {}).find("**busy: other work ran beside this run"),
              std::string::npos);
    const nlohmann::json summary = summaryJson(result);
    EXPECT_EQ(summary["machine"]["busy"], true);
    EXPECT_EQ(summary["machine"]["load_average_after"][0], 5.5);
    EXPECT_EQ(summary["machine"]["load_average_before"].size(), 3u);
    EXPECT_TRUE(summary["machine"]["contexts_apart"].empty());
    EXPECT_EQ(runHeadline(result).find("own GL context"), std::string::npos);
    m.contexts_apart = {"conditional"};
    EXPECT_NE(runHeadline(result).find("\nown GL context: conditional (conditional rendering"),
              std::string::npos);
    EXPECT_EQ(summaryJson(result)["machine"]["contexts_apart"][0], "conditional");
}

// A culler that throws in its frame `fail_at`, culling like `inner` before it.
class FailingCuller final : public Culler {
  public:
    FailingCuller(std::unique_ptr<Culler> inner, uint32_t fail_at)
        : inner_(std::move(inner)), fail_at_(fail_at) {}
    void reset(const BspTree& tree) override { inner_->reset(tree); }
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override {
        if (frames_++ == fail_at_) throw std::runtime_error("out of budget");
        inner_->cullAndRender(tree, frame, device);
    }

  private:
    std::unique_ptr<Culler> inner_;
    uint32_t fail_at_;
    uint32_t frames_ = 0;
};

// The failure is named, not thrown: every configuration keeps the whole frames before it (those
// that rendered the failed frame first, in the rotated order too, drop it), and no repetition
// after it runs.
TEST(Simulation, AConfigurationThatThrowsEndsTheRunWithTheWholeFramesBeforeItNamed) {
    BenchOptions options;
    options.algorithms = traitsOf({"vfc", "chc", "statistical"});
    options.frames = 12;
    options.repetitions = 2;
    options.frame_order = FrameOrder::rotated;
    options.make_culler = [](const CullerRow& algorithm, const CullerOptions& culler) {
        std::unique_ptr<Culler> made = makeCuller(algorithm, culler);
        if (algorithm.name == "chc")
            return std::unique_ptr<Culler>(new FailingCuller(std::move(made), 5));
        return made;
    };
    const BenchResult result = runBenchmark(parseScenarioFile(kSmall), options);
    ASSERT_TRUE(result.partial.has_value());
    EXPECT_EQ(result.partial->reason, "configuration 'chc' failed at frame 5: out of budget");
    EXPECT_EQ(result.partial->signal, 0);
    EXPECT_EQ(result.partial->frames_reached, 5u);
    for (const RunRecord& run : result.runs) {
        EXPECT_EQ(run.frames.size(), 5u) << run.summary.label;
        EXPECT_EQ(run.repetitions.size(), 1u) << run.summary.label;
        EXPECT_EQ(run.summary.frames, 5u) << run.summary.label;
    }
    EXPECT_NE(partialLine(result).find("after 5 of 12 frames; the 5 whole frames are reported"),
              std::string::npos)
        << partialLine(result);
}

// Over-draw is what a culler drew that ground truth does not see: every drawn object is either
// visible (and not missed) or over-drawn; Ideal over-draws nothing, VFC a great deal.
TEST(Simulation, OverdrawCountsTheObjectsDrawnThatGroundTruthDoesNotSee) {
    const BenchResult result =
        benchSmall(true, LatencyMode{true, 8}, {"vfc", "statistical", "async", "ideal"});
    const Scene scene = buildScene(parseScenarioFile(kSmall));
    const uint64_t teapot = scene.meshes[scene.object_mesh[0]].triangleCount();
    for (const RunRecord& run : result.runs) {
        double overdrawn = 0;
        for (const FrameStats& f : run.frames) {
            EXPECT_EQ(static_cast<int64_t>(f.objects_drawn),
                      f.visible_objects - f.missed_objects + f.overdrawn_objects)
                << run.summary.label << " frame " << f.frame;
            EXPECT_LE(f.overdrawn_triangles, static_cast<int64_t>(f.triangles));
            EXPECT_EQ(static_cast<uint64_t>(f.overdrawn_triangles),
                      teapot * static_cast<uint64_t>(f.overdrawn_objects))
                << "every object is a teapot of one tessellation";
            overdrawn += static_cast<double>(f.overdrawn_objects);
        }
        EXPECT_DOUBLE_EQ(run.summary.overdrawn_objects_mean,
                         overdrawn / static_cast<double>(run.frames.size()));
        if (run.summary.label == "ideal") {
            EXPECT_EQ(run.summary.overdrawn_objects_mean, 0.0);
        }
        if (run.summary.label == "vfc") {
            EXPECT_GT(run.summary.overdrawn_objects_mean, 10.0);
        }
    }
    const ComparisonTable table = comparisonTable(result.runs);
    EXPECT_NE(std::find(table.header.begin(), table.header.end(), "overdrawn/fr"),
              table.header.end());
    EXPECT_NE(std::find(table.header.begin(), table.header.end(), "overdrawn tris/fr"),
              table.header.end());
    EXPECT_NE(framesCsv(result.runs).find(",stray_pixels,overdrawn_objects,overdrawn_triangles,"),
              std::string::npos);
}

// conditional submits every object in the frustum and the device skips the hidden ones: the two
// are counted apart. With GL_QUERY_WAIT a draw executes exactly when its query passed samples,
// so the executed draws are the drawn set error measurement reads from those samples.
TEST(Simulation, ConditionalDrawsAreCountedAsSubmittedAndAsExecuted) {
    const Scenario scenario = parseScenarioFile(kSmall);
    BenchOptions options;
    options.measure_error = true;
    options.latency = LatencyMode{true, 8};
    options.frames = 12;
    const CullerRow& conditional = *findCuller("conditional");
    RunConfig waited{"conditional wait=true", &conditional, scenario.culler};
    waited.culler.edit(conditional).set("wait", 1.0);
    options.configs = {RunConfig{"vfc", findCuller("vfc"), scenario.culler},
                       RunConfig{"conditional", &conditional, scenario.culler}, waited};
    options.algorithms = {findCuller("vfc")};
    const BenchResult result = runBenchmark(scenario, options);
    ASSERT_EQ(result.runs.size(), 3u);
    bool skipped_some = false;
    for (const RunRecord& run : result.runs) {
        for (const FrameStats& f : run.frames) {
            EXPECT_LE(f.executed_objects, f.objects_drawn);
            EXPECT_LE(f.executed_triangles, f.triangles);
            if (run.summary.label == "vfc") {
                EXPECT_EQ(f.executed_objects, f.objects_drawn);
                EXPECT_EQ(f.executed_triangles, f.triangles);
            }
            if (run.summary.label == "conditional wait=true") {
                EXPECT_EQ(static_cast<int64_t>(f.executed_objects),
                          f.visible_objects - f.missed_objects + f.overdrawn_objects)
                    << "frame " << f.frame;
                skipped_some |= f.executed_objects < f.objects_drawn;
            }
        }
    }
    EXPECT_TRUE(skipped_some) << "the teapot field hides some of what is in the frustum";
    EXPECT_LT(result.runs[2].summary.executed_objects_mean, result.runs[2].summary.objects_mean);
    const ComparisonTable table = comparisonTable(result.runs);
    EXPECT_NE(std::find(table.header.begin(), table.header.end(), "exec objs/fr"),
              table.header.end());
}

// hzb and raster decide on the device: no read-back inside the frame (hzb read_back=true reads
// its flags once a frame), what they drew counted after the frame (the same objects for both hzb
// variants), and each phase's CPU and GPU time in frames.csv and summary.json (empty and null for
// the other cullers).
TEST(Simulation, GpuDrivenCullersReadNothingBackInTheFrameAndTimeEachPhase) {
    const Scenario scenario = parseScenarioFile(kSmall);
    BenchOptions options;
    options.measure_error = true;
    options.frames = 8;
    const CullerRow& hzb = *findCuller("hzb");
    RunConfig read_back{"hzb read_back=true", &hzb, scenario.culler};
    read_back.culler.edit(hzb).set("read_back", 1.0);
    options.configs = {RunConfig{"vfc", findCuller("vfc"), scenario.culler},
                       RunConfig{"hzb", &hzb, scenario.culler}, read_back,
                       RunConfig{"raster", findCuller("raster"), scenario.culler}};
    options.algorithms = {findCuller("vfc")};
    const BenchResult result = runBenchmark(scenario, options);
    ASSERT_EQ(result.runs.size(), 4u);
    for (size_t f = 0; f < 8; ++f) {
        SCOPED_TRACE("frame " + std::to_string(f));
        for (const RunRecord& run : result.runs) {
            const FrameStats& s = run.frames[f];
            EXPECT_EQ(s.error_pixels, 0) << run.summary.label;
            EXPECT_EQ(s.missed_objects, 0) << run.summary.label;
            const bool gpu_driven = run.summary.label == "hzb" || run.summary.label == "raster";
            if (gpu_driven) {
                EXPECT_EQ(s.read_backs, 0u) << run.summary.label;
                EXPECT_GT(s.objects_drawn, 0u) << run.summary.label;
                EXPECT_GT(s.phase_cpu_ms[0], 0.0) << run.summary.label;
                for (size_t p = 0; p < 3; ++p) EXPECT_GE(s.phase_gpu_ms[p], 0.0) << p;
            } else {
                EXPECT_LT(s.phase_cpu_ms[0], 0.0) << run.summary.label;
            }
        }
        EXPECT_EQ(result.runs[1].frames[f].objects_drawn, result.runs[2].frames[f].objects_drawn)
            << "hzb draws the same objects with and without the read-back";
        if (f > 0) {  // frame 0 builds no pyramid: nothing to read
            EXPECT_EQ(result.runs[2].frames[f].read_backs, 1u);
        }
    }
    const std::string csv = framesCsv(result.runs);
    EXPECT_NE(csv.find(",executed_triangles,phase1_cpu_ms,test_cpu_ms,phase2_cpu_ms,phase1_gpu_ms,"
                       "test_gpu_ms,phase2_gpu_ms,read_backs,shadow_cpu_ms,shadow_gpu_ms,"
                       "shading_cpu_ms,shading_gpu_ms,shadow_casters,shadow_triangles,shadow_error_"
                       "pixels,missed_casters,"
                       "shadow_seen_casters,shadow_tie_pixels,shadow_queries,left_error_pixels,"
                       "right_error_pixels\n"),
              std::string::npos);
    EXPECT_NE(csv.find("\nvfc,0,0,"), std::string::npos);
    // vfc's rows hold six empty phase columns before read_backs (0), then a scene without
    // lights has no shadow pass: four empty times and seven -1 counts; nor stereo: two -1.
    const size_t vfc_row = csv.find("\nvfc,0,0,");
    const std::string row = csv.substr(vfc_row + 1, csv.find('\n', vfc_row + 1) - vfc_row - 1);
    EXPECT_EQ(row.substr(row.size() - 39), ",,,,,,,0,,,,,-1,-1,-1,-1,-1,-1,-1,-1,-1") << row;
    EXPECT_TRUE(configurationJson(result.runs[0], result.runs)["shadow_pass"].is_null());
    const nlohmann::json j = configurationJson(result.runs[3], result.runs);
    ASSERT_TRUE(j["gpu_driven_phases"].is_object()) << j.dump();
    EXPECT_GT(j["gpu_driven_phases"]["phase1"]["cpu_ms"].get<double>(), 0.0);
    EXPECT_TRUE(j["gpu_driven_phases"]["test"]["gpu_ms"].is_number());
    EXPECT_TRUE(configurationJson(result.runs[0], result.runs)["gpu_driven_phases"].is_null());
}

// A traced frame of a GPU-driven culler (the bird's-eye picture, the viewer's trace mode) names
// the objects the device drew, read back after the frame: as many as the frame counted.
TEST(Simulation, ATraceOfAGpuDrivenFrameNamesWhatTheDeviceDrew) {
    const Scenario scenario = parseScenarioFile(kSmall);
    BenchOptions options;
    options.frames = 4;
    options.trace_frame = 3;
    options.algorithms = {findCuller("raster"), findCuller("hzb")};
    std::map<std::string, size_t> traced;  // by configuration
    options.on_frame = [&traced](const FrameEvent& e) {
        if (e.frame != 3) return;
        const FrameTrace* trace = e.simulation.lastTrace();
        ASSERT_NE(trace, nullptr);
        traced[e.config.label] = trace->drawn_objects.size();
    };
    const BenchResult result = runBenchmark(scenario, options);
    ASSERT_EQ(traced.size(), 2u);
    for (const RunRecord& run : result.runs) {
        ASSERT_EQ(traced.count(run.summary.label), 1u) << run.summary.label;
        EXPECT_GT(traced[run.summary.label], 0u);
        EXPECT_EQ(traced[run.summary.label], run.frames[3].objects_drawn) << run.summary.label;
    }
}

}  // namespace
}  // namespace occsim
