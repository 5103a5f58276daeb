// Regression runs catch what they exist to catch: dropped pixels, slower culling, changed
// decisions; and they are reproducible, shardable and strict about their inputs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>

#include "culling/cullers/statistical_culler.h"
#include "sim/output/error_picture.h"
#include "sim/output/run_folder.h"
#include "sim/regress/history.h"
#include "sim/regress/merge.h"
#include "sim/run/stop_request.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

// A copy of the small teapot scenario in a fresh folder, with a shorter run and the given expect.
fs::path makeScenario(const std::string& name, const nlohmann::json& expect, uint32_t frames = 16) {
    const fs::path dir =
        fs::temp_directory_path() / ("occsim-regress-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ifstream in(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json");
    nlohmann::json scenario = nlohmann::json::parse(in);
    scenario["name"] = name;
    scenario["frames"] = frames;
    scenario["warmup_frames"] = 2;
    if (expect.is_null()) {
        scenario.erase("expect");
    } else {
        scenario["expect"] = expect;
    }
    const fs::path file = dir / (name + ".json");
    std::ofstream(file) << scenario.dump(2);
    return file;
}

// Forwards to another device, dropping every n-th object draw: a culler that loses visible
// objects now and then.
class DroppingDevice final : public RenderDevice {
  public:
    DroppingDevice(RenderDevice& inner, uint32_t every) : inner_(inner), every_(every) {}
    void drawObject(uint32_t object) override {
        if (++draws_ % every_ != 0) inner_.drawObject(object);
    }
    using RenderDevice::issueQuery;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> tags) override {
        return inner_.issueQuery(boxes, tags);
    }
    bool isQueryReady(QueryId id) override { return inner_.isQueryReady(id); }
    QueryAnswer takeAnswer(QueryId id) override { return inner_.takeAnswer(id); }

  private:
    RenderDevice& inner_;
    uint32_t every_;
    uint64_t draws_ = 0;
};

enum class Sabotage { DropDraws, Slow, ExtraQuery, DropFromFrame10, SlowFromFrame10 };

// The clock these regression runs time their frames with (RegressOptions::frame_clock_ms): each
// reading is 1 ms after the one before, so that every culler's frame takes the same scripted
// time whatever the machine's load, and a slowed culler adds 60 ms to it.
double g_scripted_ms = 0.0;
double scriptedClockMs() { return g_scripted_ms += 1.0; }
void scriptedSlowDown() { g_scripted_ms += 60.0; }

// The statistical culler, deliberately broken in one way.
class SabotagedCuller final : public Culler {
  public:
    explicit SabotagedCuller(Sabotage how) : how_(how) {}
    void reset(const BspTree& tree) override { inner_.reset(tree); }
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override {
        switch (how_) {
            case Sabotage::DropDraws: {
                DroppingDevice dropping(device, 5);
                inner_.cullAndRender(tree, frame, dropping);
                return;
            }
            case Sabotage::Slow:
                scriptedSlowDown();
                break;
            case Sabotage::ExtraQuery:
                device.takeAnswer(device.issueQuery(tree.bounds(tree.root())));
                break;
            case Sabotage::DropFromFrame10:
                if (frame.frame_index >= 10) {
                    DroppingDevice dropping(device, 5);
                    inner_.cullAndRender(tree, frame, dropping);
                    return;
                }
                break;
            case Sabotage::SlowFromFrame10:
                if (frame.frame_index >= 10) scriptedSlowDown();
                break;
        }
        inner_.cullAndRender(tree, frame, device);
    }

  private:
    Sabotage how_;
    StatisticalCuller inner_;
};

RegressOptions optionsFor(const fs::path& scenario,
                          std::optional<Sabotage> sabotage = std::nullopt) {
    RegressOptions o;
    o.inputs = {scenario};
    o.out_dir = scenario.parent_path() / "out";
    o.frame_clock_ms = scriptedClockMs;
    if (sabotage) {
        o.make_culler = [how = *sabotage](const CullerRow& algorithm,
                                          const CullerOptions& options) {
            if (algorithm.name == "statistical")
                return std::unique_ptr<Culler>(new SabotagedCuller(how));
            return makeCuller(algorithm, options);
        };
    }
    return o;
}

