// Lights and stereo from the command line (docs/views.md): a bad light in a scenario, or a point
// light in its glTF file, is one line naming the file and the place, exit 2, nothing written; a
// run with a good light and stereo runs and says once what it renders of them (a shadow pass, two
// eyes); --sun lights any scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"
#include "gltf_builder.h"

using namespace occsim::cli_run;
using nlohmann::json;

namespace {

// The small teapot scenario, without its expectations, with `edit` applied, written to `dir`.
std::filesystem::path smallWith(const std::filesystem::path& dir,
                                const std::function<void(json&)>& edit) {
    std::ifstream in(kSmall);
    json s = json::parse(in);
    s.erase("expect");
    s["frames"] = 3;
    s["warmup_frames"] = 0;
    edit(s);
    std::filesystem::create_directories(dir);
    const auto file = dir / "lit.json";
    std::ofstream(file) << s.dump(2);
    return file;
}

TEST(CliViews, ALightWithoutADirectionIsOneLineWithExitCode2AndWritesNothing) {
    const auto dir = tempPath("views-bad");
    const auto file = smallWith(dir, [](json& s) {
        s["lights"] = {{{"type", "directional"}, {"direction", {0, 0, 0}}}};
    });
    const auto out = dir / "out";
    const Outcome o = runOccsim("bench " + file.string() + " --algos vfc --out " + out.string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("lit.json: /lights/0/direction: expected a non-zero direction"),
              std::string::npos)
        << o.output;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(CliViews, APointLightInAGltfFileIsOneLineWithExitCode2) {
    const auto dir = tempPath("views-point");
    occsim::testing_gltf::GltfBuilder b;
    b.node({{"mesh", b.triangleMesh("Tri")}});
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.doc()["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}}}}}}};
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "lamp.gltf") << b.text();
    const auto file = smallWith(dir, [](json& s) {
        s["scene"]["sources"].push_back({{"type", "gltf"}, {"path", "lamp.gltf"}});
    });
    const Outcome o =
        runOccsim("bench " + file.string() + " --algos vfc --out " + (dir / "out").string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("lamp.gltf: light 0 is a point light"), std::string::npos) << o.output;
}

TEST(CliViews, ARunWithAGoodLightSaysOnceWhatItRendersOfIt) {
    const auto dir = tempPath("views-good");
    const auto file = smallWith(dir, [](json& s) {
        s["lights"] = {{{"type", "directional"}, {"direction", {0.3, -1, 0.2}}}};
        s["stereo"] = {{"eye_separation", 0.065}};
    });
    const Outcome o =
        runOccsim("bench " + file.string() + " --algos vfc --out " + (dir / "out").string());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    // The note is wrapped to the terminal's width: read it unwrapped.
    std::string text;
    for (size_t i = 0; i < o.output.size(); ++i) {
        if (o.output[i] == '\n' && o.output.compare(i + 1, 2, "  ") == 0) {
            text += ' ';
            i += 2;
        } else {
            text += o.output[i];
        }
    }
    const std::string note = "light 0 renders a shadow pass drawing every object in its box";
    const size_t at = text.find(note);
    EXPECT_NE(at, std::string::npos) << o.output;
    EXPECT_EQ(text.find(note, at + 1), std::string::npos) << "once";
    EXPECT_NE(text.find("stereo renders two eyes of"), std::string::npos) << o.output;
}

// A stereo scenario culled per eye, from the command line with the error measured: summary.json
// names the stereo, frames.csv has each eye's error (zero for chc); --stereo gives any scene two
// eyes; a bad --stereo, and a culler stereo does not take yet, is one line, exit 2, nothing
// written.
TEST(CliViews, AStereoRunWritesEachEyesErrorAndRefusesWhatItCannotCullYet) {
    const auto dir = tempPath("views-stereo");
    const auto file = smallWith(dir, [](json& s) {
        s["stereo"] = {{"eye_separation", 0.065}, {"culling", "per_eye"}};
    });
    const auto out = dir / "out";
    const Outcome o =
        runOccsim("bench " + file.string() + " --algos vfc,chc --error --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::ifstream in(out / "summary.json");
    const json summary = json::parse(in);
    EXPECT_EQ(summary["scenario"]["stereo"]["culling"], "per_eye") << summary["scenario"].dump();
    EXPECT_EQ(summary["scenario"]["stereo"]["eye_separation_m"], 0.065);
    std::ifstream csv(out / "frames.csv");
    std::string header, row;
    std::getline(csv, header);
    EXPECT_EQ(header.substr(header.size() - 36), "left_error_pixels,right_error_pixels");
    size_t rows = 0;
    while (std::getline(csv, row)) {
        ++rows;
        EXPECT_EQ(row.substr(row.size() - 4), ",0,0") << row;
    }
    EXPECT_EQ(rows, 6u) << "two configurations, three frames";

    // --stereo gives any scene two eyes, in place of the scenario's; a bad one is one line.
    const auto flagged = dir / "flagged";
    const Outcome f = runOccsim(
        "run " + kSmall + " --algo chc --error --frames 3 --stereo 1.5 --out " + flagged.string());
    ASSERT_EQ(f.exit_code, 0) << f.output;
    std::ifstream flagged_in(flagged / "summary.json");
    const json flagged_summary = json::parse(flagged_in);
    EXPECT_EQ(flagged_summary["scenario"]["stereo"]["culling"], "enclosing");
    EXPECT_EQ(flagged_summary["scenario"]["stereo"]["eye_separation_m"], 1.5);
    EXPECT_EQ(flagged_summary["algorithms"][0]["error"]["pixels_total"], 0);
    const Outcome bad_flag = runOccsim("run " + kSmall + " --algo chc --stereo 0.06,both --out " +
                                       (dir / "bad-flag").string());
    EXPECT_EQ(bad_flag.exit_code, 2) << bad_flag.output;
    EXPECT_EQ(lineCount(bad_flag.output), 1u) << bad_flag.output;
    EXPECT_NE(bad_flag.output.find("--stereo: expected SEPARATION[,MODE]"), std::string::npos)
        << bad_flag.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad-flag"));

    const auto refused = dir / "refused";
    const Outcome bad =
        runOccsim("bench " + file.string() + " --algos hzb --out " + refused.string());
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_EQ(lineCount(bad.output), 1u) << bad.output;
    EXPECT_NE(bad.output.find("culler 'hzb' cannot cull a stereo view yet"), std::string::npos)
        << bad.output;
    EXPECT_FALSE(std::filesystem::exists(refused));
}

// --sun lights any scene without a copy of its file: the run renders its shadow pass, measures
// its error (light-frustum culling misses nothing) and says so once; a sun below the horizon is
// one line naming the flag, exit 2, nothing written.
TEST(CliViews, TheSunFlagLightsAnySceneAndABadOneIsOneLine) {
    const auto dir = tempPath("views-sun");
    const auto out = dir / "out";
    const Outcome bad =
        runOccsim("bench " + kSmall + " --algos vfc --sun -5,40 --out " + out.string());
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_EQ(lineCount(bad.output), 1u) << bad.output;
    EXPECT_NE(bad.output.find("--sun: expected ELEVATION,AZIMUTH[,SHADOW_MAP]"), std::string::npos)
        << bad.output;
    EXPECT_FALSE(std::filesystem::exists(out));

    const Outcome o =
        runOccsim("bench " + kSmall + " --algos vfc,chc --sun 25,40,512 --error --frames 8 --out " +
                  out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("light 0 renders a shadow pass"), std::string::npos) << o.output;
    std::ifstream in(out / "summary.json");
    const json summary = json::parse(in);
    for (const json& a : summary["algorithms"]) {
        const json& shadow = a["shadow_pass"];
        ASSERT_TRUE(shadow.is_object()) << a.dump();
        EXPECT_GT(shadow["casters_per_frame"].get<double>(), 0.0);
        EXPECT_EQ(shadow["missed_casters_total"], 0);
        EXPECT_EQ(shadow["error_pixels_total"], 0);
    }
}

// --shadow-casters: receivers runs the receiver-masked shadow pass (said in the note, no caster
// missed); a value it does not know, or a culler whose draws the device decides, is one line
// naming it, exit 2.
TEST(CliViews, ShadowCastersReceiversRunsAndABadValueIsOneLine) {
    const auto dir = tempPath("views-receivers");
    const auto out = dir / "out";
    const Outcome bad = runOccsim("bench " + kSmall + " --algos vfc --sun 30,40 --shadow-casters " +
                                  "light --out " + out.string());
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_EQ(lineCount(bad.output), 1u) << bad.output;
    EXPECT_NE(bad.output.find("--shadow-casters: expected frustum, receivers, culler or "
                              "culler+receivers, got 'light'"),
              std::string::npos)
        << bad.output;
    const Outcome gpu =
        runOccsim("bench " + kSmall +
                  " --algos raster --sun 30,40 --shadow-casters receivers --out " + out.string());
    EXPECT_EQ(gpu.exit_code, 2) << gpu.output;
    EXPECT_NE(gpu.output.find("culler 'raster' draws from the device"), std::string::npos)
        << gpu.output;
    EXPECT_FALSE(std::filesystem::exists(out));

    const Outcome o = runOccsim("bench " + kSmall +
                                " --algos vfc --sun 30,40,512 --shadow-casters receivers --error "
                                "--frames 8 --out " +
                                out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("(receiver-masked)"), std::string::npos) << o.output;
    std::ifstream in(out / "summary.json");
    const json shadow = json::parse(in)["algorithms"][0]["shadow_pass"];
    ASSERT_TRUE(shadow.is_object());
    EXPECT_EQ(shadow["missed_casters_total"], 0);
    EXPECT_EQ(shadow["error_pixels_total"], 0);
    ASSERT_TRUE(shadow["shading_pass"].is_object()) << shadow.dump();
    EXPECT_GE(shadow["shading_pass"]["cpu_ms_mean"].get<double>(), 0.0);
}

// --shadow-casters culler and culler+receivers: each configuration's culler culls the light's
// view (said in the note, no caster missed, no shadow error); a culler that cannot cull a light's
// view yet is refused before any frame with a line naming it, exit 2, nothing written.
TEST(CliViews, ShadowCastersCullerRunsEachCullerInTheLightsView) {
    const auto dir = tempPath("views-culler");
    const auto out = dir / "out";
    const Outcome refused =
        runOccsim("bench " + kSmall + " --algos hzb --sun 20,40 --shadow-casters culler --out " +
                  out.string());
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_EQ(lineCount(refused.output), 1u) << refused.output;
    EXPECT_NE(refused.output.find("culler 'hzb' cannot cull a light's view yet"), std::string::npos)
        << refused.output;
    EXPECT_FALSE(std::filesystem::exists(out));

    for (const std::string mode : {"culler", "culler+receivers"}) {
        const Outcome o =
            runOccsim("bench " + kSmall + " --algos vfc,chc --sun 20,40,512 " +
                      "--shadow-casters " + mode + " --error --frames 8 --out " + out.string());
        ASSERT_EQ(o.exit_code, 0) << o.output;
        EXPECT_NE(o.output.find("culls in the light's view"), std::string::npos) << o.output;
        EXPECT_EQ(o.output.find("leaving out those that may shadow nothing") != std::string::npos,
                  mode == "culler+receivers")
            << o.output;
        std::ifstream in(out / "summary.json");
        const json summary = json::parse(in);
        ASSERT_EQ(summary["algorithms"].size(), 2u);
        for (const json& algorithm : summary["algorithms"]) {
            const json& shadow = algorithm["shadow_pass"];
            ASSERT_TRUE(shadow.is_object()) << algorithm.dump();
            EXPECT_GT(shadow["casters_per_frame"].get<double>(), 0.0);
            EXPECT_EQ(shadow["missed_casters_total"], 0);
            EXPECT_EQ(shadow["error_pixels_total"], 0);
            // The light view's queries: chc's, none for vfc.
            EXPECT_EQ(shadow["queries_per_frame"].get<double>() > 0.0,
                      algorithm["configuration"] == "chc")
                << algorithm.dump();
        }
    }
}
}  // namespace
