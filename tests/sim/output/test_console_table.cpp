// The console's first answer (sim/output/console_table.h): the compact table fits 100 columns with
// every registered culler and long labels, says which rows are conservative and sorts them; the
// verdict names the fastest conservative culler and its margin, or the tie and by what rule, the
// cullers that drew wrong pixels, and the why command for the runner-up. Figures made here, no
// run.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/output/console_table.h"
#include "sim/output/report.h"

namespace occsim {
namespace {

constexpr uint32_t kWarmup = 10;

// A configuration of `algorithm` whose frames take `ms` each, with `jitter` added on odd frames;
// 40 frames, the first kWarmup of them warm-up.
RunRecord record(const std::string& label, const std::string& algorithm, double ms,
                 double jitter = 0.0, int64_t error_pixels = 0, int64_t missed = 0) {
    RunRecord r;
    r.algorithm = findCuller(algorithm);
    for (uint32_t f = 0; f < 40; ++f) {
        FrameStats s;
        s.frame = f;
        s.frame_ms = ms + (f % 2 ? jitter : 0.0);
        s.queries = 12;
        s.objects_drawn = 30;
        s.error_pixels = f == 20 ? error_pixels : 0;
        s.tie_pixels = 0;
        s.stray_pixels = 0;
        s.missed_objects = f == 20 ? missed : 0;
        r.frames.push_back(s);
    }
    r.summary = summarize(label, r.frames, kWarmup);
    return r;
}

std::vector<std::string> linesOf(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

BenchResult resultOf(std::vector<RunRecord> runs, bool error = true) {
    BenchResult result;
    result.metadata.error_measured = error;
    result.runs = std::move(runs);
    return result;
}

TEST(ConsoleTable, FitsOneHundredColumnsWithEveryRegisteredCullerAndLongLabels) {
    std::vector<RunRecord> runs;
    double ms = 1000.5;  // wide figures
    for (const CullerRow* row : cullerRows()) {
        runs.push_back(record(row->name, row->name, ms, 0.0, 123456789, 99999));
        ms *= 1.1;
    }
    runs.push_back(record("statistical+:base_time_ms=0.125,decay=0.75,stale_results=true",
                          "statistical+", 2.0));
    const std::string table = formatCompactTable(runs);
    const std::vector<std::string> lines = linesOf(table);
    ASSERT_EQ(lines.size(), runs.size() + 3) << table;  // header, rows, two legend lines
    for (const std::string& line : lines)
        EXPECT_LE(line.size(), kConsoleWidth) << "'" << line << "'";
    for (const CullerRow* row : cullerRows())
        EXPECT_NE(table.find("\n" + row->name + " "), std::string::npos) << row->name << table;
    // The long label is cut in its middle: the culler's name and the last value stay.
    EXPECT_NE(table.find("\nstatistical+...results=true "), std::string::npos) << table;
}

TEST(ConsoleTable, SaysWhatEachRowIsAndSortsConservativeFirstByTime) {
    RunRecord thresholded = record("chc threshold_pixels=4", "chc", 1.0);
    thresholded.approximation.threshold_pixels = 4;
    const std::vector<RunRecord> runs = {record("vfc", "vfc", 9.0),
                                         record("ideal", "ideal", 0.5),
                                         record("async", "async", 1.5),
                                         record("chc", "chc", 3.0),
                                         thresholded,
                                         record("statistical+", "statistical+", 2.0)};
    const std::vector<std::string> lines = linesOf(formatCompactTable(runs));
    ASSERT_GE(lines.size(), 7u);
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"statistical+", "cons"}, {"chc", "cons"},
        {"vfc", "cons"},          {"chc threshold_pixels=4", "approx"},
        {"async", "approx"},      {"ideal", "oracle"}};
    for (size_t i = 0; i < expected.size(); ++i) {
        const std::string& line = lines[i + 1];
        EXPECT_EQ(line.rfind(expected[i].first + " ", 0), 0u) << i << ": " << line;
        EXPECT_NE(line.find(" " + expected[i].second + " "), std::string::npos) << line;
    }
    EXPECT_NE(lines[1].find("4.50x"), std::string::npos) << "speedup over vfc: " << lines[1];
    EXPECT_NE(lines[1].find("4.00x"), std::string::npos) << "ratio to ideal: " << lines[1];
}

TEST(ConsoleTable, ShowsErrorColumnsOnlyWhenErrorWasMeasured) {
    RunRecord a = record("vfc", "vfc", 2.0);
    a.summary.error_measured = false;
    const std::string table = formatCompactTable({a});
    EXPECT_EQ(table.find("err px"), std::string::npos) << table;
    EXPECT_NE(formatCompactTable({record("vfc", "vfc", 2.0)}).find("err px"), std::string::npos);
}

TEST(Verdict, NamesTheFastestConservativeCullerAndItsMarginBeyondTheNoise) {
    const BenchResult result =
        resultOf({record("vfc", "vfc", 9.0), record("chc", "chc", 3.0),
                  record("statistical+", "statistical+", 2.0), record("ideal", "ideal", 0.5)});
    const std::vector<std::string> lines = verdictStatements(result, "out/x", true);
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0].rfind("verdict: fastest conservative culler statistical+, 1.50x faster than "
                             "chc (statistical+ 2.00 ms, chc 3.00 ms; faster on 30 of 30 frames",
                             0),
              0u)
        << lines[0];
    EXPECT_EQ(lines[1], "wrong pixels: none from a conservative culler, none at all");
    EXPECT_EQ(lines[2], "why chc lost: occsim why out/x --overdraw --algo chc");
    // On the console each statement is broken into lines that fit, continued with an indent.
    std::vector<std::string> console;
    for (const std::string& statement : lines) {
        const std::vector<std::string> w = wrapped(statement);
        console.insert(console.end(), w.begin(), w.end());
    }
    ASSERT_EQ(console.size(), 4u);
    EXPECT_EQ(console[0].rfind("verdict: fastest conservative culler statistical+", 0), 0u);
    EXPECT_EQ(console[1].rfind("  ", 0), 0u) << console[1];
    for (const std::string& line : console) EXPECT_LE(line.size(), kConsoleWidth) << line;
    EXPECT_EQ(console[2], lines[1]);
}