const CheckResult* findCheck(const RegressReport& report, const std::string& prefix) {
    for (const CheckResult& c : report.scenarios.at(0).checks) {
        if (c.check.rfind(prefix, 0) == 0) return &c;
    }
    return nullptr;
}

const nlohmann::json kExpect = {{"algorithms", {"vfc", "statistical"}},
                                {"deterministic_latency", 6}};

TEST(Regress, PassesAfterUpdateAndBaselineIsRewrittenAtomically) {
    const fs::path file = makeScenario("passes", kExpect);
    RegressOptions o = optionsFor(file);
    EXPECT_FALSE(runRegression(o).passed()) << "no baseline yet";
    o.update = true;
    const RegressReport updated = runRegression(o);
    EXPECT_TRUE(updated.passed());
    EXPECT_NE(updated.scenarios[0].note.find("statistical: new"), std::string::npos);
    EXPECT_TRUE(fs::exists(file.parent_path() / "passes.baseline.json"));
    o.update = false;
    const RegressReport again = runRegression(o);
    EXPECT_TRUE(again.passed()) << again.table();
    for (const auto& entry : fs::directory_iterator(file.parent_path())) {
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    }
}

// A baseline records where it was made; a run elsewhere says so beside its checks (the counts
// themselves must not depend on it), and a failing check names the difference.
TEST(Regress, ABaselineFromAnotherBackendOrRendererIsNamed) {
    const fs::path file = makeScenario("elsewhere", kExpect);
    RegressOptions o = optionsFor(file);
    o.update = true;
    runRegression(o);
    const fs::path baseline = file.parent_path() / "elsewhere.baseline.json";
    nlohmann::json b = nlohmann::json::parse(std::ifstream(baseline));
    EXPECT_EQ(b["backend"], "egl");
    EXPECT_NE(b["renderer"].get<std::string>().find("llvmpipe"), std::string::npos) << b.dump();
    o.update = false;
    EXPECT_TRUE(runRegression(o).scenarios[0].note.empty()) << "same backend, nothing to say";

    b["backend"] = "osmesa";
    b["renderer"] = "Some GPU";
    std::ofstream(baseline) << b.dump();
    const RegressReport same_counts = runRegression(o);
    EXPECT_TRUE(same_counts.passed()) << same_counts.table();
    EXPECT_NE(same_counts.scenarios[0].note.find(
                  "baseline made on osmesa (Some GPU), this run on egl (llvmpipe"),
              std::string::npos)
        << same_counts.scenarios[0].note;

    b["algorithms"]["statistical"]["queries"][3] = 99999;
    std::ofstream(baseline) << b.dump();
    const RegressReport failed = runRegression(o);
    const CheckResult* queries = findCheck(failed, "queries per frame = baseline: statistical");
    ASSERT_NE(queries, nullptr);
    EXPECT_FALSE(queries->passed);
    EXPECT_NE(queries->got.find("[baseline made on osmesa (Some GPU), this run on egl"),
              std::string::npos)
        << queries->got;
}

TEST(Regress, ACullerThatDropsVisibleObjectsFailsWithErrorPixelsAndAPicture) {
    const fs::path file = makeScenario("drops", kExpect);
    const RegressReport report = runRegression(optionsFor(file, Sabotage::DropDraws));
    EXPECT_FALSE(report.passed());
    const CheckResult* zero = findCheck(report, "zero error pixels: statistical");
    ASSERT_NE(zero, nullptr);
    EXPECT_FALSE(zero->passed);
    EXPECT_NE(zero->got.find("px on"), std::string::npos) << zero->got;
    ASSERT_FALSE(report.scenarios[0].captures.empty());
    EXPECT_TRUE(fs::exists(report.scenarios[0].captures[0]));
    const CheckResult* vfc = findCheck(report, "zero error pixels: vfc");
    ASSERT_NE(vfc, nullptr);
    EXPECT_TRUE(vfc->passed);
    EXPECT_NE(vfc->got.find("tie px)"), std::string::npos) << "ties are shown apart: " << vfc->got;
    const CheckResult* missed = findCheck(report, "no missed objects: statistical");
    ASSERT_NE(missed, nullptr);
    EXPECT_FALSE(missed->passed) << missed->got;
    const CheckResult* vfc_missed = findCheck(report, "no missed objects: vfc");
    ASSERT_NE(vfc_missed, nullptr);
    EXPECT_TRUE(vfc_missed->passed) << vfc_missed->got;
}

