// Stereo end to end (docs/views.md): two eyes rendered one above the other, ground truth of both,
// culled by one pass over the enclosing frustum or by an instance of the culler per eye. Every
// query culler draws every pixel either eye sees, in both modes, with eyes an IPD apart and 4 m
// apart (where each eye sees much the middle camera does not); each eye's error is its own figure;
// the same decisions on a second run; with a sun, the shadow pass keeps zero shadow error for
// both eyes. What stereo does not take yet is refused with one line.
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "error_bench.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

using testing::kScenarios;

Scenario stereoCity(double separation_m, StereoCulling culling) {
    Scenario scenario = parseScenarioFile(kScenarios / "city-small.json");
    scenario.stereo = StereoSpec{separation_m, culling};
    return scenario;
}

BenchOptions stereoBench(std::initializer_list<const char*> cullers) {
    return testing::errorBenchOf(cullers, 12);
}

const std::initializer_list<const char*> kQueryCullers = {"vfc", "stop-and-wait", "statistical",
                                                          "chc", "conditional"};

TEST(Stereo, EveryQueryCullerDrawsEveryPixelEitherEyeSeesInBothCullingModes) {
    const BenchOptions options = stereoBench(kQueryCullers);
    const BenchResult mono =
        runBenchmark(parseScenarioFile(kScenarios / "city-small.json"), options);
    for (const double separation : {0.064, 4.0}) {
        for (const StereoCulling culling : {StereoCulling::Enclosing, StereoCulling::PerEye}) {
            const std::string mode =
                std::string(culling == StereoCulling::PerEye ? "per eye" : "enclosing") + ", " +
                std::to_string(separation) + " m";
            const BenchResult stereo = runBenchmark(stereoCity(separation, culling), options);
            testing::expectNoErrorAndNoMiss(stereo);
            ASSERT_EQ(stereo.runs.size(), mono.runs.size());
            int64_t more_visible = 0;
            for (size_t r = 0; r < stereo.runs.size(); ++r) {
                const std::string& label = stereo.runs[r].summary.label;
                for (size_t f = 0; f < stereo.runs[r].frames.size(); ++f) {
                    const FrameStats& s = stereo.runs[r].frames[f];
                    EXPECT_EQ(s.left_error_pixels, 0) << mode << ", " << label << " frame " << f;
                    EXPECT_EQ(s.right_error_pixels, 0) << mode << ", " << label << " frame " << f;
                    EXPECT_GT(s.objects_drawn, 0) << mode << ", " << label << " frame " << f;
                    const FrameStats& m = mono.runs[r].frames[f];
                    EXPECT_EQ(m.left_error_pixels, -1) << "no stereo, no eyes";
                    more_visible += s.visible_objects - m.visible_objects;
                }
            }
            // Four metres apart, the eyes see well past the middle camera's frustum: the zero
            // above held where a culler of the middle camera's view would have missed.
            if (separation > 1.0) {
                EXPECT_GT(more_visible, 0) << mode;
            }
        }
    }
}

// Teapots on the ground (x, z, height) before a still camera at the origin looking down -z, seen
// by two eyes 4 m apart (each frustum shifted by 2 m; the camera's spans +-15.4 m at 20 m).
struct Teapot {
    double x, z, size;
};
Scenario teapotsAt(std::initializer_list<Teapot> teapots, StereoCulling culling) {
    std::string sources;
    for (const Teapot& t : teapots) {
        const std::string at = "[" + std::to_string(t.x) + ", 0, " + std::to_string(t.z) + "]";
        const std::string size = "[" + std::to_string(t.size) + ", " + std::to_string(t.size) + "]";
        sources += std::string(sources.empty() ? "" : ", ") +
                   R"({"type": "teapots", "count": 1, "size": )" + size +
                   R"(, "region": {"min": )" + at + R"(, "max": )" + at + "}}";
    }
    Scenario scenario = parseScenarioText(R"({
        "format_version": 1, "frames": 3, "viewport": {"width": 200, "height": 150},
        "camera": {"fov_y": 60, "keyframes": [{"time": 0, "position": [0, 0.5, 0],
                                                "target": [0, 0.5, -10]}]},
        "scene": {"sources": [)" + sources + R"(]}})",
                                          "teapots.json");
    scenario.stereo = StereoSpec{4.0, culling};
    return scenario;
}

