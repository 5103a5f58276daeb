// Every list of cullers the docs give names every registered one (issue 56: the README's console
// sample showed 8 of 12, docs/architecture.md's list named 9). A list is marked by the line
// `<!-- every culler -->` before it: a paragraph or bullet list (up to the next blank line) names
// each culler as `name`; a code block (the README's console sample) has a row starting with it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

constexpr const char* kMarker = "<!-- every culler -->";

struct MarkedList {
    std::string where;  // file:line of the marker
    std::string text;
    bool code = false;
};

std::vector<MarkedList> markedLists(const fs::path& file, const std::string& shown) {
    std::ifstream in(file);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    std::vector<MarkedList> lists;
    for (size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].find(kMarker) == std::string::npos) continue;
        MarkedList list{shown + ":" + std::to_string(i + 1), "", false};
        size_t j = i + 1;
        list.code = j < lines.size() && lines[j].rfind("```", 0) == 0;
        if (list.code) {
            for (++j; j < lines.size() && lines[j].rfind("```", 0) != 0; ++j)
                list.text += lines[j] + "\n";
        } else {
            for (; j < lines.size() && !lines[j].empty(); ++j) list.text += lines[j] + "\n";
        }
        lists.push_back(list);
    }
    return lists;
}

// The registered cullers a list lacks.
std::vector<std::string> missingFrom(const MarkedList& list) {
    std::vector<std::string> missing;
    for (const CullerRow* row : cullerRows()) {
        if (!row->source.empty()) continue;  // a plugin's: not the docs' to list
        const std::string named = list.code ? "\n" + row->name + " " : "`" + row->name + "`";
        if (("\n" + list.text).find(named) == std::string::npos) missing.push_back(row->name);
    }
    return missing;
}

TEST(CullerLists, EveryMarkedListInTheDocsNamesEveryRegisteredCuller) {
    const fs::path root(OCCSIM_SOURCE_DIR);
    std::vector<fs::path> files = {root / "README.md"};
    for (const fs::directory_entry& e : fs::directory_iterator(root / "docs"))
        if (e.path().extension() == ".md") files.push_back(e.path());
    size_t lists = 0;
    for (const fs::path& file : files) {
        for (const MarkedList& list :
             markedLists(file, file.lexically_relative(root).generic_string())) {
            ++lists;
            for (const std::string& name : missingFrom(list))
                ADD_FAILURE() << list.where << ": the list does not name " << name;
        }
    }
    // The README's sample and intro and the architecture page's list at least.
    EXPECT_GE(lists, 3u);
}

// The check can fail: a marked list that lacks a culler names it, in prose and in a sample.
TEST(CullerLists, TheCheckNamesACullerAMarkedListLacks) {
    const fs::path file =
        fs::temp_directory_path() / ("occsim-culler-lists-" + std::to_string(::getpid()) + ".md");
    std::ofstream(file) << "text\n"
                        << kMarker << "\n- `vfc` and `chc`\n- `ideal`\n\nafter `hzb`\n"
                        << kMarker << "\n```\nconfiguration  kind\nvfc  cons\nchc++  cons\n```\n";
    const std::vector<MarkedList> lists = markedLists(file, "planted.md");
    ASSERT_EQ(lists.size(), 2u);
    EXPECT_EQ(lists[0].where, "planted.md:2");
    const std::vector<std::string> prose = missingFrom(lists[0]);
    EXPECT_NE(std::find(prose.begin(), prose.end(), "hzb"), prose.end()) << "after the list";
    EXPECT_EQ(std::find(prose.begin(), prose.end(), "chc"), prose.end());
    const std::vector<std::string> sample = missingFrom(lists[1]);
    EXPECT_NE(std::find(sample.begin(), sample.end(), "chc"), sample.end()) << "chc++ is not chc";
    EXPECT_EQ(std::find(sample.begin(), sample.end(), "chc++"), sample.end());
    fs::remove(file);
}

}  // namespace
}  // namespace occsim
