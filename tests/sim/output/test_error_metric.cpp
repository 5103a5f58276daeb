// Error against tie end to end through OSMesa (docs/error.md): on boxes that share faces and on a
// depth range of 10^-3 to 10^6 m, frustum culling, Ideal and every conservative culler show no
// error pixel and no missed object, with the ties counted apart; and the metric still fails
// when it should: a shrunken frustum and a culler that drops a visible object show error.
#include <gtest/gtest.h>

#include <filesystem>

#include "culling_fixtures.h"
#include "occsim/culling/registry/registry.h"
#include "render/headless_context.h"
#include "sim/output/error_picture.h"
#include "sim/run/frame_view.h"
#include "sim/run/ground_truth.h"
#include "sim/run/runner.h"
#include "sim/run/simulation.h"
#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

const std::filesystem::path kScenarios =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small";
const std::filesystem::path kSharedFaces = kScenarios / "shared-faces-small.json";
const std::filesystem::path kDeepDepth = kScenarios / "deep-depth-small.json";
const std::filesystem::path kTeapots = kScenarios / "teapots-small.json";

BenchResult bench(const std::filesystem::path& file, const std::vector<std::string>& algorithms,
                  uint32_t frames = 0, BenchOptions options = {}) {
    for (const std::string& n : algorithms) options.algorithms.push_back(findCuller(n));
    options.measure_error = true;
    options.latency = {true, 8};
    if (frames > 0) options.frames = frames;
    return runBenchmark(parseScenarioFile(file), options);
}

const RunSummary& summaryOf(const BenchResult& result, const std::string& name) {
    for (const RunRecord& r : result.runs) {
        if (r.summary.label == name) return r.summary;
    }
    throw std::runtime_error("no run " + name);
}

std::vector<std::string> conservativeAlgorithms() {
    std::vector<std::string> out;
    for (const std::string& name : cullerNames()) {
        if (findCuller(name)->conservative) out.push_back(name);
    }
    return out;
}

void expectNoErrorAndNoMiss(const BenchResult& result) {
    for (const RunRecord& run : result.runs) {
        for (const FrameStats& f : run.frames) {
            EXPECT_EQ(f.error_pixels, 0) << run.summary.label << " frame " << f.frame;
            EXPECT_EQ(f.missed_objects, 0) << run.summary.label << " frame " << f.frame;
            EXPECT_GE(f.tie_pixels, 0);
            EXPECT_GT(f.visible_objects, 0);
        }
    }
}

TEST(ErrorMetric, SharedFacesShowTiesButNoErrorAndNoMissForConservativeCullers) {
    const BenchResult result = bench(kSharedFaces, conservativeAlgorithms());
    expectNoErrorAndNoMiss(result);
    // Coincident boxes tie everywhere they show: the draw order decides the ID, and it differs
    // between ground truth (index order) and a culler (front to back).
    EXPECT_GT(summaryOf(result, "vfc").tie_pixels_total, 0);
    EXPECT_GT(summaryOf(result, "ideal").tie_pixels_total, 0);
}

// llvmpipe draws one pixel of teapot 439 at 3.7 m on frame 9 of this scene while every vertex of
// it lies 7.2 to 9.2 m away (a depth extrapolated on a sliver triangle): CHC's query on the
// teapot's node rightly finds the box hidden, and that pixel used to count as CHC's error.
TEST(ErrorMetric, AStrayFragmentOfGroundTruthIsNoErrorOfAConservativeCuller) {
    const std::filesystem::path file =
        std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/general/dense-movers-near.json";
    const BenchResult result = bench(file, {"chc"}, 10);
    expectNoErrorAndNoMiss(result);
    int64_t stray = 0;
    for (const FrameStats& f : result.runs.at(0).frames) stray += f.stray_pixels;
    // The case is still there (if a Mesa update removes it, this test no longer proves anything).
    EXPECT_GT(stray, 0);
    EXPECT_EQ(summaryOf(result, "chc").stray_pixels_total, stray);
}

// The bound is never tighter than the geometry: on ordinary frames, under both depth
// conventions, ground truth marks no fragment stray.
class GroundTruthStray : public ::testing::TestWithParam<bool> {};

