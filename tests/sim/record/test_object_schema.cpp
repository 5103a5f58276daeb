// objects.sqlite's schema (sim/record/object_schema.h) against its docs page: every table, column
// and kind of reason.
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
    for (const char* table : {"run", "configurations", "objects", "reasons", "decisions",
                              "right_eye_decisions", "light_decisions"}) {
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

}  // namespace
}  // namespace occsim::testing