// Each scenario's folder is one unit: a rerun that takes no picture leaves none of the last
// run's beside its report.
TEST(Regress, ARerunReplacesTheScenarioFolderWithNoStalePicture) {
    const fs::path file = makeScenario("stale", kExpect);
    const RegressReport dropped = runRegression(optionsFor(file, Sabotage::DropDraws));
    ASSERT_FALSE(dropped.scenarios[0].captures.empty());
    const fs::path picture = dropped.scenarios[0].captures[0];
    ASSERT_TRUE(fs::exists(picture)) << "the picture is named where it is once published";
    const RegressReport clean = runRegression(optionsFor(file));
    EXPECT_TRUE(clean.scenarios[0].captures.empty()) << clean.table();
    EXPECT_FALSE(fs::exists(picture)) << "the last run's picture is still there";
    EXPECT_TRUE(fs::exists(picture.parent_path() / "report.md"));
}

// The width and height a PNG's header gives (IHDR: bytes 16-23, big-endian).
std::pair<uint32_t, uint32_t> pngSize(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    unsigned char header[24] = {};
    in.read(reinterpret_cast<char*>(header), sizeof header);
    auto word = [&](int at) {
        return uint32_t{header[at]} << 24 | uint32_t{header[at + 1]} << 16 |
               uint32_t{header[at + 2]} << 8 | header[at + 3];
    };
    return {word(16), word(20)};
}

// A culler that fails two error checks (zero error, and error pixels against its baseline) gets
// one picture, named once; report.md shows it, and it is large enough to see single pixels: each
// panel of the 200 x 150 frame scaled 4 times, the three one above the other under their labels.
TEST(Regress, AFailingCullersWorstFrameIsOneLargePictureThatReportMdShows) {
    const fs::path file = makeScenario("pictured", kExpect);
    RegressOptions o = optionsFor(file);
    o.update = true;
    runRegression(o);  // the baseline of the intact culler
    const RegressReport report = runRegression(optionsFor(file, Sabotage::DropDraws));
    const CheckResult* zero = findCheck(report, "zero error pixels: statistical");
    const CheckResult* baseline =
        findCheck(report, "error pixels per frame = baseline: statistical");
    ASSERT_NE(zero, nullptr);
    ASSERT_NE(baseline, nullptr);
    EXPECT_FALSE(zero->passed);
    EXPECT_FALSE(baseline->passed) << baseline->got;
    const std::vector<std::string>& captures = report.scenarios[0].captures;
    ASSERT_EQ(captures.size(), 1u) << "one worst frame, one picture";
    const fs::path picture = captures[0];
    EXPECT_EQ(picture.parent_path(), file.parent_path() / "out" / "pictured");

    const auto [width, height] = pngSize(picture);
    EXPECT_EQ(errorPictureScale(200), 4u);
    EXPECT_GE(width, 4u * 200) << "each frame pixel a 4 x 4 square";
    EXPECT_GE(height, 3u * 4 * 150) << "three panels one above the other";
    EXPECT_LT(height, 3u * (4 * 150 + 40)) << "and a label strip each";

    std::ifstream in(picture.parent_path() / "report.md");
    const std::string md{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::string name = picture.filename().string();
    EXPECT_NE(md.find("![" + name + "](" + name + ")"), std::string::npos) << md;
    EXPECT_NE(md.find("## Worst frames"), std::string::npos) << md;
}

TEST(Regress, ASlowedCullerFailsTheRatioCheck) {
    nlohmann::json expect = kExpect;
    expect["ratios"] = {
        {{"algorithm", "statistical"}, {"reference", "vfc"}, {"max", 1.0}, {"tolerance", 0.5}}};
    const fs::path file = makeScenario("slow", expect);
    const RegressReport fair = runRegression(optionsFor(file));
    const CheckResult* fair_ratio = findCheck(fair, "frame time statistical / vfc");
    ASSERT_NE(fair_ratio, nullptr);
    EXPECT_TRUE(fair_ratio->passed) << fair_ratio->got;
    const RegressReport slow = runRegression(optionsFor(file, Sabotage::Slow));
    const CheckResult* ratio = findCheck(slow, "frame time statistical / vfc");
    ASSERT_NE(ratio, nullptr);
    EXPECT_FALSE(ratio->passed) << ratio->got;
}

// makeScenario's scenario (16 frames, 2 of warm-up) with two segments: frames 2 to 9 and 10 to 15.
fs::path makeSegmentedScenario(const std::string& name, const nlohmann::json& expect) {
    const fs::path file = makeScenario(name, nullptr);
    nlohmann::json scenario = nlohmann::json::parse(std::ifstream(file));
    scenario["segments"] = nlohmann::json::parse(R"([
        {"name": "calm", "from_frame": 2, "to_frame": 10},
        {"name": "late", "from_frame": 10, "to_frame": 16}])");
    scenario["expect"] = expect;
    std::ofstream(file) << scenario.dump(2);
    return file;
}

