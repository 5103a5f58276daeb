// The viewer's key table (sim/view/key_bindings.h): every action key is a key a window reports and
// no key does two things; docs/viewer.md lists the program's own keys and algorithms.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <sstream>

#include "occsim/culling/registry/registry.h"
#include "sim/view/key_bindings.h"
#include "sim/view/view_script.h"
#include "view_files.h"

namespace occsim {
namespace {

using namespace view_files;

TEST(ViewKeys, EveryActionKeyIsAKeyAWindowReportsAndNoKeyDoesTwoThings) {
    std::set<std::string> keys;
    for (const KeyBinding& b : actionKeys()) {
        if (b.keys == "1-9") continue;
        EXPECT_FALSE(findKeyName(b.keys).empty()) << b.keys;
        EXPECT_TRUE(keys.insert(std::string(b.keys)).second) << b.keys << " is bound twice";
        uint32_t index = 0;
        EXPECT_EQ(actionForKey(b.keys, &index), b.action) << b.keys;
    }
    // The flying keys act while held; an action on one of them would fire on every flight.
    for (const char* fly : {"w", "a", "s", "d", "e", "q", "shift", "up", "down", "left", "right"}) {
        EXPECT_EQ(keys.count(fly), 0u) << fly;
    }
    uint32_t index = 99;
    EXPECT_EQ(actionForKey("3", &index), ViewAction::SelectAlgorithm);
    EXPECT_EQ(index, 2u);
    EXPECT_EQ(actionForKey("w", &index), ViewAction::None);
}
// The keys table lists exactly the program's action keys; the digit keys name the algorithms in
// the program's order; every "press DIGIT  # name" in the docs presses that algorithm; --algo
// lists every built-in algorithm.
TEST(ViewDocs, TheKeysAndAlgorithmsOfViewerMdAreTheProgramsOwn) {
    const std::string doc = readText(std::filesystem::path(OCCSIM_SOURCE_DIR) / "docs/viewer.md");
    const size_t keys_at = doc.find("## Keys");
    ASSERT_NE(keys_at, std::string::npos);
    const std::string keys = doc.substr(keys_at, doc.find("Flying", keys_at) - keys_at);
    size_t rows = 0;
    for (size_t at = keys.find("\n| `"); at != std::string::npos; at = keys.find("\n| `", at + 1))
        ++rows;
    EXPECT_EQ(rows, actionKeys().size()) << keys;
    for (const KeyBinding& k : actionKeys()) {
        EXPECT_NE(keys.find("\n| `" + std::string(k.keys) + "` |"), std::string::npos) << k.keys;
    }
    const auto& all = cullerRows();
    std::string digits;
    for (size_t i = 0; i < all.size() && i < 9; ++i) {
        digits += (i ? ", `" : "`") + std::to_string(i + 1) + "` " + std::string(all[i]->name);
    }
    EXPECT_NE(keys.find(digits), std::string::npos) << "expected the digit keys as: " << digits;
    std::istringstream lines(doc);
    std::string line;
    size_t presses = 0;
    while (std::getline(lines, line)) {
        unsigned digit = 0;
        char name[64] = {};
        if (std::sscanf(line.c_str(), "press %u # %63[^: ]", &digit, name) == 2 && digit >= 1 &&
            digit <= all.size()) {
            EXPECT_EQ(std::string(name), all[digit - 1]->name) << line;
            ++presses;
        }
    }
    EXPECT_GT(presses, 0u) << "the session example presses an algorithm's digit";
    const size_t algo_at = doc.find("| `--algo NAME` |");
    ASSERT_NE(algo_at, std::string::npos);
    const std::string algo_row = doc.substr(algo_at, doc.find('\n', algo_at) - algo_at);
    for (const CullerRow* a : all) {
        EXPECT_NE(algo_row.find("`" + std::string(a->name) + "`"), std::string::npos) << a->name;
    }
}

}  // namespace
}  // namespace occsim
