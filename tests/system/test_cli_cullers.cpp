// Every culler as the docs and the command line name it: docs/cullers.md is the registry's own
// output, no page types an incomplete list of the cullers, and sweeps and ablations read the
// descriptors.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"

using namespace occsim::cli_run;

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