// A check scoped to a segment judges that segment's frames only: a culler slow from frame 10 on
// passes its ratio over the calm segment and fails it over the late one, by name.
TEST(Regress, ARatioCheckOverASegmentFailsOnlyWhereItsBoundIsBroken) {
    nlohmann::json expect = kExpect;
    for (const char* segment : {"calm", "late"}) {
        expect["ratios"].push_back({{"algorithm", "statistical"},
                                    {"reference", "vfc"},
                                    {"max", 1.0},
                                    {"tolerance", 0.5},
                                    {"segment", segment}});
    }
    const fs::path file = makeSegmentedScenario("segment-ratio", expect);
    const RegressReport slow = runRegression(optionsFor(file, Sabotage::SlowFromFrame10));
    const CheckResult* calm = findCheck(slow, "frame time statistical / vfc in segment calm");
    const CheckResult* late = findCheck(slow, "frame time statistical / vfc in segment late");
    ASSERT_NE(calm, nullptr);
    ASSERT_NE(late, nullptr);
    EXPECT_TRUE(calm->passed) << calm->got;
    EXPECT_FALSE(late->passed) << late->got;
    // report.md has the segment tables the checks read.
    std::ifstream in(file.parent_path() / "out" / "segment-ratio" / "report.md");
    const std::string md{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_NE(md.find("### late: frames 10 to 15"), std::string::npos) << md;
}

// Zero error over a segment: a culler that drops draws from frame 10 on is exact over the calm
// segment and fails over the late one, with a picture of its worst frame (which lies in it).
TEST(Regress, AZeroErrorCheckOverASegmentFailsOnlyOverTheSegmentWithTheError) {
    nlohmann::json expect = kExpect;
    expect["zero_error"] = nlohmann::json::parse(R"(["vfc",
        {"algorithm": "statistical", "segment": "calm"},
        {"algorithm": "statistical", "segment": "late"}])");
    expect["max_error_pixels"] =
        nlohmann::json::parse(R"([{"algorithm": "statistical", "max": 0, "segment": "calm"}])");
    const fs::path file = makeSegmentedScenario("segment-error", expect);
    const RegressReport report = runRegression(optionsFor(file, Sabotage::DropFromFrame10));
    const CheckResult* calm = findCheck(report, "zero error pixels in segment calm: statistical");
    const CheckResult* late = findCheck(report, "zero error pixels in segment late: statistical");
    const CheckResult* bound = findCheck(report, "error pixels per frame in segment calm");
    const CheckResult* missed = findCheck(report, "no missed objects in segment late: statistical");
    ASSERT_NE(calm, nullptr);
    ASSERT_NE(late, nullptr);
    ASSERT_NE(bound, nullptr);
    ASSERT_NE(missed, nullptr);
    EXPECT_TRUE(calm->passed) << calm->got;
    EXPECT_TRUE(bound->passed) << bound->got;
    EXPECT_FALSE(late->passed) << late->got;
    EXPECT_FALSE(missed->passed) << missed->got;
    EXPECT_EQ(late->expected, "0 on frames 10 to 15");
    ASSERT_EQ(report.scenarios[0].captures.size(), 1u);
    EXPECT_TRUE(fs::exists(report.scenarios[0].captures[0]));
}

