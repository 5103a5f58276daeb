// What a shard of a regression run leaves for the merge (sim/regress/shard_result.h): shard.json
// and junit.xml read back as written, a file of another format or version refused naming the
// file and the place, and the scenario set's id, which changes when a scenario file does.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "merge_files.h"
#include "sim/regress/shard_result.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

std::string readError(const fs::path& dir) {
    try {
        readShardResult(dir);
    } catch (const ResultFileError& e) {
        return e.what();
    }
    return "";
}

TEST(ShardResult, AShardReadsBackAsWritten) {
    const fs::path dir = writeShard(freshDir("shard-roundtrip"), 1, 3);
    const ShardResult r = readShardResult(dir);
    EXPECT_EQ(r.dir, dir);
    EXPECT_EQ(r.shard.index, 1u);
    EXPECT_EQ(r.shard.count, 3u);
    EXPECT_EQ(r.set.id, sixScenarios().id);
    EXPECT_EQ(r.set.ids, sixScenarios().ids);
    ASSERT_EQ(r.report.scenarios.size(), 2u) << "b and e of a..f";
    EXPECT_EQ(r.report.scenarios[0].id, "b");
    EXPECT_EQ(r.report.scenarios[1].id, "e");
    EXPECT_TRUE(r.report.scenarios[1].skipped);
    EXPECT_EQ(shardResultJson(r), readFile(dir / "shard.json"));
}

TEST(ShardResult, AnotherFormatOrVersionIsRefusedNamingTheFileAndThePlace) {
    const fs::path dir = writeShard(freshDir("shard-version"), 0, 2);
    const std::string text = readFile(dir / "shard.json");
    std::string edited = text;
    edited.replace(edited.find("\"version\": 2"), 12, "\"version\": 9");
    writeFile(dir / "shard.json", edited);
    const std::string version = readError(dir);
    EXPECT_NE(version.find("shard.json"), std::string::npos) << version;
    EXPECT_NE(version.find("/version: shard result format version 9; this program reads version 2"),
              std::string::npos)
        << version;
    writeFile(dir / "shard.json", "{\"format\": \"something else\"}");
    EXPECT_NE(readError(dir).find("not a shard result of occsim regress"), std::string::npos)
        << readError(dir);
    fs::remove(dir / "shard.json");
    EXPECT_NE(readError(dir).find("shard.json: missing"), std::string::npos) << readError(dir);
}

TEST(ShardResult, TheSetsIdFollowsItsFilesNamesAndContents) {
    const fs::path dir = freshDir("shard-set");
    const fs::path small = fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small";
    fs::copy_file(small / "teapots-small.json", dir / "b.json");
    fs::copy_file(small / "city-small.json", dir / "a.json");
    const ScenarioSet set = scenarioSetOf({dir});
    ASSERT_EQ(set.scenarios.size(), 2u);
    EXPECT_LT(set.scenarios[0], set.scenarios[1]) << "sorted";
    EXPECT_EQ(set.ids.size(), 2u);
    EXPECT_EQ(scenarioSetOf({dir}).id, set.id) << "the same files, the same id";
    writeFile(dir / "b.json", readFile(dir / "b.json") + "\n");
    EXPECT_NE(scenarioSetOf({dir}).id, set.id) << "an edited file";
    fs::rename(dir / "b.json", dir / "c.json");
    const std::string renamed = scenarioSetOf({dir}).id;
    EXPECT_NE(renamed, set.id);
    fs::remove(dir / "a.json");
    EXPECT_NE(scenarioSetOf({dir}).id, renamed) << "a removed file";
}

}  // namespace
}  // namespace occsim
