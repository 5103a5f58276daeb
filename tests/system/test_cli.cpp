// The occsim executable as a user meets it: bad input ends with one line and exit code 2, good
// input writes whole files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "shell_command.h"

namespace {

using occsim::testing::Outcome;
using occsim::testing::shell;

Outcome runOccsim(const std::string& args) { return shell(std::string(OCCSIM_EXE) + " " + args); }

const std::string kSmall = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";

std::filesystem::path tempPath(const std::string& name) {
    const auto p = std::filesystem::temp_directory_path() /
                   ("occsim-cli-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(p);
    return p;
}

size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

TEST(Cli, UnknownAlgorithmIsOneLineNamingTheFlagAndTheChoicesWithExitCode2) {
    const Outcome o =
        runOccsim("run " + kSmall + " --algo fastest --out " + tempPath("a").string());
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("--algo"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("statistical"), std::string::npos) << o.output;
    EXPECT_FALSE(std::filesystem::exists(tempPath("a")));
}

TEST(Cli, MissingScenarioFileNamesTheFileWithExitCode2) {
    const Outcome o = runOccsim("bench /no/such/scenario.json");
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("/no/such/scenario.json"), std::string::npos) << o.output;
}

TEST(Cli, MalformedScenarioNamesFileAndPlaceWithExitCode2AndWritesNothing) {
    const auto dir = tempPath("bad");
    std::filesystem::create_directories(dir);
    const auto file = dir / "bad.json";
    std::ofstream(file) << "{\n  \"format_version\": 1,\n  \"frames\": 0\n}\n";
    const auto out = dir / "out";
    const Outcome o = runOccsim("run " + file.string() + " --out " + out.string());
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("bad.json"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("/frames"), std::string::npos) << o.output;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, BadFlagsAreOneLineWithExitCode2) {
    const std::vector<std::string> cases = {"bench " + kSmall + " --frames 0",
                                            "bench " + kSmall + " --frmaes 3",
                                            "run " + kSmall + " --frames ten", "fly " + kSmall, ""};
    for (const std::string& args : cases) {
        const Outcome o = runOccsim(args);
        EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << args << ": " << o.output;
    }
}

// What a new user tried: each answer names the flag or command and what was expected.
TEST(Cli, BadValuesSayWhatWasExpectedAndWhatWasGiven) {
    const struct {
        std::string args, must_contain;
    } cases[] = {
        {"frobnicate " + kSmall, "unknown command 'frobnicate'; expected one of: run, bench"},
        {"run " + kSmall + " --frames abc",
         "--frames: expected an integer in [1, 10000000], got 'abc'"},
        {"run " + kSmall + " --capture 1,x",
         "--capture: expected an integer in [0, 9999999], got 'x'"},
        {"run " + kSmall + " --capture 40",
         "--capture: frame 40 is past the last frame (40 frames"},
        {"run " + kSmall + " --birds-eye 40", "--birds-eye: frame 40 is past the last frame"},
        {"bench " + kSmall + " --repetitions 0", "--repetitions: expected an integer in [1, 1000]"},
        {"bench " + kSmall + " --frame-order random",
         "--frame-order: expected balanced, rotated or fixed, got 'random'"},
    };
    for (const auto& c : cases) {
        const Outcome o = runOccsim(c.args);
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << c.args << ": " << o.output;
        EXPECT_NE(o.output.find(c.must_contain), std::string::npos) << c.args << ": " << o.output;
    }
}

// The headless backend and device: a choice that cannot be served is bad input, one line naming
// what is missing and what was found, and nothing is written.
TEST(Cli, ABackendOrDeviceThatCannotServeIsOneLineWithExitCode2) {
    const auto out = tempPath("bad-backend");
    const struct {
        std::string args, must_contain;
    } cases[] = {
        {"bench " + kSmall + " --backend vulkan",
         "--backend: expected auto, egl or osmesa, got 'vulkan'"},
        {"bench " + kSmall + " --device 64", "--device 64: out of range, EGL lists "},
        {"run " + kSmall + " --backend egl --device 9", "--device 9: out of range"},
        {"run " + kSmall + " --device -1", "--device: expected an integer in [0, 1023], got '-1'"},
        {"run " + kSmall + " --backend osmesa --device 0",
         "--device 0: only the EGL backend has devices"},
        {"regress " + kSmall + " --device 5", "--device 5: out of range"},
        {"regress " + kSmall + " --backend gl",
         "--backend: expected auto, egl or osmesa, got 'gl'"},
    };
    for (const auto& c : cases) {
        const Outcome o = runOccsim(c.args + " --out " + out.string());
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << c.args << ": " << o.output;
        EXPECT_NE(o.output.find(c.must_contain), std::string::npos) << c.args << ": " << o.output;
        EXPECT_FALSE(std::filesystem::exists(out / "summary.json")) << c.args;
    }
}

// Without EGL (here: glvnd told to load no vendor library), `auto` falls back to OSMesa where the
// build has it and says so everywhere; `egl` is bad input; without OSMesa `auto` is bad input too.
TEST(Cli, WithoutEglAutoFallsBackToOsmesaAndSaysWhyAndEglIsBadInput) {
    const std::string no_egl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json ";
    const auto out = tempPath("no-egl");
    const Outcome egl = shell(no_egl + OCCSIM_EXE + " run " + kSmall +
                              " --algo vfc --frames 2 --backend egl --out " + out.string());
    EXPECT_EQ(egl.exit_code, 2) << egl.output;
    EXPECT_EQ(lineCount(egl.output), 1u) << egl.output;
    EXPECT_NE(egl.output.find("--backend egl: EGL: EGL lacks EGL_EXT_device_enumeration"),
              std::string::npos)
        << egl.output;
    const Outcome fallback = shell(no_egl + OCCSIM_EXE + " run " + kSmall +
                                   " --algo vfc --frames 2 --out " + out.string());
    if (!OCCSIM_HAVE_OSMESA) {
        EXPECT_EQ(fallback.exit_code, 2) << fallback.output;
        EXPECT_NE(fallback.output.find("and this build has no OSMesa"), std::string::npos)
            << fallback.output;
        return;
    }
    ASSERT_EQ(fallback.exit_code, 0) << fallback.output;
    EXPECT_NE(fallback.output.find("backend: OSMesa"), std::string::npos) << fallback.output;
    EXPECT_NE(fallback.output.find("backend auto fell back to OSMesa: EGL: EGL lacks"),
              std::string::npos)
        << fallback.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    EXPECT_NE(json.find("\"backend\": \"osmesa\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"backend_fallback\": \"EGL: EGL lacks"), std::string::npos) << json;
}

// A device whose OpenGL is too old (Mesa told to offer 4.3, or to hide the timer queries, which
// takes it below 3.3) is bad input naming what was asked for and what was found.
TEST(Cli, AContextBelowOpenGl45IsOneLineNamingWhatWasFound) {
    const auto out = tempPath("old-gl");
    for (const std::string& env : {std::string("MESA_GL_VERSION_OVERRIDE=4.3"),
                                   std::string("MESA_EXTENSION_OVERRIDE=-GL_ARB_timer_query")}) {
        const Outcome o = shell(env + " " + OCCSIM_EXE + " run " + kSmall +
                                " --algo vfc --frames 2 --backend egl --out " + out.string());
        EXPECT_EQ(o.exit_code, 2) << env << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << env << ": " << o.output;
        EXPECT_NE(o.output.find("EGL device 0: cannot create an OpenGL 4.5 core context"),
                  std::string::npos)
            << o.output;
        EXPECT_NE(o.output.find("found OpenGL \""), std::string::npos) << o.output;
        EXPECT_FALSE(std::filesystem::exists(out / "summary.json"));
    }
}

TEST(Cli, DevicesListsTheSoftwareDeviceWithVendorRendererAndDriver) {
    const Outcome o = runOccsim("devices");
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("EGL devices: "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("(software): vendor Mesa"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("renderer llvmpipe"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("driver Mesa "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("gpu ms not meaningful"), std::string::npos) << o.output;
}

// Where a run rendered is in its console header, summary.json and report.md.
TEST(Cli, TheBackendDeviceAndDriverAreRecordedEverywhere) {
    const auto out = tempPath("backend");
    const Outcome o = runOccsim(
        "run " + kSmall + " --algo vfc --frames 2 --backend egl --device 0 --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("backend: EGL device 0, vendor Mesa"), std::string::npos) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    for (const char* part :
         {"\"backend\": \"egl\"", "\"device\": 0", "\"gl_renderer\": \"llvmpipe",
          "\"driver\": \"Mesa ", "\"gl_vendor\"", "\"gpu_time_meaningful\": false"}) {
        EXPECT_NE(json.find(part), std::string::npos) << part << " in " << json;
    }
    std::ifstream report(out / "report.md");
    const std::string md{std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>()};
    EXPECT_NE(md.find("| backend | EGL device 0: vendor Mesa"), std::string::npos) << md;
}

// A run whose every frame is warm-up has no timing to report: it says so instead of 0.00 ms.
TEST(Cli, ARunWithOnlyWarmupFramesSaysNothingWasTimed) {
    const Outcome o = runOccsim("bench " + kSmall + " --algos vfc --frames 3 --out " +
                                tempPath("warmup").string());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("nothing was timed"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("not timed"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("0.00"), std::string::npos) << o.output;
}

// The first answer fits a terminal (issue 56): bench prints the compact table and the verdict in
// lines of at most 100 columns, the kind of each row, the fastest conservative culler or the tie,
// the wrong pixels and the why command; --wide prints the full table of every figure instead.
TEST(Cli, BenchPrintsACompactTableAndAVerdictThatFitAndWidePrintsEveryFigure) {
    const std::string args =
        "bench " + kSmall + " --error --algos vfc,chc,statistical+,async,ideal --frames 30 --out ";
    const Outcome o = runOccsim(args + tempPath("compact").string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::istringstream lines(o.output);
    size_t checked = 0;
    for (std::string line; std::getline(lines, line);) {
        EXPECT_LE(line.size(), 100u) << "'" << line << "'";
        ++checked;
    }
    EXPECT_GT(checked, 10u) << o.output;
    // The header's columns, in order.
    const size_t header_at = o.output.find("\nconfiguration  kind ");
    ASSERT_NE(header_at, std::string::npos) << o.output;
    const std::string header =
        o.output.substr(header_at + 1, o.output.find('\n', header_at + 1) - header_at - 1);
    size_t at = 0;
    for (const char* column :
         {"mean ms", "vs vfc", "vs ideal", "queries", "objects", "err px", "missed"}) {
        at = header.find(column, at);
        EXPECT_NE(at, std::string::npos) << column << " in " << header;
    }
    for (const char* part : {"\nvfc ", " cons ", " approx ", " oracle ", "\nverdict: fastest ",
                             "\nwrong pixels: ", "\nwhy "}) {
        EXPECT_NE(o.output.find(part), std::string::npos) << part << " in " << o.output;
    }
    EXPECT_EQ(o.output.find("median ms"), std::string::npos) << o.output;

    const Outcome wide = runOccsim(args + tempPath("wide").string() + " --wide");
    ASSERT_EQ(wide.exit_code, 0) << wide.output;
    for (const char* part :
         {"configuration  mean ms  median ms  p95 ms  gpu ms  queries/fr", "err px/fr", "tie px",
          "pop max", "overdrawn/fr", "speedup", "vs ideal  pareto"}) {
        EXPECT_NE(wide.output.find(part), std::string::npos) << part << " in " << wide.output;
    }
    EXPECT_EQ(wide.output.find("verdict:"), std::string::npos) << wide.output;
}

TEST(Cli, RunWritesTheSummaryTableAndBothFiles) {
    const auto out = tempPath("ok");
    const Outcome o =
        runOccsim("run " + kSmall + " --algo statistical --frames 5 --error --out " + out.string());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("statistical"), std::string::npos) << o.output;
    EXPECT_TRUE(std::filesystem::exists(out / "frames.csv"));
    EXPECT_TRUE(std::filesystem::exists(out / "summary.json"));
}

// The console says what the run cost beside its frames: without --error that no ground truth
// was rendered, with it how many renders and what they took.
TEST(Cli, RunStatesItsWallClockAgainstFrameTimeAndWhatGroundTruthCost) {
    const Outcome plain =
        runOccsim("run " + kSmall + " --algo chc --frames 5 --out " + tempPath("plain").string());
    EXPECT_EQ(plain.exit_code, 0) << plain.output;
    EXPECT_NE(plain.output.find("ms wall clock after set-up for"), std::string::npos)
        << plain.output;
    EXPECT_NE(plain.output.find("no ground truth rendered"), std::string::npos) << plain.output;
    const Outcome measured = runOccsim("run " + kSmall + " --algo chc --frames 5 --error --out " +
                                       tempPath("measured").string());
    EXPECT_EQ(measured.exit_code, 0) << measured.output;
    EXPECT_NE(measured.output.find("ground truth 5 renders"), std::string::npos) << measured.output;
}

TEST(Cli, InfoPrintsTheSceneWithoutRendering) {
    const Outcome o = runOccsim("info " + kSmall);
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("triangles"), std::string::npos) << o.output;
    // What was read about occluders is said (issue 56): the teapots carry no roles.
    EXPECT_NE(o.output.find("\noccluders     300 by size, 0 always, 0 never; 0 with an authored "
                            "occluder mesh\n"),
              std::string::npos)
        << o.output;
    // The courtyards' walls are always occluders (scripts/make_levels.py gives the role).
    const Outcome level =
        runOccsim("info " + std::string(OCCSIM_SOURCE_DIR) + "/scenarios/levels/courtyards.json");
    EXPECT_NE(level.output.find("\noccluders     338 by size, 97 always, 0 never"),
              std::string::npos)
        << level.output;
}

// A run with an occluder pass (masked) says the roles in its header; one without does not.
TEST(Cli, ARunWithAnOccluderPassSaysTheOccluderRoles) {
    const Outcome masked = runOccsim("run " + kSmall + " --algo masked --frames 2 --out " +
                                     tempPath("roles-masked").string());
    ASSERT_EQ(masked.exit_code, 0) << masked.output;
    EXPECT_NE(masked.output.find("\noccluders: 300 by size, 0 always, 0 never;"), std::string::npos)
        << masked.output;
    const Outcome vfc = runOccsim("run " + kSmall + " --algo vfc --frames 2 --out " +
                                  tempPath("roles-vfc").string());
    ASSERT_EQ(vfc.exit_code, 0) << vfc.output;
    EXPECT_EQ(vfc.output.find("occluders:"), std::string::npos) << vfc.output;
}

// --culling FILE: a scenario's culling section on its own (what occtune writes as tuned.json),
// read with the scenario parser's strict readers and applied over the scenario's.
TEST(Cli, CullingFileOverridesTheScenariosCullingOptions) {
    const auto dir = tempPath("culling");
    std::filesystem::create_directories(dir);
    const auto file = dir / "culling.json";
    std::ofstream(file)
        << R"({"format_version": 1, "culling": {"algorithm": "vfc", "statistical": {"base_time": 0.3}}})";
    // The scenario's algorithm is statistical; the file's wins.
    const Outcome o = runOccsim("run " + kSmall + " --frames 3 --culling " + file.string() +
                                " --out " + (dir / "run").string());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("\nvfc "), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("statistical"), std::string::npos) << o.output;
    std::filesystem::remove_all(dir);
}

TEST(Cli, BadCullingFileIsOneLineNamingTheFileAndPointerWithExitCode2) {
    const auto dir = tempPath("bad-culling");
    std::filesystem::create_directories(dir);
    const struct {
        std::string contents, must_contain;
    } cases[] = {
        {R"({"format_version": 1, "culling": {"statistical": {"base_tme": 0.3}}})",
         "/culling/statistical/base_tme: unknown key 'base_tme'; did you mean 'base_time'?"},
        {R"({"format_version": 1, "culling": {"statistical": {"decay_b": 2}}})",
         "/culling/statistical/decay_b: expected a number in [0, 1], got 2"},
        {R"({"format_version": 1})", "missing required key 'culling'"},
        {R"({"format_version": 1, "culling": {}, "camera": {}})", "unknown key 'camera'"},
        {R"({"culling": {}})", "format_version"},
    };
    for (const auto& c : cases) {
        const auto file = dir / "culling.json";
        std::ofstream(file) << c.contents;
        for (const std::string& command :
             {"run " + kSmall, "bench " + kSmall, "regress " + kSmall}) {
            const Outcome o = runOccsim(command + " --culling " + file.string() + " --out " +
                                        (dir / "out").string());
            EXPECT_EQ(o.exit_code, 2) << command << " " << c.contents << ": " << o.output;
            EXPECT_EQ(lineCount(o.output), 1u) << command << ": " << o.output;
            EXPECT_NE(o.output.find(file.string()), std::string::npos) << o.output;
            EXPECT_NE(o.output.find(c.must_contain), std::string::npos) << o.output;
            EXPECT_FALSE(std::filesystem::exists(dir / "out")) << command;
        }
    }
    std::filesystem::remove_all(dir);
}

}  // namespace

// docs/cullers.md holds the registry's own tables between two markers: regenerate them with
// `occsim cullers --markdown` when a descriptor changes.
TEST(Cli, TheCullersPageIsTheRegistrysOwnOutput) {
    std::ifstream in(std::string(OCCSIM_SOURCE_DIR) + "/docs/cullers.md");
    std::stringstream page;
    page << in.rdbuf();
    const std::string text = page.str();
    const std::string begin = "<!-- BEGIN occsim cullers --markdown -->\n";
    const std::string end = "<!-- END occsim cullers --markdown -->";
    const size_t b = text.find(begin), e = text.find(end);
    ASSERT_NE(b, std::string::npos);
    ASSERT_NE(e, std::string::npos);
    const Outcome o = runOccsim("cullers --markdown");
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_EQ(text.substr(b + begin.size(), e - b - begin.size()), o.output)
        << "docs/cullers.md is out of date: paste the output of occsim cullers --markdown";
}

namespace {

// Where `name` stands as a word of its own in `line` (not inside "statistical+" or "chc++").
std::vector<std::pair<size_t, size_t>> nameSpans(const std::string& line,
                                                 const std::vector<std::string>& names) {
    auto part = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '+' || c == '-';
    };
    std::vector<std::pair<size_t, size_t>> spans;
    for (size_t i = 0; i < line.size(); ++i) {
        if (i > 0 && part(line[i - 1])) continue;
        size_t longest = 0;
        for (const std::string& n : names) {
            if (line.compare(i, n.size(), n) == 0 &&
                (i + n.size() == line.size() || !part(line[i + n.size()])))
                longest = std::max(longest, n.size());
        }
        if (longest > 0) spans.push_back({i, i + longest});
    }
    return spans;
}

// Text between two names of one typed list: a comma and a space (a bare comma is a command
// line's), "and", "or", with backticks.
bool listSeparator(std::string between) {
    std::erase(between, '`');
    if (between == ",") return false;  // a command line's list: --algos vfc,chc
    while (!between.empty() && between.front() == ' ') between.erase(0, 1);
    while (!between.empty() && between.back() == ' ') between.pop_back();
    return between == "," || between == "and" || between == ", and" || between == "or" ||
           between == ", or";
}

}  // namespace

// A page that lists the cullers by hand goes stale when one is added (docs/cli.md once gave 8 of
// 11 as bench's default): a typed list of five or more of them names every one, or ends in "...",
// or is replaced by a link to docs/cullers.md, which the registry generates. Lists of a command
// line (--algos a,b,c) are the command's own choice, and pass.
TEST(Cli, NoPageTypesAnIncompleteListOfTheCullers) {
    const Outcome o = runOccsim("cullers");
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::vector<std::string> names;
    std::istringstream listing(o.output);
    for (std::string line; std::getline(listing, line);) {
        if (!line.empty() && line[0] != ' ') names.push_back(line.substr(0, line.find(':')));
    }
    ASSERT_GE(names.size(), 11u) << o.output;
    std::vector<std::filesystem::path> pages = {std::filesystem::path(OCCSIM_SOURCE_DIR) /
                                                "README.md"};
    for (const auto& e :
         std::filesystem::directory_iterator(std::filesystem::path(OCCSIM_SOURCE_DIR) / "docs")) {
        if (e.path().extension() == ".md" && e.path().filename() != "cullers.md")
            pages.push_back(e.path());
    }
    auto incomplete = [&](const std::string& line) {
        const auto spans = nameSpans(line, names);
        for (size_t first = 0; first < spans.size();) {
            size_t last = first;
            while (last + 1 < spans.size() &&
                   listSeparator(
                       line.substr(spans[last].second, spans[last + 1].first - spans[last].second)))
                ++last;
            std::set<std::string> listed;
            for (size_t k = first; k <= last; ++k)
                listed.insert(line.substr(spans[k].first, spans[k].second - spans[k].first));
            const std::string after = line.substr(spans[last].second, 6);
            const bool elided =
                after.find("...") != std::string::npos || after.find("\u2026") != std::string::npos;
            if (listed.size() >= 5 && listed.size() < names.size() && !elided) return true;
            first = last + 1;
        }
        return false;
    };
    // The check finds what it is for.
    EXPECT_TRUE(
        incomplete("(default: all: `vfc, stop-and-wait, statistical, statistical+, chc, "
                   "chc++, async, ideal`)"));
    EXPECT_FALSE(
        incomplete("expected one of: vfc, stop-and-wait, statistical, statistical+, chc, "
                   "..."));
    EXPECT_FALSE(incomplete("--algos vfc,stop-and-wait,statistical,chc,chc++,ideal"));
    for (const auto& page : pages) {
        std::ifstream in(page);
        size_t number = 0;
        for (std::string line; std::getline(in, line);) {
            ++number;
            EXPECT_FALSE(incomplete(line))
                << page.filename().string() << ":" << number
                << ": names some of the cullers by hand; list every one, end the list in \"...\", "
                   "or link to docs/cullers.md: "
                << line;
        }
    }
}

// A sweep names an option by its JSON key and is checked against the listed algorithms'
// descriptors before any run; --ablate switches off each mechanism a descriptor marks.
TEST(Cli, SweepsAndAblationsReadTheDescriptors) {
    const auto out = tempPath("sweep");
    const struct {
        std::string args, expected;
    } refused[] = {
        {"--algos vfc,chc --sweep base_time=0.5",
         "--sweep: 'base_time' is an option of none of the algorithms run; expected one of: "
         "threshold_pixels, "
         "stale_results, visible_frames_skip"},
        {"--algos statistical --sweep base_time=-1",
         "--sweep: base_time: expected a number >= 0 (s), got -1"},
        {"--algos statistical --sweep history_length=2.5",
         "--sweep: history_length: expected an integer in [1, 32]"},
        {"--algos statistical --sweep chc:visible_frames_skip=1",
         "--sweep: 'chc' is not among the algorithms run"},
        {"--algos statistical --sweep base_time=", "--sweep: expected [ALGORITHM:]KEY=V1,V2,..."},
        {"--algos vfc,chc --ablate chc",
         "--ablate: 'chc' has no mechanism switched on to switch off"},
        {"--algos vfc --ablate statistical+",
         "--ablate: 'statistical+' is not among the algorithms run"},
        // Two configurations with the same options would be two rows under one label.
        {"--algos statistical --sweep threshold_pixels=1,1",
         "--sweep: threshold_pixels: 1 is listed twice (as '1' too); expected each value once"},
        {"--algos statistical+ --sweep ready_answers=true,1",
         "--sweep: ready_answers: true is listed twice (as '1' too)"},
        {"--algos statistical+ --sweep ready_answers=false,true --ablate statistical+",
         "--ablate: 'statistical+ ready_answers=false' would run the same options as "
         "'statistical+ ready_answers=false'"},
    };
    for (const auto& c : refused) {
        const Outcome o = runOccsim("bench " + kSmall + " " + c.args + " --out " + out.string());
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << o.output;
        EXPECT_NE(o.output.find(c.expected), std::string::npos) << c.args << ": " << o.output;
        EXPECT_FALSE(std::filesystem::exists(out));
    }

    const Outcome sweep = runOccsim(
        "bench " + kSmall +
        " --algos vfc,statistical,statistical+ --sweep statistical+:stale_results=false,true "
        "--frames 3 --deterministic-latency 4 --out " +
        out.string());
    ASSERT_EQ(sweep.exit_code, 0) << sweep.output;
    EXPECT_NE(sweep.output.find("\nstatistical+ stale_results=true "), std::string::npos)
        << sweep.output;
    EXPECT_NE(sweep.output.find("\nstatistical "), std::string::npos)
        << "not swept: runs once" << sweep.output;

    const Outcome ablation = runOccsim("bench " + kSmall +
                                       " --algos vfc,statistical+ --ablate statistical+ --frames 3 "
                                       "--deterministic-latency 4 --out " +
                                       out.string());
    ASSERT_EQ(ablation.exit_code, 0) << ablation.output;
    for (const char* row :
         {"\nstatistical+ ", "\nstatistical+ ready_answers=false ",
          "\nstatistical+ virtual_leaves=false ", "\nstatistical+ object_queries=false ",
          "\nstatistical+ cost_model=false ", "\nstatistical+ requery_parallax=0 ",
          "\nstatistical+ fallback=false "}) {
        EXPECT_NE(ablation.output.find(row), std::string::npos) << row << ablation.output;
    }
    std::filesystem::remove_all(out);
}

// Nonsense on the command line is refused before any work, one line each: a name listed twice
// or an empty one in --algos, an output folder that is a file or empty, a JUnit file that is a
// folder; a misspelt flag gets the nearest one.
TEST(Cli, NonsenseAndUnwritableOutputsAreRefusedBeforeAnyRun) {
    const auto dir = tempPath("nonsense");
    std::filesystem::create_directories(dir);
    const auto file = dir / "a-file";
    std::ofstream(file) << "x";
    const auto out = dir / "out";
    const struct {
        std::string args, expected;
    } cases[] = {
        {"bench " + kSmall + " --algos vfc,chc,vfc --out " + out.string(),
         "--algos: 'vfc' is listed twice"},
        {"bench " + kSmall + " --algos vfc,chc, --out " + out.string(),
         "--algos: an empty algorithm name"},
        {"bench " + kSmall + " --out " + file.string(),
         "--out " + file.string() + ": is a file; expected a folder"},
        {"run " + kSmall + " --out ''", "--out: empty; expected a folder"},
        {"regress " + kSmall + " --junit " + dir.string() + " --out " + out.string(),
         "--junit " + dir.string() + ": is a folder; expected a file name"},
        {"bench " + kSmall + " --frame 3", "not expected: 3 --frame; did you mean '--frames'?"},
    };
    for (const auto& c : cases) {
        const Outcome o = runOccsim(c.args);
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << o.output;
        EXPECT_NE(o.output.find(c.expected), std::string::npos) << c.args << ": " << o.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
        EXPECT_FALSE(std::filesystem::exists("out/teapots-small/run-statistical/summary.json.tmp"));
    }
    std::filesystem::remove_all(dir);
}

// A regression run that checks nothing (an empty folder, or scenarios without expect blocks)
// fails with one line saying why, unless --allow-empty says that is expected.
TEST(Cli, RegressWithNothingToCheckFailsUnlessAllowed) {
    const auto dir = tempPath("regress-empty");
    const auto empty = dir / "empty", plain = dir / "plain";
    std::filesystem::create_directories(empty);
    std::filesystem::create_directories(plain);
    std::ifstream in(kSmall);
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    text = text.substr(0, text.find(",\n  \"expect\"")) + "\n}\n";  // the same scenario, no expect
    std::ofstream(plain / "plain.json") << text;
    const std::string out = " --out " + (dir / "out").string();
    for (const auto& [folder, why] : {std::pair{empty, "no scenario file found"},
                                      std::pair{plain, "no scenario found has an expect block"}}) {
        const Outcome o = runOccsim("regress " + folder.string() + out);
        EXPECT_EQ(o.exit_code, 1) << o.output;
        EXPECT_NE(o.output.find("occsim regress: nothing was checked: " + std::string(why)),
                  std::string::npos)
            << o.output;
        const Outcome allowed = runOccsim("regress " + folder.string() + " --allow-empty" + out);
        EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
        EXPECT_EQ(allowed.output.find("nothing was checked"), std::string::npos) << allowed.output;
    }
    std::filesystem::remove_all(dir);
}

// A camera that looks away from every object measures empty frames: the run warns in one line
// and gives no speedup (n/a), in the table, report.md and summary.json.
TEST(Cli, ACameraThatSeesNothingWarnsAndGivesNoSpeedup) {
    const auto dir = tempPath("looks-away");
    std::filesystem::create_directories(dir);
    std::ifstream in(kSmall);
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    // The teapots stand at z in [-60, 0]; this camera at z = 6 looks towards +z.
    const std::string from = "\"target\": [0, 1.5, -20]", to = "\"target\": [0, 2, 40]";
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), to);
    const std::string from2 = "\"target\": [-3, 1.5, -35]";
    ASSERT_NE(text.find(from2), std::string::npos);
    text.replace(text.find(from2), from2.size(), "\"target\": [3, 2.5, 40]");
    const auto scenario = dir / "away.json";
    std::ofstream(scenario) << text;
    const auto out = dir / "out";
    const Outcome o = runOccsim("bench " + scenario.string() +
                                " --algos vfc,chc,ideal --frames 8 --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("warning: the camera sees no object on any frame"), std::string::npos)
        << o.output;
    EXPECT_EQ(o.output.find("1.00x"), std::string::npos)
        << "no speedup, not even vfc over itself: " << o.output;
    // Nor a ratio of empty frames' times: no worst windows (they printed "1.00x ideal" when the
    // noise rounded so, and this test failed on a loaded machine).
    EXPECT_EQ(o.output.find("worst windows"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("n/a"), std::string::npos) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    EXPECT_NE(json.find("\"nothing_in_view\": true"), std::string::npos) << json;
    EXPECT_EQ(json.find("speedup_over_vfc"), std::string::npos) << json;
    std::ifstream report(out / "report.md");
    const std::string md{std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>()};
    EXPECT_NE(md.find("the camera sees no object on any frame"), std::string::npos) << md;
    std::filesystem::remove_all(dir);
}

// summary.json says what ran and how to run it again: the version and commit, every option of
// every culler after defaults, and the command shell-quoted, which pasted back runs as typed.
TEST(Cli, SummaryJsonRecordsTheVersionTheOptionsAndACommandThatPastesBack) {
    const auto dir = tempPath("repro");
    const auto out = dir / "it's a folder";
    const Outcome o = runOccsim(
        "bench " + kSmall + " --algos vfc,statistical+ --frames 2 --out \"" + out.string() + "\"");
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    EXPECT_NE(json.find("\"occsim\": {\n    \"commit\": \""), std::string::npos) << json;
    EXPECT_NE(json.find("\"version\": \"0."), std::string::npos) << json;
    for (const char* option : {"\"options\": {", "\"base_time\": ", "\"cost_model\": ",
                               "\"threshold_pixels\": 0", "\"frame_order\": \"balanced\""}) {
        EXPECT_NE(json.find(option), std::string::npos) << option << " in " << json;
    }
    std::string quoted = (dir / "it'\\\\''s a folder").string();
    quoted.insert(quoted.begin(), '\'');
    quoted.push_back('\'');
    const size_t at = json.find("\"command\": \"");
    ASSERT_NE(at, std::string::npos) << json;
    const size_t start = at + std::string("\"command\": \"").size();
    std::string command = json.substr(start, json.find("\",\n", start) - start);
    EXPECT_NE(command.find(quoted), std::string::npos) << command << " lacks " << quoted;
    // JSON escapes the backslash of '\'' once: undo that, then run it again from the shell.
    for (size_t p = command.find("\\\\"); p != std::string::npos; p = command.find("\\\\", p + 1))
        command.erase(p, 1);
    std::filesystem::remove_all(out);
    const Outcome again = shell(command);
    EXPECT_EQ(again.exit_code, 0) << command << ": " << again.output;
    EXPECT_TRUE(std::filesystem::exists(out / "summary.json")) << command;
    std::filesystem::remove_all(dir);
}

TEST(Cli, VersionPrintsTheProjectVersionAndCommitThatSummaryJsonRecords) {
    const Outcome v = runOccsim("--version");
    ASSERT_EQ(v.exit_code, 0) << v.output;
    const std::string prefix = std::string("occsim ") + OCCSIM_PROJECT_VERSION + " (commit ";
    ASSERT_EQ(v.output.rfind(prefix, 0), 0u) << v.output;
    ASSERT_EQ(lineCount(v.output), 1u) << v.output;
    const std::string commit = v.output.substr(prefix.size(), v.output.find(")\n") - prefix.size());
    EXPECT_FALSE(commit.empty()) << v.output;
    const auto out = tempPath("version");
    const Outcome o = runOccsim("run " + kSmall + " --algo vfc --frames 1 --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    EXPECT_NE(json.find("\"commit\": \"" + commit + "\""), std::string::npos) << json;
    EXPECT_NE(json.find(std::string("\"version\": \"") + OCCSIM_PROJECT_VERSION + "\""),
              std::string::npos)
        << json;
    std::filesystem::remove_all(out);
}