// Three teapots 20 m ahead: one in the middle, one 16.8 m to each side, beyond the camera's
// frustum there and inside one eye's. A culler given the camera's frustum, or the left eye's for
// the right eye, leaves a side teapot out: the zero error below is what that would break.
Scenario sideTeapots(StereoCulling culling) {
    return teapotsAt({{0.0, -20.0, 1.0}, {-16.8, -20.0, 1.0}, {16.8, -20.0, 1.0}}, culling);
}

TEST(Stereo, AnObjectOnlyOneEyeSeesIsDrawnForThatEye) {
    for (const StereoCulling culling : {StereoCulling::Enclosing, StereoCulling::PerEye}) {
        // masked rasterises one eye's depth: per eye only.
        const BenchOptions options =
            culling == StereoCulling::PerEye
                ? stereoBench({"vfc", "stop-and-wait", "statistical", "chc", "masked"})
                : stereoBench({"vfc", "stop-and-wait", "statistical", "chc"});
        const BenchResult stereo = runBenchmark(sideTeapots(culling), options);
        testing::expectNoErrorAndNoMiss(stereo);
        for (const RunRecord& run : stereo.runs) {
            for (const FrameStats& f : run.frames) {
                EXPECT_EQ(f.visible_objects, 3) << run.summary.label << " frame " << f.frame;
                EXPECT_EQ(f.left_error_pixels, 0);
                EXPECT_EQ(f.right_error_pixels, 0);
            }
        }
    }
    Scenario mono = sideTeapots(StereoCulling::Enclosing);
    mono.stereo.reset();
    for (const RunRecord& run : runBenchmark(mono, stereoBench({"vfc", "chc"})).runs) {
        EXPECT_EQ(run.frames[0].visible_objects, 1) << "the camera alone sees the middle one";
    }
}

// masked (a software depth buffer of one eye) and the oracles cull each eye apart: each eye's
// instance rasterises that eye's view, each eye's oracle draws what ground truth shows that eye.
TEST(Stereo, MaskedAndTheOraclesCullEachEyeApart) {
    const BenchOptions options = stereoBench({"masked", "ideal", "ideal-box"});
    for (const double separation : {0.064, 4.0}) {
        const BenchResult stereo =
            runBenchmark(stereoCity(separation, StereoCulling::PerEye), options);
        testing::expectNoErrorAndNoMiss(stereo);
        for (const RunRecord& run : stereo.runs) {
            for (const FrameStats& f : run.frames) {
                EXPECT_EQ(f.left_error_pixels, 0) << run.summary.label << " frame " << f.frame;
                EXPECT_EQ(f.right_error_pixels, 0) << run.summary.label << " frame " << f.frame;
            }
        }
    }
    // The side teapots: each eye sees the middle one and its own side's. Each eye's oracle draws
    // those two (four draws a frame); given both eyes' ground truth it would draw three each.
    const BenchResult teapots =
        runBenchmark(sideTeapots(StereoCulling::PerEye), stereoBench({"ideal"}));
    testing::expectNoErrorAndNoMiss(teapots);
    for (const FrameStats& f : teapots.runs.at(0).frames) {
        EXPECT_EQ(f.objects_drawn, 4u) << "frame " << f.frame;
    }
}

// Each eye's error is counted in its own half: `async` (one query per object, an earlier frame's
// answer, not conservative) misses pixels as the eyes move when answers come 100 commands late; the
// two halves add up to the frame's error on every frame, and both eyes have some.
TEST(Stereo, EachEyesErrorIsItsHalfOfTheFrames) {
    BenchOptions options = stereoBench({"async"});
    options.frames.reset();         // the whole walk: the camera turns late in it
    options.latency = {true, 100};  // answers come late: async draws on stale ones
    const BenchResult stereo = runBenchmark(stereoCity(4.0, StereoCulling::PerEye), options);
    int64_t left = 0, right = 0;
    for (const RunRecord& run : stereo.runs) {
        for (const FrameStats& f : run.frames) {
            ASSERT_GE(f.left_error_pixels, 0);
            ASSERT_GE(f.right_error_pixels, 0);
            EXPECT_EQ(f.left_error_pixels + f.right_error_pixels, f.error_pixels)
                << run.summary.label << " frame " << f.frame;
            left += f.left_error_pixels;
            right += f.right_error_pixels;
        }
    }
    EXPECT_GT(left, 0) << "async missed nothing in the left eye: the check above proves little";
    EXPECT_GT(right, 0) << "async missed nothing in the right eye: the check above proves little";
}