TEST_P(GroundTruthStray, NoFragmentOfTheSmallScenariosIsStray) {
    for (const char* name :
         {"teapots-small.json", "deep-depth-small.json", "city-small.json", "plant-small.json"}) {
        Scenario scenario = parseScenarioFile(kScenarios / name);
        scenario.conventional_depth = GetParam();
        const auto context = createHeadlessContext({}, scenario.width, scenario.height);
        const Scene scene = buildScene(scenario);
        GlRenderer renderer(scenario.width, scenario.height, depthConventionOf(scenario));
        uploadScene(scene, renderer);
        SharedWorld world(scene, scenario);
        GroundTruth truth(renderer);
        for (uint32_t f = 0; f < 12; ++f) {
            world.advance();
            const GroundTruthFrame& frame = truth.of(world);
            EXPECT_EQ(frame.stray_fragments, 0) << name << " frame " << f;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Depth, GroundTruthStray, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& param) {
                             return std::string(param.param ? "Conventional24" : "ReverseFloat");
                         });

TEST(ErrorMetric, ADeepDepthRangeShowsNoErrorAndNoMissForConservativeCullers) {
    expectNoErrorAndNoMiss(bench(kDeepDepth, conservativeAlgorithms()));
}

TEST(ErrorMetric,
     TheTeapotsShowNoErrorAndNoMissForConservativeCullersWhileAsyncStillMissesOnThePlant) {
    std::vector<std::string> algorithms = conservativeAlgorithms();
    const BenchResult conservative = bench(kTeapots, algorithms);
    expectNoErrorAndNoMiss(conservative);
    // On the small plant the per-object scheme draws some newly visible objects a frame late.
    const BenchResult plant = bench(kScenarios / "plant-small.json", {"async"});
    const RunSummary& async = summaryOf(plant, "async");
    EXPECT_GT(async.missed_objects_total, 0);
    EXPECT_GT(async.error_pixels_total, 0);
}

// A device that never draws one object: what a culler that wrongly drops it puts on screen.
class DroppingDevice final : public RenderDevice {
  public:
    DroppingDevice(RenderDevice& inner, uint32_t dropped) : inner_(inner), dropped_(dropped) {}
    void drawObject(uint32_t object) override {
        if (object != dropped_) inner_.drawObject(object);
    }
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override {
        return inner_.issueQuery(boxes, subjects);
    }
    bool isQueryReady(QueryId id) override { return inner_.isQueryReady(id); }
    QueryAnswer takeAnswer(QueryId id) override { return inner_.takeAnswer(id); }
    const DeviceCounters& counters() const override { return inner_.counters(); }
    void resetCounters() override { inner_.resetCounters(); }

  private:
    RenderDevice& inner_;
    uint32_t dropped_;
};

class DroppingCuller final : public Culler {
  public:
    explicit DroppingCuller(uint32_t dropped) : dropped_(dropped) {}
    void reset(const BspTree& tree) override { inner_->reset(tree); }
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override {
        DroppingDevice dropping(device, dropped_);
        inner_->cullAndRender(tree, frame, dropping);
    }

  private:
    uint32_t dropped_;
    std::unique_ptr<Culler> inner_ = makeCuller(*findCuller("vfc"), CullerOptions{});
};

BenchOptions withCuller(std::function<std::unique_ptr<Culler>()> make) {
    BenchOptions options;
    options.make_culler = [make](const CullerRow&, const CullerOptions&) { return make(); };
    options.keep_worst_error_frame = true;
    return options;
}

TEST(ErrorMetric, AShrunkenFrustumStillShowsErrorOnBothTestScenes) {
    for (const auto& file : {kSharedFaces, kDeepDepth}) {
        const BenchResult result =
            bench(file, {"vfc"}, 12,
                  withCuller([] { return std::make_unique<testing::ShrunkenFrustumCuller>(); }));
        EXPECT_GT(result.runs[0].summary.error_pixels_total, 0) << file;
        EXPECT_GT(result.runs[0].summary.missed_objects_total, 0) << file;
    }
}

TEST(ErrorMetric, ACullerThatDropsAVisibleObjectShowsErrorAndTheMissAndItsPopping) {
    // Object 433: one of the four large boxes in front of the grid, in view from frame 0, with
    // grid boxes behind it.
    const BenchResult result = bench(
        kSharedFaces, {"vfc"}, 8, withCuller([] { return std::make_unique<DroppingCuller>(433); }));
    const RunSummary& s = result.runs[0].summary;
    EXPECT_GT(s.error_pixels_total, 0);
    EXPECT_EQ(s.missed_objects_total, 8) << "missed on every one of the 8 frames";
    EXPECT_EQ(s.popping_events, 1u);
    EXPECT_EQ(s.popping_max_frames, 8u);
    // The worst frame's picture marks errors apart from ties.
    ASSERT_EQ(result.worst_error_frames.size(), 1u);
    const ErrorFrame& worst = result.worst_error_frames[0];
    const uint32_t w = result.metadata.width, h = result.metadata.height;
    const std::vector<uint8_t> picture = composeErrorPicture(worst, w, h);
    int64_t magenta = 0, yellow = 0;
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const uint8_t* p = picture.data() + (size_t{y} * 3 * w + 2 * w + x) * 4;
            magenta +=
                p[0] == kErrorColour[0] && p[1] == kErrorColour[1] && p[2] == kErrorColour[2];
            yellow += p[0] == kTieColour[0] && p[1] == kTieColour[1] && p[2] == kTieColour[2];
        }
    }
    EXPECT_EQ(magenta, worst.error_pixels);
    EXPECT_EQ(yellow, worst.tie_pixels);
}

}  // namespace
}  // namespace occsim
