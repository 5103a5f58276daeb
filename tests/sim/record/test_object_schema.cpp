// objects.sqlite without a run: the schema against its docs page, the file checks that find a
// truncated database, the wording of `occsim why` for each kind of reason, frame ranges.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "objects_fixtures.h"
#include "sim/output/object_highlights.h"
#include "sim/record/object_database.h"
#include "sim/record/object_schema.h"
#include "sim/record/why.h"

namespace occsim::testing {
namespace {

namespace fs = std::filesystem;

TEST(ObjectsSchema, DocsObjectsMdListsEveryTableColumnAndEveryReasonKind) {
    TempDir dir;
    sql::Database db(dir.path() / "schema.sqlite", sql::Database::Mode::Create);
    db.exec(kObjectsSchema);
    db.exec(kObjectsIndexes);
    const std::string doc = fileText(fs::path(OCCSIM_SOURCE_DIR) / "docs/objects.md");
    ASSERT_FALSE(doc.empty());
    uint32_t columns = 0;
    for (const char* table : {"run", "configurations", "objects", "reasons", "decisions"}) {
        EXPECT_NE(doc.find("### `" + std::string(table) + "`"), std::string::npos) << table;
        sql::Statement s =
            db.prepare("SELECT name FROM pragma_table_xinfo('" + std::string(table) + "')");
        while (s.step()) {
            ++columns;
            EXPECT_NE(doc.find("| `" + s.text(0) + "` |"), std::string::npos)
                << table << "." << s.text(0) << " is not in docs/objects.md";
        }
    }
    EXPECT_GT(columns, 30u);
    for (uint32_t k = 0; k < kDecisionKinds; ++k) {
        std::string row = "| ";
        row.append(std::to_string(k)).append(" | `");
        row.append(decisionKindName(static_cast<DecisionKind>(k))).append("` |");
        EXPECT_NE(doc.find(row), std::string::npos) << row;
    }
    sql::Statement indexes = db.prepare(
        "SELECT name FROM sqlite_master WHERE type = 'index' "
        "AND name LIKE 'decisions_%'");
    while (indexes.step()) {
        std::string quoted(1, '`');  // appended: GCC 12 warns falsely (-Wrestrict) on "`" + ...
        quoted.append(indexes.text(0)).push_back('`');
        EXPECT_NE(doc.find(quoted), std::string::npos) << quoted;
    }
}

TEST(ObjectsSchema, AFileShorterThanItsHeaderDeclaresIsFoundTruncated) {
    TempDir dir;
    const fs::path file = dir.path() / "db.sqlite";
    {
        sql::Database db(file, sql::Database::Mode::Create);
        db.exec(kObjectsSchema);
        db.exec("CREATE TABLE filler (x BLOB); INSERT INTO filler VALUES (zeroblob(100000));");
        db.close();
    }
    EXPECT_EQ(sqliteFileProblem(file), "");
    const auto size = fs::file_size(file);
    fs::resize_file(file, size / 2);
    EXPECT_EQ(sqliteFileProblem(file), "truncated: " + std::to_string(size / 2) + " bytes of the " +
                                           std::to_string(size) + " its header declares");
    fs::resize_file(file, 40);
    EXPECT_EQ(sqliteFileProblem(file).rfind("truncated: 40 bytes", 0), 0u);
    std::ofstream(file) << "not a database at all";
    EXPECT_EQ(sqliteFileProblem(file), "not an SQLite database");
    std::ofstream(file).close();
    EXPECT_EQ(sqliteFileProblem(file), "empty; expected an SQLite database");
}

RecordedDecision decision(DecisionKind kind, uint32_t frame, bool drawn, uint32_t truth) {
    RecordedDecision d;
    d.frame = frame;
    d.drawn = drawn;
    d.why.kind = kind;
    d.truth_pixels = truth;
    return d;
}

TEST(WhyWording, EachReasonIsSaidInWordsWithTheQueryFrameAndGroundTruth) {
    RecordedDecision hid = decision(DecisionKind::CulledOnQuery, 178, false, 412);
    hid.why.query_frame = 176;
    hid.error_pixels = 300;
    EXPECT_EQ(describeDecision(hid),
              "not drawn: the query issued at frame 176 (2 frames before) answered occluded (0 "
              "samples); ground truth sees 412 px (missed: 300 error pixels)");

    RecordedDecision stats = decision(DecisionKind::DrawnOnStatistics, 30, true, 0);
    stats.why.query_frame = 12;
    stats.why.count = 3;
    stats.why.history = 4;
    stats.why.interval = 1.25f;
    stats.why.next_query = 1.65f;
    EXPECT_EQ(describeDecision(stats),
              "drawn: no query: its last query, issued at frame 12 (18 frames before), found it "
              "visible (3 of its last 4 answers visible); the decay curve gives 1.25 s, so it is "
              "queried again after 1.65 s; ground truth sees 0 px (drawn while hidden)");

    RecordedDecision pyramid = decision(DecisionKind::CulledOnPyramid, 5, false, 0);
    pyramid.why.phase = 2;
    pyramid.why.level = 3;
    EXPECT_EQ(describeDecision(pyramid),
              "not drawn: the depth pyramid hides it (phase 2, level 3); ground truth sees 0 px");

    RecordedDecision same = decision(DecisionKind::DrawnOnQuery, 9, true, 40);
    same.why.query_frame = 9;
    same.why.samples = 1;
    same.why.flags = kDecisionWaited;
    EXPECT_EQ(describeDecision(same),
              "drawn: the query issued this frame answered visible (1 sample, waited for); "
              "ground truth sees 40 px");

    RecordedDecision skipped = decision(DecisionKind::DrawnConditional, 4, false, 0);
    skipped.why.query_frame = 4;
    EXPECT_NE(describeDecision(skipped).find("the device skipped it"), std::string::npos);
    // Every kind has words of its own.
    for (uint32_t k = 0; k < kDecisionKinds; ++k) {
        const std::string s = describeDecision(decision(static_cast<DecisionKind>(k), 1, false, 0));
        EXPECT_GT(s.size(), std::string("not drawn: ; ground truth sees 0 px").size() + 8) << k;
    }
}

TEST(WhyWording, FramesAreListedAsRanges) {
    EXPECT_EQ(frameRanges({}), "");
    EXPECT_EQ(frameRanges({7}), "7");
    EXPECT_EQ(frameRanges({3, 4, 5, 9, 12, 13, 14}), "3-5, 9, 12-14");
}

}  // namespace
}  // namespace occsim::testing
