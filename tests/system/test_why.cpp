// `occsim why` and `--record` through the executable: bad input is one line naming the flag or
// file, the place and what was expected, exit code 2, before any work: a --record value not
// listed, a folder with no database, an unknown object name or index, a frame outside the run, a
// configuration not in it, a database from another occsim version, a truncated or corrupt one.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "objects_fixtures.h"
#include "sim/record/object_schema.h"

namespace occsim::testing {
namespace {

namespace fs = std::filesystem;

const std::string kExe = OCCSIM_EXE;

Outcome occsim(const std::string& args) { return shell(kExe + " " + args); }

// Exit code 2 and exactly one line, holding `text`.
void expectBadInput(const Outcome& o, const std::string& text, const std::string& what) {
    EXPECT_EQ(o.exit_code, 2) << what << ": " << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << what << ": " << o.output;
    EXPECT_NE(o.output.find(text), std::string::npos) << what << ": " << o.output;
}

TEST(RecordFlag, AValueNotListedIsOneLineWithExitCode2BeforeAnyWork) {
    TempDir dir;
    const fs::path scenario = writeWalledYard(dir, 3);
    const fs::path out = dir.path() / "out";
    for (const std::string command : {"run", "bench"}) {
        expectBadInput(
            occsim(command + " " + scenario.string() + " --record object --out " + out.string()),
            "--record: 'object' is not something a run records; expected: objects", command);
        EXPECT_FALSE(fs::exists(out)) << command << ": refused before any work";
    }
    expectBadInput(
        occsim("regress " + scenario.string() + " --record objects,frames --out " + out.string()),
        "--record: 'frames' is not something a run records; expected: objects", "regress");
    EXPECT_FALSE(fs::exists(out));
}

// One recorded run of the walled yard (vfc and async, 12 frames) for the questions below.
class WhyBadInput : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new TempDir;
        const fs::path scenario = writeWalledYard(*dir_, 12);
        const Outcome o = shell(kExe + " bench " + scenario.string() +
                                " --algos vfc,async --deterministic-latency 20 --record objects "
                                "--out " +
                                run().string());
        ASSERT_EQ(o.exit_code, 0) << o.output;
    }
    static void TearDownTestSuite() {
        delete dir_;
        dir_ = nullptr;
    }
    static fs::path run() { return dir_->path() / "run"; }
    // A copy of the run, its database changed by `change`.
    static fs::path copyOfRun(const std::string& name) {
        const fs::path copy = dir_->path() / name;
        fs::remove_all(copy);
        fs::copy(run(), copy, fs::copy_options::recursive);
        return copy;
    }
    static TempDir* dir_;
};
TempDir* WhyBadInput::dir_ = nullptr;

TEST_F(WhyBadInput, AnUnknownObjectFrameOrConfigurationIsNamedWithWhatWasExpected) {
    const std::string r = "why " + run().string();
    ASSERT_EQ(occsim(r + " --object truck --frame 3").exit_code, 0);
    expectBadInput(occsim(r + " --object truk"),
                   "--object 'truk': no object of that name; did you mean 'truck'?", "near name");
    expectBadInput(occsim(r + " --object bulldozer"),
                   "--object 'bulldozer': no object of that name; expected an object's index or "
                   "its name",
                   "unknown name");
    expectBadInput(occsim(r + " --object 7"),
                   "--object 7: no such object; the run has 7 objects (0-6)", "index");
    expectBadInput(occsim(r + " --object truck --frame 12"),
                   "--frame 12: outside the run; frames 0-11 were recorded", "frame");
    expectBadInput(occsim(r + " --object truck --algo chc"),
                   "--algo chc: not in this run; expected one of: vfc, async", "algo");
    expectBadInput(occsim(r), "expected one of --object ID|NAME, --overdraw or --missed",
                   "no question");
    expectBadInput(occsim(r + " --missed --frame 2"), "--frame: goes with --object", "frame");
}