TEST(Verdict, CallsATieWhenTheMarginIsWithinTheFrameToFrameNoise) {
    // chc is faster on average, but only because of its odd frames: each is faster on half.
    RunRecord chc = record("chc", "chc", 1.0, 2.0);           // 1, 3, 1, 3, ...
    RunRecord masked = record("masked", "masked", 2.1, 0.0);  // 2.1 every frame
    const BenchResult result = resultOf({chc, masked});
    const std::vector<std::string> lines = verdictStatements(result, "out/x", false);
    ASSERT_FALSE(lines.empty());
    EXPECT_NE(lines[0].find("fastest conservative cullers chc and masked tie"), std::string::npos)
        << lines[0];
    EXPECT_NE(lines[0].find("faster on 15 of 30 frames"), std::string::npos) << lines[0];
    EXPECT_EQ(lines.back(),
              "why masked lost: rerun with --record objects, then occsim why out/x --overdraw "
              "--algo masked");
}

TEST(Verdict, WithRepetitionsTiesWhenTheMeansRangesOverlap) {
    RunRecord a = record("chc", "chc", 2.0), b = record("statistical+", "statistical+", 2.2);
    for (RunRecord* r : {&a, &b}) r->summary.repetitions = 3;
    a.summary.frame_ms_mean_min = 1.9, a.summary.frame_ms_mean_max = 2.3;
    b.summary.frame_ms_mean_min = 2.1, b.summary.frame_ms_mean_max = 2.4;
    EXPECT_NE(verdictStatements(resultOf({a, b}), "o", true)[0].find(
                  "tie (chc 2.00 ms, statistical+ 2.20 ms; their means over 3 repetitions overlap"),
              std::string::npos);
    a.summary.frame_ms_mean_max = 2.05;
    EXPECT_NE(
        verdictStatements(resultOf({a, b}), "o", true)[0].find("1.10x faster than statistical+"),
        std::string::npos);
}