// --algos NAME,NAME@tuned.json: a tuned file's setting runs beside the culler's own, interleaved
// in one run, as a row of its own everywhere; a file that cannot be that is one line, exit 2.
TEST(Cli, ATunedFileRunsBesideTheDefaultsInterleavedAndLabelledApart) {
    const auto dir = tempPath("tuned-beside");
    std::filesystem::create_directories(dir);
    auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    };
    const std::string tuned =
        write("tuned.json", R"({"format_version": 1, "tuned_for": "statistical+", "culling": {
            "algorithm": "statistical+",
            "statistical+": {"queries_before_restart": 1, "ready_answers": true}}})");
    const auto out = dir / "out";
    const Outcome o =
        runOccsim("bench " + kSmall + " --algos statistical+,statistical+@" + tuned +
                  " --frames 8 --deterministic-latency 8 --quiet --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("\nstatistical+@tuned "), std::string::npos) << o.output;
    std::ifstream summary_in(out / "summary.json");
    const std::string summary{std::istreambuf_iterator<char>(summary_in),
                              std::istreambuf_iterator<char>()};
    EXPECT_NE(summary.find("\"configuration\": \"statistical+@tuned\""), std::string::npos);
    EXPECT_NE(summary.find("\"culling_file\": \"" + tuned + "\""), std::string::npos) << summary;
    EXPECT_NE(summary.find("\"queries_before_restart\": 1,"), std::string::npos) << summary;
    std::ifstream report_in(out / "report.md");
    const std::string report{std::istreambuf_iterator<char>(report_in),
                             std::istreambuf_iterator<char>()};
    EXPECT_NE(report.find("| statistical+@tuned |"), std::string::npos) << report;
    // frames.csv: both rows every frame, interleaved in one run; the tuned options decide
    // otherwise (another query count on some frame).
    std::ifstream csv(out / "frames.csv");
    std::map<std::string, std::vector<std::string>> queries;
    std::string line;
    std::getline(csv, line);
    while (std::getline(csv, line)) {
        std::vector<std::string> cells;
        std::stringstream cell(line);
        for (std::string c; std::getline(cell, c, ',');) cells.push_back(c);
        ASSERT_GT(cells.size(), 8u) << line;
        queries[cells[0]].push_back(cells[8]);
    }
    ASSERT_EQ(queries.size(), 2u);
    EXPECT_EQ(queries["statistical+"].size(), 8u);
    EXPECT_EQ(queries["statistical+@tuned"].size(), 8u);
    EXPECT_NE(queries["statistical+"], queries["statistical+@tuned"]);

    // Bad input: one line naming the flag and the file, exit 2, nothing written.
    const std::string other =
        write("other.json", R"({"format_version": 1, "tuned_for": "statistical", "culling": {
            "algorithm": "statistical", "statistical": {"base_time": 0.3}}})");
    const std::string broken = write("broken.json", R"({"format_version": 1, "culling": )");
    const struct {
        std::string entry, expected;
    } refused[] = {
        {"statistical+@" + (dir / "missing.json").string(), "missing.json: cannot open file"},
        {"statistical+@" + broken, "broken.json: "},
        {"statistical+@" + other, "other.json is a culling file for statistical, not statistical+"},
        {"statistical+@", "no file after '@'"},
        {"statistical+@" + tuned + ",statistical+@" + tuned,
         "'statistical+@tuned' is listed twice"},
    };
    for (const auto& r : refused) {
        const auto bad_out = dir / "bad-out";
        const Outcome bad = runOccsim("bench " + kSmall + " --algos " + r.entry +
                                      " --frames 2 --out " + bad_out.string());
        EXPECT_EQ(bad.exit_code, 2) << r.entry << ": " << bad.output;
        EXPECT_EQ(lineCount(bad.output), 1u) << bad.output;
        EXPECT_EQ(bad.output.rfind("occsim: --algos", 0), 0u) << bad.output;
        EXPECT_NE(bad.output.find(r.expected), std::string::npos) << bad.output;
        EXPECT_FALSE(std::filesystem::exists(bad_out)) << r.entry;
    }
    std::filesystem::remove_all(dir);
}