// The case: `--object 3` answered for index 3 while another object was named "3", with no
// note. Digits that are both are refused; "#3" is always the index; digits past the last index
// that name one object are that object.
TEST_F(WhyBadInput, DigitsThatAreAnIndexAndAnotherObjectsNameAreRefusedNotGuessed) {
    const fs::path renamed = copyOfRun("numeric-names");
    {
        sql::Database db(renamed / kObjectsDatabaseFile, sql::Database::Mode::Create);
        db.exec("UPDATE objects SET name = '3' WHERE object = 5");
        db.exec("UPDATE objects SET name = '9' WHERE object = 4");
        db.close();
    }
    std::string name3;
    {
        sql::Database db(renamed / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
        sql::Statement s = db.prepare("SELECT name FROM objects WHERE object = 3");
        ASSERT_TRUE(s.step());
        name3 = s.text(0);
    }
    const std::string r = "why " + renamed.string();
    expectBadInput(occsim(r + " --object 3 --frame 2"),
                   "--object 3: both object 3 ('" + name3 +
                       "') and the name of object 5; expected #3 for the index, or the named "
                       "object's index",
                   "ambiguous");
    const Outcome by_index = occsim(r + " --object '#3' --frame 2");
    EXPECT_EQ(by_index.exit_code, 0) << by_index.output;
    EXPECT_EQ(by_index.output.rfind("object 3 '" + name3 + "'", 0), 0) << by_index.output;
    const Outcome by_name = occsim(r + " --object 5 --frame 2");
    EXPECT_EQ(by_name.exit_code, 0) << by_name.output;
    EXPECT_EQ(by_name.output.rfind("object 5 '3'", 0), 0) << by_name.output;
    const Outcome past_the_last = occsim(r + " --object 9 --frame 2");
    EXPECT_EQ(past_the_last.exit_code, 0) << past_the_last.output;
    EXPECT_EQ(past_the_last.output.rfind("object 4 '9'", 0), 0) << past_the_last.output;
    expectBadInput(occsim(r + " --object '#9'"),
                   "--object #9: no such object; the run has 7 objects (0-6)", "#9 is an index");
}

TEST_F(WhyBadInput, AFolderWithoutADatabaseOrWithoutAFolderIsNamed) {
    const fs::path plain = dir_->path() / "plain";
    fs::create_directories(plain);
    expectBadInput(occsim("why " + plain.string() + " --missed"),
                   plain.string() +
                       ": no objects.sqlite; expected a run recorded with --record "
                       "objects",
                   "no database");
    expectBadInput(occsim("why " + (dir_->path() / "nowhere").string() + " --missed"),
                   (dir_->path() / "nowhere").string() + ": no such folder", "no folder");
}

TEST_F(WhyBadInput, ADatabaseFromAnotherVersionATruncatedOrACorruptOneIsRefused) {
    {
        const fs::path other = copyOfRun("other-version");
        sql::Database db(other / kObjectsDatabaseFile, sql::Database::Mode::Create);
        db.exec("UPDATE run SET occsim_version = '0.0.1'");
        db.close();
        expectBadInput(occsim("why " + other.string() + " --missed"),
                       "objects.sqlite: written by occsim 0.0.1 (database format " +
                           std::to_string(kObjectsFormatVersion) + "); this is occsim ",
                       "another version");
    }
    {
        const fs::path cut = copyOfRun("truncated");
        const fs::path file = cut / kObjectsDatabaseFile;
        fs::resize_file(file, fs::file_size(file) / 2);
        expectBadInput(occsim("why " + cut.string() + " --missed"),
                       "objects.sqlite: truncated: ", "truncated");
    }
    {
        const fs::path bad = copyOfRun("corrupt");
        const fs::path file = bad / kObjectsDatabaseFile;
        // Every page after the first overwritten with noise: the header still says SQLite.
        const auto size = fs::file_size(file);
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(4096);
        for (uintmax_t i = 4096; i < size; ++i) f.put(static_cast<char>((i * 7919) & 0xff));
        f.close();
        const Outcome o = occsim("why " + bad.string() + " --missed");
        expectBadInput(o, "objects.sqlite: ", "corrupt");
        EXPECT_TRUE(o.output.find("corrupt") != std::string::npos ||
                    o.output.find("unreadable") != std::string::npos)
            << o.output;
    }
    {
        const fs::path text = copyOfRun("not-sqlite");
        std::ofstream(text / kObjectsDatabaseFile) << "frame,config\n";
        expectBadInput(occsim("why " + text.string() + " --missed"),
                       "objects.sqlite: not an SQLite database", "not a database");
    }
}

}  // namespace
}  // namespace occsim::testing