TEST(Stereo, TheSameScenarioGivesTheSameDecisionsTwice) {
    const BenchOptions options = stereoBench({"statistical", "chc"});
    const BenchResult a = runBenchmark(stereoCity(0.064, StereoCulling::PerEye), options);
    const BenchResult b = runBenchmark(stereoCity(0.064, StereoCulling::PerEye), options);
    ASSERT_EQ(a.runs.size(), b.runs.size());
    for (size_t r = 0; r < a.runs.size(); ++r) {
        for (size_t f = 0; f < a.runs[r].frames.size(); ++f) {
            EXPECT_EQ(a.runs[r].frames[f].objects_drawn, b.runs[r].frames[f].objects_drawn);
            EXPECT_EQ(a.runs[r].frames[f].queries, b.runs[r].frames[f].queries);
        }
    }
}

// A low sun over the stereo city, eyes 4 m apart: the light's box holds both eyes' frusta, and
// the receiver mask takes each eye's receivers through that eye's view, so light-frustum culling,
// the receiver mask, the cullers in the light's view and both together leave no shadow pixel of
// either eye lit; the mask draws fewer casters than light-frustum culling. In both culling modes:
// per eye, each eye's half is shaded with what that eye's pass drew (leaving the right eye's half
// unshaded fails here, shading it with the left eye's set fails the test below: checked by
// mutation).
TEST(Stereo, TheShadowPassServesBothEyes) {
    for (const StereoCulling culling : {StereoCulling::Enclosing, StereoCulling::PerEye}) {
        SCOPED_TRACE(culling == StereoCulling::PerEye ? "per eye" : "enclosing");
        int64_t frustum_casters = 0;
        for (const ShadowCasterCulling casters :
             {ShadowCasterCulling::LightFrustum, ShadowCasterCulling::Culler,
              ShadowCasterCulling::ReceiverMask, ShadowCasterCulling::CullerWithReceiverMask}) {
            Scenario scenario = stereoCity(4.0, culling);
            LightSpec sun;
            sun.direction = glm::normalize(glm::dvec3(1.0, -0.35, 0.25));
            sun.shadow_map = 1024;
            scenario.lights.push_back(sun);
            BenchOptions options = stereoBench({"vfc", "chc"});
            options.shadow_casters = casters;
            const BenchResult lit = runBenchmark(scenario, options);
            testing::expectNoErrorAndNoMiss(lit);
            int64_t seen = 0, drawn = 0;
            for (const RunRecord& run : lit.runs) {
                for (const FrameStats& f : run.frames) {
                    EXPECT_EQ(f.shadow_error_pixels, 0)
                        << run.summary.label << " frame " << f.frame;
                    EXPECT_EQ(f.missed_casters, 0) << run.summary.label << " frame " << f.frame;
                    // No pixel left unshaded: where the two maps agree, a pixel the shading
                    // pass missed (an eye's half shaded with the other eye's set) reads as a tie.
                    EXPECT_EQ(f.shadow_tie_pixels, 0) << run.summary.label << " frame " << f.frame;
                    seen += f.shadow_seen_casters;
                    drawn += f.shadow_casters;
                }
            }
            EXPECT_GT(seen, 0) << "ground truth shows no shadow: the check above proves nothing";
            if (casters == ShadowCasterCulling::LightFrustum) frustum_casters = drawn;
            if (casters == ShadowCasterCulling::ReceiverMask) {
                EXPECT_LT(drawn, frustum_casters);
            }
        }
    }
}