// A cost model a culling file gives for one culler (as tuned.json does) reaches that culler
// only: statistical+ keeps the reference figures of a deterministic run.
TEST(Cli, ACostModelForOneCullerChangesNoOther) {
    const auto dir = tempPath("scoped-cost");
    std::filesystem::create_directories(dir);
    const auto file = dir / "tuned.json";
    std::ofstream(file) << R"({"format_version": 1, "culling": {"algorithm": "statistical",
        "statistical": {"cost_model": true},
        "cost_model": {"query_box_ms": 0.5, "triangle_ms": 0.25, "draw_call_ms": 0.125, "cullers": ["statistical"]}}})";
    const auto out = dir / "out";
    const Outcome o = runOccsim("bench " + kSmall +
                                " --algos statistical,statistical+ --frames 2 "
                                "--deterministic-latency 4 --culling " +
                                file.string() + " --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    const size_t plus = json.find("\"configuration\": \"statistical+\"");
    const size_t paper = json.find("\"configuration\": \"statistical\"");
    ASSERT_NE(plus, std::string::npos) << json;
    ASSERT_NE(paper, std::string::npos) << json;
    // Each algorithm's object: from its start to the next configuration (or the end of the list).
    auto objectOf = [&](size_t at) {
        const size_t open = json.rfind("\n    {", at);
        return json.substr(open, json.find("\n    }", at) - open);
    };
    EXPECT_NE(objectOf(paper).find("\"query_box_ms\": 0.5"), std::string::npos) << objectOf(paper);
    EXPECT_NE(objectOf(plus).find("\"cost_model\": {"), std::string::npos) << objectOf(plus);
    EXPECT_EQ(objectOf(plus).find("\"query_box_ms\": 0.5"), std::string::npos) << objectOf(plus);
    std::filesystem::remove_all(dir);
}