// With every expected frame inside the warm-up nothing is timed: the ratio check has nothing to
// judge and fails, saying so, instead of passing on 0 / 0.
TEST(Regress, ARatioCheckWithNothingTimedFails) {
    nlohmann::json expect = kExpect;
    expect["frames"] = 2;  // makeScenario's warmup_frames is 2
    expect["ratios"] = {{{"algorithm", "statistical"}, {"reference", "vfc"}, {"max", 1.0}}};
    const RegressReport report = runRegression(optionsFor(makeScenario("untimed", expect)));
    const CheckResult* ratio = findCheck(report, "frame time statistical / vfc");
    ASSERT_NE(ratio, nullptr);
    EXPECT_FALSE(ratio->passed) << ratio->got;
    EXPECT_NE(ratio->got.find("nothing timed"), std::string::npos) << ratio->got;
    EXPECT_FALSE(report.passed());
}

// Each scenario's report.md gives the command that reruns it and lists its check results.
TEST(Regress, TheScenarioReportHasTheRerunCommandAndTheChecks) {
    const fs::path file = makeScenario("report", kExpect, 8);
    RegressOptions o = optionsFor(file);
    o.rerun_flags = {"--culling", "my tuned.json"};
    const RegressReport report = runRegression(o);
    std::ifstream in(o.out_dir / "report" / "report.md");
    const std::string md{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_NE(md.find("```sh\noccsim regress " + file.string() +
                      " --culling 'my tuned.json' --out " + o.out_dir.string() + "\n```"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("## Checks"), std::string::npos) << md;
    EXPECT_NE(md.find("| zero error pixels: vfc | 0 on every frame | 0 ("), std::string::npos)
        << md;
    EXPECT_NE(md.find("| baseline | a readable baseline of this format |"), std::string::npos)
        << md;
    EXPECT_NE(md.find("**FAIL**"), std::string::npos) << "no baseline yet: " << md;
    ASSERT_FALSE(report.scenarios[0].checks.empty());
}

TEST(Regress, AChangedQueryCountFailsTheExactCheckNamingTheFrame) {
    const fs::path file = makeScenario("queries", kExpect);
    RegressOptions o = optionsFor(file);
    o.update = true;
    runRegression(o);
    const RegressReport report = runRegression(optionsFor(file, Sabotage::ExtraQuery));
    const CheckResult* queries = findCheck(report, "queries per frame = baseline: statistical");
    ASSERT_NE(queries, nullptr);
    EXPECT_FALSE(queries->passed);
    EXPECT_NE(queries->expected.find("frame 0"), std::string::npos) << queries->expected;
    const CheckResult* vfc = findCheck(report, "queries per frame = baseline: vfc");
    ASSERT_NE(vfc, nullptr);
    EXPECT_TRUE(vfc->passed);
}

TEST(Regress, DeterministicModeGivesIdenticalCountsOverThreeRuns) {
    const fs::path file = makeScenario("determinism", kExpect);
    std::vector<std::string> baselines;
    for (int run = 0; run < 3; ++run) {
        RegressOptions o = optionsFor(file);
        o.update = true;
        runRegression(o);
        std::ifstream in(file.parent_path() / "determinism.baseline.json");
        baselines.emplace_back(std::istreambuf_iterator<char>(in),
                               std::istreambuf_iterator<char>());
    }
    EXPECT_EQ(baselines[0], baselines[1]);
    EXPECT_EQ(baselines[0], baselines[2]);
}

TEST(Regress, AScenarioWithoutExpectIsSkippedWithANote) {
    const fs::path file = makeScenario("no-expect", nullptr);
    const RegressReport report = runRegression(optionsFor(file));
    ASSERT_EQ(report.scenarios.size(), 1u);
    EXPECT_TRUE(report.scenarios[0].skipped);
    EXPECT_EQ(report.scenarios[0].note, "no expect block");
    EXPECT_TRUE(report.passed());
    EXPECT_NE(junitXml(report).find("<skipped message=\"no expect block\""), std::string::npos);
}

TEST(Regress, MalformedExpectationsFailNamingFileAndKey) {
    nlohmann::json expect = kExpect;
    expect["zero_error"] = {"chc"};
    const fs::path file = makeScenario("bad-expect", expect);
    const RegressReport report = runRegression(optionsFor(file));
    ASSERT_EQ(report.scenarios[0].checks.size(), 1u);
    const std::string& got = report.scenarios[0].checks[0].got;
    EXPECT_NE(got.find("bad-expect.json: /expect/zero_error/0"), std::string::npos) << got;
    expect = kExpect;
    expect["tolerance"] = 0.1;
    const RegressReport unknown = runRegression(optionsFor(makeScenario("bad-expect2", expect)));
    EXPECT_NE(unknown.scenarios[0].checks[0].got.find("/expect/tolerance"), std::string::npos)
        << unknown.scenarios[0].checks[0].got;
}

TEST(Regress, MalformedBaselineFailsNamingFileAndKey) {
    const fs::path file = makeScenario("bad-baseline", kExpect);
    RegressOptions o = optionsFor(file);
    o.update = true;
    runRegression(o);
    const fs::path baseline = file.parent_path() / "bad-baseline.baseline.json";
    nlohmann::json b = nlohmann::json::parse(std::ifstream(baseline));
    b["algorithms"]["vfc"]["queries"] = {1, 2};
    std::ofstream(baseline) << b.dump();
    const RegressReport report = runRegression(optionsFor(file));
    const CheckResult* check = findCheck(report, "baseline");
    ASSERT_NE(check, nullptr);
    EXPECT_FALSE(check->passed);
    EXPECT_NE(check->got.find("bad-baseline.baseline.json: /algorithms/vfc/queries"),
              std::string::npos)
        << check->got;
}

TEST(Regress, BaselineOfAnotherFormatVersionSaysSoInsteadOfComparing) {
    const fs::path file = makeScenario("old-baseline", kExpect);
    RegressOptions o = optionsFor(file);
    o.update = true;
    runRegression(o);
    const fs::path baseline = file.parent_path() / "old-baseline.baseline.json";
    nlohmann::json b = nlohmann::json::parse(std::ifstream(baseline));
    b["version"] = 1;  // before ties were told apart from error
    std::ofstream(baseline) << b.dump();
    const RegressReport report = runRegression(optionsFor(file));
    ASSERT_EQ(report.scenarios[0].checks.back().check, "baseline");
    EXPECT_NE(report.scenarios[0].checks.back().got.find(
                  "baseline format version 1; this program reads version 2"),
              std::string::npos);
    // --update replaces it and says that the old file was not compared.
    const RegressReport rewritten = runRegression(o);
    EXPECT_NE(rewritten.scenarios[0].note.find("the old file was not compared"), std::string::npos)
        << rewritten.scenarios[0].note;
    EXPECT_TRUE(runRegression(optionsFor(file)).passed());
}

TEST(Regress, JunitXmlHasOneTestcasePerCheckAndFailuresWithMessages) {
    const fs::path file = makeScenario("junit", kExpect);
    const RegressReport report = runRegression(optionsFor(file, Sabotage::DropDraws));
    const std::string xml = junitXml(report);
    EXPECT_NE(xml.find("<testsuites name=\"occsim regress\""), std::string::npos);
    EXPECT_NE(
        xml.find("<testcase classname=\"junit\" name=\"zero error pixels: statistical\"><failure"),
        std::string::npos)
        << xml;
    EXPECT_NE(xml.find("<testcase classname=\"junit\" name=\"zero error pixels: vfc\"/>"),
              std::string::npos);
}

// A folder of scenarios as issue 40 found them: a.json named "b" and b.json named "a", the same
// file name in two subfolders, a scenario whose baseline is itself, one whose baseline lies two
// folders up. The last two are refused before any work, one line each; the first two are each
// filed under their own identity through regress, merge and history.
TEST(Regress, ASetWithSwappedNamesSameStemsASelfBaselineAndAnOutsideOneIsCheckedBeforeAnyWork) {
    const fs::path root = makeScenario("identity-seed", kExpect, 4).parent_path();
    const fs::path seed = root / "identity-seed.json";
    nlohmann::json base = nlohmann::json::parse(std::ifstream(seed));
    fs::remove(seed);
    const fs::path set = root / "set";
    auto write = [&](const fs::path& rel, const std::string& name, const std::string& baseline) {
        nlohmann::json j = base;
        j["name"] = name;
        if (!baseline.empty()) j["expect"]["baseline"] = baseline;
        fs::create_directories((set / rel).parent_path());
        std::ofstream(set / rel) << j.dump(2);
    };
    write("a.json", "b", "");
    write("b.json", "a", "");
    write("x/scene.json", "scene", "");
    write("y/scene.json", "scene", "");
    write("self.json", "self", "self.json");
    write("up/up.json", "up", "../../x.json");
    RegressOptions o = optionsFor(set);
    o.inputs = {set};
    o.out_dir = root / "out";
    std::string refused;
    try {
        runRegression(o);
    } catch (const InputError& e) {
        refused = e.what();
    }
    EXPECT_EQ(std::count(refused.begin(), refused.end(), '\n'), 1) << "two problems: " << refused;
    EXPECT_NE(refused.find("self.json: /expect/baseline: " + (set / "self.json").string() +
                           " is the scenario file itself"),
              std::string::npos)
        << refused;
    EXPECT_NE(refused.find("up.json: /expect/baseline:"), std::string::npos) << refused;
    EXPECT_NE(refused.find("lies outside the scenario's folder"), std::string::npos) << refused;
    EXPECT_FALSE(fs::exists(o.out_dir)) << "refused before any work";
    EXPECT_TRUE(fs::exists(set / "self.json"));

    fs::remove(set / "self.json");
    fs::remove_all(set / "up");
    o.update = true;
    runRegression(o);
    o.update = false;
    const RegressReport report = runRegression(o);
    ASSERT_EQ(report.scenarios.size(), 4u);
    std::map<std::string, std::string> name_of;  // id -> name
    for (const ScenarioOutcome& s : report.scenarios) name_of[s.id] = s.name;
    EXPECT_EQ(name_of, (std::map<std::string, std::string>{
                           {"a", "b"}, {"b", "a"}, {"x+scene", "scene"}, {"y+scene", "scene"}}));
    for (const ScenarioOutcome& s : report.scenarios) {
        EXPECT_TRUE(s.passed()) << report.table();
        const nlohmann::json summary =
            nlohmann::json::parse(std::ifstream(o.out_dir / s.id / "summary.json"));
        EXPECT_EQ(summary["scenario"]["id"], s.id);
        EXPECT_EQ(summary["scenario"]["file"], s.scenario);
    }
    // The same set as shards, merged: each summary where its id says, into the history by id.
    const ScenarioSet whole = scenarioSetOf({set});
    std::vector<fs::path> dirs;
    for (uint32_t i = 0; i < 2; ++i) {
        RegressOptions shard = o;
        shard.shard = {i, 2};
        shard.out_dir = root / ("shard-" + std::to_string(i));
        writeShardResult(shard.out_dir,
                         {shard.out_dir, whole, shard.shard, "host", "cpu", runRegression(shard)});
        dirs.push_back(shard.out_dir);
    }
    const MergedRun merged = mergeShards(dirs);
    std::vector<std::pair<std::string, Json>> summaries;
    for (size_t k = 0; k < merged.summaries.size(); ++k) {
        EXPECT_EQ(merged.summaries[k]["scenario"]["id"], merged.report.scenarios[k].id);
        EXPECT_EQ(merged.summaries[k]["scenario"]["name"], merged.report.scenarios[k].name);
        summaries.emplace_back(merged.report.scenarios[k].id, merged.summaries[k]);
    }
    const HistoryEntry entry = historyEntryNow(summaries, "test");
    EXPECT_EQ(entry.scenarios.size(), 4u);
    EXPECT_TRUE(entry.scenarios.count("x+scene") && entry.scenarios.count("y+scene"));
    fs::remove_all(root);
}

// A `run --out` into a scenario's folder of a regress in progress holds that folder's lock; the
// regress, which locks every scenario folder of its share before the first runs, says so and
// runs nothing (and, the other way round, such a run is refused while regress holds them).
TEST(Regress, AScenarioFolderHeldByAnotherRunIsFoundBeforeAnyScenarioRuns) {
    const fs::path file = makeScenario("locked", kExpect, 4);
    RegressOptions o = optionsFor(file);
    o.update = true;
    claimRegressFolder(o.out_dir);  // an earlier regress's folder
    const FolderLock held(o.out_dir / "locked", false);
    EXPECT_THROW(runRegression(o), RunFolderBusy);
    EXPECT_FALSE(fs::exists(file.parent_path() / "locked.baseline.json")) << "nothing ran";
    fs::remove_all(file.parent_path());
}

// Issue 40: a 3-repetition bench of a culler that misses reports the misses of every repetition,
// not their median (deep-depth-small: async misses an object in deterministic-latency mode).
TEST(Regress, AThreeRepetitionBenchOfACullerThatMissesReportsEveryMiss) {
    const Scenario scenario =
        parseScenarioFile(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/deep-depth-small.json");
    BenchOptions bench;
    bench.algorithms = {findCuller("vfc"), findCuller("async")};
    bench.measure_error = true;
    bench.latency = {true, 8};
    bench.repetitions = 3;
    const BenchResult result = runBenchmark(scenario, bench);
    const RunRecord& async = result.runs[1];
    ASSERT_EQ(async.repetitions.size(), 3u);
    const int64_t once = async.repetitions[0].missed_objects_total;
    ASSERT_GT(once, 0) << "the scene no longer makes async miss: pick another";
    EXPECT_EQ(async.summary.missed_objects_total, 3 * once);
    EXPECT_EQ(async.summary.error_pixels_total, 3 * async.repetitions[0].error_pixels_total);
    EXPECT_EQ(async.summary.frames_with_error, 3 * async.repetitions[0].frames_with_error);
    EXPECT_GT(async.summary.error_pixels_mean, 0.0);
}

// "partial" only when frames were lost: a signal after the last frame leaves the run whole; one
// before it keeps the whole frames and says so. In a child process of its own (a death test):
// the stop request, once recorded, stays for the process.
TEST(Stopping, ASignalAfterTheLastFrameLosesNothingAndOneBeforeItMarksThePartialRun) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    auto runSignalledAt = [](uint32_t signal_frame) {
        installStopHandlers();
        Scenario s =
            parseScenarioFile(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json");
        BenchOptions b;
        b.algorithms = {findCuller("vfc")};
        b.frames = 4;
        b.on_frame = [signal_frame](const FrameEvent& e) {
            if (e.frame == signal_frame) std::raise(SIGINT);
        };
        const BenchResult r = runBenchmark(s, b);
        if (stopSignal() != SIGINT) std::exit(9);
        std::exit(r.partial ? static_cast<int>(r.partial->frames_reached) : 0);
    };
    EXPECT_EXIT(runSignalledAt(3), ::testing::ExitedWithCode(0), "") << "after the last frame";
    EXPECT_EXIT(runSignalledAt(1), ::testing::ExitedWithCode(2), "") << "two whole frames kept";
}

// A world that cannot go on (an object beyond finite float coordinates) keeps the frames before
// it, marked partial with the reason, instead of ending the run with nothing written.
TEST(Stopping, AWorldThatLeavesFiniteCoordinatesKeepsTheFramesBeforeIt) {
    Scenario s =
        parseScenarioFile(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json");
    s.movers.resize(1);
    s.movers[0] = MoverSpec{};
    s.movers[0].motion = MotionType::Orbit;
    s.movers[0].fraction = 0.05;
    s.movers[0].radius_min_m = s.movers[0].radius_max_m = 1e39;  // beyond float once it moves
    s.movers[0].speed_min_mps = s.movers[0].speed_max_mps = 1e300;
    BenchOptions b;
    b.algorithms = {findCuller("vfc")};
    b.frames = 6;
    const BenchResult r = runBenchmark(s, b);
    ASSERT_TRUE(r.partial.has_value());
    EXPECT_NE(r.partial->reason.find("the world stopped at frame"), std::string::npos)
        << r.partial->reason;
    EXPECT_NE(r.partial->reason.find("its scale"), std::string::npos) << r.partial->reason;
    EXPECT_EQ(r.runs[0].frames.size(), r.partial->frames_reached);
}

}  // namespace
}  // namespace occsim