// A sun low from +x; a teapot only the right eye sees (16.8 m to the right, 20 m ahead) lies in
// the shadow of a large one neither eye sees (30 m to the right), a teapot 30 m ahead for both
// eyes. The receiver mask must take the right eye's receivers too: from the left eye's alone it
// would leave the large caster out (checked by mutation), and its shadow would be lost.
TEST(Stereo, ACasterWhoseShadowOnlyOneEyeSeesIsDrawn) {
    for (const StereoCulling culling : {StereoCulling::Enclosing, StereoCulling::PerEye}) {
        SCOPED_TRACE(culling == StereoCulling::PerEye ? "per eye" : "enclosing");
        Scenario scenario =
            teapotsAt({{0.0, -30.0, 1.0}, {16.8, -20.0, 1.0}, {30.0, -20.0, 4.0}}, culling);
        LightSpec sun;
        sun.direction = glm::normalize(glm::dvec3(-1.0, -0.05, 0.0));
        sun.shadow_map = 1024;
        scenario.lights.push_back(sun);
        for (const ShadowCasterCulling casters :
             {ShadowCasterCulling::ReceiverMask, ShadowCasterCulling::CullerWithReceiverMask}) {
            BenchOptions options = stereoBench({"vfc", "chc"});
            options.shadow_casters = casters;
            const BenchResult lit = runBenchmark(scenario, options);
            testing::expectNoErrorAndNoMiss(lit);
            for (const RunRecord& run : lit.runs) {
                for (const FrameStats& f : run.frames) {
                    EXPECT_GT(f.shadow_seen_casters, 0) << "the large teapot's shadow shows";
                    EXPECT_EQ(f.shadow_error_pixels, 0)
                        << run.summary.label << " frame " << f.frame;
                    EXPECT_EQ(f.missed_casters, 0) << run.summary.label << " frame " << f.frame;
                    // The shadowed teapot only the right eye draws is shaded in its half.
                    EXPECT_EQ(f.shadow_tie_pixels, 0) << run.summary.label << " frame " << f.frame;
                }
            }
        }
    }
}

TEST(Stereo, WhatStereoDoesNotTakeYetIsRefusedWithOneLine) {
    auto refusal = [](Scenario scenario, const char* culler, BenchOptions options) {
        options.algorithms = {findCuller(culler)};
        try {
            runBenchmark(scenario, options);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const BenchOptions options = stereoBench({});
    for (const StereoCulling culling : {StereoCulling::Enclosing, StereoCulling::PerEye}) {
        for (const char* culler : {"hzb", "raster"}) {
            const std::string line = refusal(stereoCity(0.064, culling), culler, options);
            EXPECT_NE(line.find("cannot cull a stereo view yet"), std::string::npos)
                << culler << ": " << line;
            EXPECT_EQ(line.find('\n'), std::string::npos);
        }
    }
    const std::string masked =
        refusal(stereoCity(0.064, StereoCulling::Enclosing), "masked", options);
    EXPECT_NE(masked.find("in one enclosing pass"), std::string::npos) << masked;
    EXPECT_NE(masked.find("per_eye"), std::string::npos) << masked;
    EXPECT_EQ(refusal(stereoCity(0.064, StereoCulling::PerEye), "masked", options), "");
    EXPECT_EQ(refusal(stereoCity(0.064, StereoCulling::PerEye), "ideal", options), "");
    EXPECT_EQ(refusal(stereoCity(0.064, StereoCulling::Enclosing), "ideal", options), "")
        << "the oracle draws what either eye sees";
    BenchOptions receivers = options;
    receivers.shadow_casters = ShadowCasterCulling::ReceiverMask;
    EXPECT_EQ(refusal(stereoCity(0.064, StereoCulling::PerEye), "vfc", receivers), "");
    EXPECT_EQ(refusal(stereoCity(0.064, StereoCulling::Enclosing), "vfc", receivers), "");
    BenchOptions record = options;
    record.record_objects = true;
    EXPECT_EQ(refusal(stereoCity(0.064, StereoCulling::PerEye), "vfc", record), "")
        << "each eye's decisions are recorded in a table of its own";
}

}  // namespace
}  // namespace occsim