TEST(Verdict, SaysLoudlyWhenAConservativeCullerDrewWrongPixels) {
    const BenchResult result =
        resultOf({record("masked", "masked", 1.0, 0.0, 17, 1), record("chc", "chc", 2.0),
                  record("async", "async", 0.5, 0.0, 300, 4)});
    const std::vector<std::string> lines = verdictStatements(result, "out/my run", true);
    ASSERT_GE(lines.size(), 2u);
    EXPECT_EQ(lines[1],
              "WRONG PIXELS from conservative cullers (a bug): masked 17 px, 1 missed; occsim why "
              "'out/my run' --missed");
    const std::vector<std::string> fine =
        verdictStatements(resultOf({record("chc", "chc", 2.0), record("vfc", "vfc", 3.0),
                                    record("async", "async", 0.5, 0.0, 300, 4)}),
                          "o", true);
    EXPECT_EQ(fine[1],
              "wrong pixels: none from a conservative culler; approximate: async 300 px, "
              "4 missed");
    EXPECT_EQ(verdictStatements(resultOf({record("chc", "chc", 2.0)}, false), "o", true)[1],
              "wrong pixels: not measured (--error renders ground truth and counts them)");
}

TEST(Verdict, IsEmptyWithoutATimedConservativeCuller) {
    EXPECT_TRUE(verdictStatements(resultOf({record("async", "async", 1.0)}), "o", true).empty());
    EXPECT_EQ(verdictStatements(resultOf({record("chc", "chc", 1.0)}), "o", true)[0],
              "verdict: chc is the only conservative culler timed (1.00 ms)");
}

TEST(Wrapped, BreaksAtSpacesIntoLinesThatFitAndIndentsTheRest) {
    std::string text;
    for (int i = 0; i < 60; ++i) text += "word" + std::to_string(i) + " ";
    const std::vector<std::string> lines = wrapped(text);
    ASSERT_GT(lines.size(), 3u);
    std::string joined;
    for (size_t i = 0; i < lines.size(); ++i) {
        EXPECT_LE(lines[i].size(), kConsoleWidth) << lines[i];
        EXPECT_EQ(lines[i].rfind("  ", 0) == 0, i > 0) << lines[i];
        joined += (i ? " " : "") + lines[i].substr(i ? 2 : 0);
    }
    EXPECT_EQ(joined + " ", text);
    // A word longer than a line stays whole, on a line of its own.
    const std::string path(150, 'p');
    EXPECT_EQ(wrapped("see " + path + " now"),
              (std::vector<std::string>{"see", "  " + path, "  now"}));
    // A line's own spacing stays: aligned columns keep their padding.
    EXPECT_EQ(wrapped("  vfc    frames  1-10"),
              (std::vector<std::string>{"  vfc    frames  1-10"}));
    // Columns, not bytes: "×" takes one.
    EXPECT_EQ(displayWidth("objects \xC3\x97 frames"), 16u);
    const std::string times = std::string(97, 'a') +
                              " \xC3\x97"
                              "b";  // 100 columns, 101 bytes
    EXPECT_EQ(wrapped(times), (std::vector<std::string>{times}));
    EXPECT_EQ(wrappedText(""), "");
    EXPECT_EQ(wrappedText("a b"), "a b\n");
    // Every line of a text, its indent kept and its blank lines too.
    const std::string indented = "    " + std::string(60, 'x') + " " + std::string(60, 'y');
    EXPECT_EQ(wrappedText("head\n\n" + indented + "\n"),
              "head\n\n    " + std::string(60, 'x') + "\n      " + std::string(60, 'y') + "\n");
}

}  // namespace
}  // namespace occsim
