// The tuner's runs (tune/measure.h) without rendering: a setting made into a configuration (its
// values and cost model for the tuned culler alone), the session's count of runs on a busy
// machine, and a run's figures as the log keeps them (the first repetition, the timed frames).
// Interleaved runs on a real scene: test_tuned_file.cpp and tests/system/test_occtune.cpp.
#include <gtest/gtest.h>

#include <optional>

#include "occsim/culling/registry/registry.h"
#include "tune/measure.h"

namespace occsim::tune {
namespace {

TEST(Measure, ASettingGoesToTheTunedCullerAloneWithItsCostModel) {
    Scenario scenario;
    const CullerRow& statistical = *findCuller("statistical");
    const CullerRow& plus = *findCuller("statistical+");
    Setting setting;
    setting.label = "sample 3";
    setting.options = scenario.culler.of(statistical);
    setting.options.set("base_time", 0.25);
    setting.options.set("decay_b", 0.5);
    setting.cost_model = CostModel{0.5, 0.001, 0.0};

    const RunConfig config = configOf(scenario, statistical, setting);
    EXPECT_EQ(config.label, "sample 3");
    EXPECT_EQ(config.algorithm, &statistical);
    EXPECT_EQ(config.culler.of(statistical), setting.options);
    EXPECT_EQ(config.culler.of(plus), scenario.culler.of(plus)) << "another culler keeps its own";
    ASSERT_EQ(config.culler.cost_model_of.count("statistical"), 1u);
    EXPECT_EQ(config.culler.cost_model_of.at("statistical"), (CostModel{0.5, 0.001, 0.0}));
    EXPECT_FALSE(config.culler.cost_model.known()) << "the shared cost model stays the scenario's";

    setting.cost_model.reset();
    EXPECT_TRUE(configOf(scenario, statistical, setting).culler.cost_model_of.empty());
}

TEST(Measure, EveryRunIsCountedAndThoseOnABusyMachineApart) {
    SessionRuns session;
    RunMetadata quiet;
    quiet.hardware_threads = 2;
    quiet.load_before = {0.5, 0.5, 0.5};
    quiet.load_after = {1.0, 0.5, 0.5};
    RunMetadata busy = quiet;
    busy.load_before = {3.5, 2.0, 1.0};
    EXPECT_FALSE(noteMachineLoad(session, quiet));
    EXPECT_TRUE(noteMachineLoad(session, busy));
    EXPECT_FALSE(noteMachineLoad(session, quiet));
    EXPECT_EQ(session.runs, 3u);
    EXPECT_EQ(session.busy_runs, 1u);
}

TEST(Measure, ALoggedRunHasTheFirstRepetitionsFiguresAndOnlyTheTimedFrames) {
    RunRecord run;
    for (uint32_t f = 0; f < 6; ++f) {
        FrameStats frame;
        frame.frame = f;
        frame.frame_ms = 10.0 + f;
        frame.queries = 20 + f;
        frame.triangles = 1000 * f;
        frame.objects_drawn = 30 + f;
        frame.wait_ms = 0.5 * f;
        run.frames.push_back(frame);
    }
    run.summary.frame_ms.mean = 99.0;  // all repetitions together: not what the log keeps
    RunSummary first;
    first.frame_ms.mean = 13.5;
    first.frame_ms.p95 = 15.0;
    first.error_pixels_total = 7;
    run.repetitions = {first, RunSummary{}};

    const LoggedRun logged = loggedRunOf(run, 2);
    EXPECT_EQ(logged.mean_ms, 13.5);
    EXPECT_EQ(logged.p95_ms, 15.0);
    EXPECT_EQ(logged.error_pixels, 7);
    ASSERT_EQ(logged.frames.size(), 4u) << "frames 0 and 1 are the warm-up";
    EXPECT_EQ(logged.frames[0].frame_ms, 12.0);
    EXPECT_EQ(logged.frames[3].queries, 25.0);
    EXPECT_EQ(logged.frames[3].triangles, 5000.0);
    EXPECT_EQ(logged.frames[3].objects_drawn, 35.0);
    EXPECT_EQ(logged.frames[3].wait_ms, 2.5);

    run.repetitions.clear();  // one repetition: the summary is its figures
    EXPECT_EQ(loggedRunOf(run, 2).mean_ms, 99.0);
}

}  // namespace
}  // namespace occsim::tune
