// The checks on an objects.sqlite file (sim/record/object_database.h) before it is read: a file
// shorter than its header declares, one that is not a database, an empty one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "objects_fixtures.h"
#include "sim/record/object_database.h"
#include "sim/record/object_schema.h"

namespace occsim::testing {
namespace {

namespace fs = std::filesystem;

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

}  // namespace
}  // namespace occsim::testing
