// The occsim executable's output folder as a user meets it: a run replaces it as a whole or
// leaves the old run as it was, refuses a folder that is not an occsim run, keeps a second run
// out, finds an unwritable folder before the first frame, and keeps a scenario's name inside out/.
// The full-disk and read-only cases need a file system of their own: a small tmpfs, mounted
// where the tests run as root (skipped elsewhere).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "shell_command.h"

namespace {
namespace fs = std::filesystem;

using occsim::testing::Outcome;
using occsim::testing::shell;

Outcome runOccsim(const std::string& args) { return shell(std::string(OCCSIM_EXE) + " " + args); }

const std::string kSmall = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";

fs::path tempDir(const std::string& name) {
    const auto p =
        fs::temp_directory_path() / ("occsim-cli-out-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

std::string read(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> namesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

size_t lineCount(const std::string& s) {
    return static_cast<size_t>(std::count(s.begin(), s.end(), '\n'));
}

// A small tmpfs of its own at `dir` (root only), unmounted when done.
struct SmallFileSystem {
    fs::path dir;
    bool mounted = false;
    SmallFileSystem(const std::string& name, const std::string& size) : dir(tempDir(name)) {
        mounted =
            shell("mount -t tmpfs -o size=" + size + " occsim-test " + dir.string()).exit_code == 0;
    }
    ~SmallFileSystem() {
        if (mounted) shell("umount " + dir.string());
        fs::remove_all(dir);
    }
};

TEST(CliOutputFolder, ARerunReplacesTheWholeFolderWithNoStalePicture) {
    const fs::path dir = tempDir("rerun");
    const fs::path out = dir / "out";
    const std::string run = "run " + kSmall + " --algo vfc --frames 6 --out " + out.string();
    const Outcome first = runOccsim(run + " --capture 0");
    ASSERT_EQ(first.exit_code, 0) << first.output;
    EXPECT_TRUE(fs::exists(out / "frame-00000-vfc.png"));

    const Outcome again = runOccsim(run);
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(namesIn(out),
              (std::vector<std::string>{".occsim-run", "frames.csv", "report.md", "summary.json"}))
        << "the first run's picture is gone with the rest of it";
    EXPECT_EQ(namesIn(dir), (std::vector<std::string>{".out.lock", "out"}))
        << "nothing staged is left beside it";
    fs::remove_all(dir);
}

TEST(CliOutputFolder, AFolderThatIsNotAnOccsimRunIsRefusedBeforeAnyWork) {
    const fs::path dir = tempDir("not-ours");
    const fs::path out = dir / "out";
    fs::create_directories(out / "teapots-small");
    std::ofstream(out / "notes.txt") << "keep me";
    std::ofstream(out / "teapots-small" / "notes.txt") << "keep me too";
    // An earlier regress's folder, whose scenario folder holds someone else's files.
    const fs::path regress_out = dir / "regress-out";
    fs::create_directories(regress_out / "teapots-small");
    std::ofstream(regress_out / ".occsim-regress") << "";
    std::ofstream(regress_out / "teapots-small" / "notes.txt") << "keep me too";
    const struct {
        std::string args, folder, what;
    } cases[] = {
        {"run " + kSmall + " --algo vfc --frames 6 --out " + out.string(), out.string(),
         "occsim run"},
        {"bench " + kSmall + " --algos vfc --frames 6 --out " + out.string(), out.string(),
         "occsim run"},
        {"regress " + kSmall + " --out " + out.string(), out.string(), "occsim regress run"},
        {"regress " + kSmall + " --out " + regress_out.string(),
         (regress_out / "teapots-small").string(), "occsim run"},
    };
    for (const auto& c : cases) {
        const Outcome o = runOccsim(c.args);
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << o.output;
        EXPECT_NE(o.output.find("occsim: --out " + c.folder + ": holds files that are not an " +
                                c.what + " ("),
                  std::string::npos)
            << o.output;
    }
    EXPECT_EQ(read(out / "notes.txt"), "keep me");
    EXPECT_EQ(namesIn(out), (std::vector<std::string>{"notes.txt", "teapots-small"}));
    EXPECT_EQ(namesIn(out / "teapots-small"), std::vector<std::string>{"notes.txt"});
    EXPECT_EQ(namesIn(regress_out / "teapots-small"), std::vector<std::string>{"notes.txt"});
    fs::remove_all(dir);
}

TEST(CliOutputFolder, ASecondRunIntoALockedFolderSaysSoOrWaits) {
    const fs::path dir = tempDir("locked");
    const fs::path out = dir / "out";
    const int fd = ::open((dir / ".out.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX), 0);  // as a run in progress holds it
    const std::string run = "run " + kSmall + " --algo vfc --frames 6 --out " + out.string();
    const Outcome busy = runOccsim(run);
    EXPECT_EQ(busy.exit_code, 1) << busy.output;
    EXPECT_NE(
        busy.output.find("occsim: --out " + out.string() + ": another occsim run is writing it"),
        std::string::npos)
        << busy.output;
    EXPECT_FALSE(fs::exists(out));
    const Outcome regress = runOccsim("regress " + kSmall + " --out " + out.string());
    EXPECT_EQ(regress.exit_code, 1) << regress.output;
    EXPECT_NE(
        regress.output.find("occsim: --out " + out.string() + ": another occsim run is writing it"),
        std::string::npos)
        << regress.output;
    EXPECT_FALSE(fs::exists(out));

    Outcome waited;
    std::thread waiting([&] { waited = runOccsim(run + " --wait-lock"); });
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::close(fd);  // the first run ends
    waiting.join();
    EXPECT_EQ(waited.exit_code, 0) << waited.output;
    EXPECT_TRUE(fs::exists(out / "summary.json"));
    fs::remove_all(dir);
}

// The disk fills during a rerun: the old run stays whole (no new frames.csv beside the old
// summary.json, as when each file was replaced on its own), and the error says why. The new run
// is a bench of three algorithms: its frames.csv fits where the old one was, its summary.json
// (two pages of tmpfs) does not.
TEST(CliOutputFolder, AFullDiskLeavesTheOldRunWholeAndNamesTheReason) {
    SmallFileSystem disk("full-disk", "2m");
    if (!disk.mounted) GTEST_SKIP() << "no tmpfs mount here (needs root)";
    const fs::path out = disk.dir / "out";
    const std::string args = kSmall + " --frames 6 --out " + out.string();
    const Outcome old = runOccsim("run " + args + " --algo vfc");
    ASSERT_EQ(old.exit_code, 0) << old.output;
    const std::string old_frames = read(out / "frames.csv"),
                      old_summary = read(out / "summary.json");

    // One free page: room for the staging folder's marker, not for the new run's files.
    const auto left = fs::space(disk.dir).available;
    ASSERT_GT(left, 16384u);
    std::ofstream(disk.dir / "filler", std::ios::binary)
        << std::string(static_cast<size_t>(left - 4096), 'x');
    const Outcome full = runOccsim("bench " + args + " --algos vfc,chc,statistical");
    EXPECT_EQ(full.exit_code, 1) << full.output;
    EXPECT_NE(full.output.find("No space left on device"), std::string::npos) << full.output;
    EXPECT_EQ(read(out / "frames.csv"), old_frames);
    EXPECT_EQ(read(out / "summary.json"), old_summary);
    EXPECT_EQ(namesIn(disk.dir), (std::vector<std::string>{".out.lock", "filler", "out"}));
}

// A read-only --out is found before the first frame: the message is about the folder, not about
// a picture taken during the run (--capture 0) or a file written after it.
TEST(CliOutputFolder, AReadOnlyOutIsFoundBeforeTheFirstFrame) {
    SmallFileSystem disk("read-only", "2m");
    if (!disk.mounted) GTEST_SKIP() << "no tmpfs mount here (needs root)";
    const fs::path out = disk.dir / "out";
    const std::string run = "run " + kSmall + " --algo vfc --frames 6 --out " + out.string();
    ASSERT_EQ(runOccsim(run).exit_code, 0);
    const std::string old_summary = read(out / "summary.json");
    ASSERT_EQ(shell("mount -o remount,ro " + disk.dir.string()).exit_code, 0);

    const Outcome o = runOccsim(run + " --capture 0");
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_EQ(o.output.rfind("occsim: --out " + out.string() + ": ", 0), 0u) << o.output;
    EXPECT_NE(o.output.find("Read-only file system"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("frame-00000"), std::string::npos) << o.output;
    EXPECT_EQ(read(out / "summary.json"), old_summary);
}

// A scenario's "name" is one path component of out/<name>/<command> in run, bench and view:
// "/abs/path" or "../.." must not write outside out/.
TEST(CliOutputFolder, AScenarioNameNeverLeavesOut) {
    const fs::path dir = tempDir("names");
    const std::string text = read(kSmall);
    const std::string from = "\"name\": \"teapots-small\"";
    ASSERT_NE(text.find(from), std::string::npos);
    const fs::path escaped = dir / "escaped";
    const struct {
        std::string name, folder;
    } cases[] = {
        {escaped.string(), "_" + escaped.string().substr(1)},  // absolute
        {"../../../escaped", "_._.._.._escaped"},              // from out/ in dir/work/here
    };
    for (const auto& c : cases) {
        std::string named = text;
        named.replace(named.find(from), from.size(), "\"name\": \"" + c.name + "\"");
        const fs::path work = dir / "work" / "here";
        fs::create_directories(work);
        std::ofstream(work / "named.json") << named;
        for (const char* command : {"run named.json --algo vfc", "bench named.json --algos vfc"}) {
            const Outcome o =
                shell("cd " + work.string() + " && " + OCCSIM_EXE + " " + command + " --frames 6");
            EXPECT_EQ(o.exit_code, 0) << command << ": " << o.output;
        }
        std::string safe = c.folder;
        std::replace(safe.begin(), safe.end(), '/', '_');
        EXPECT_TRUE(fs::exists(work / "out" / safe / "run-vfc" / "summary.json")) << c.name;
        EXPECT_TRUE(fs::exists(work / "out" / safe / "bench" / "summary.json")) << c.name;
        EXPECT_FALSE(fs::exists(escaped)) << c.name;
        fs::remove_all(dir / "work");
    }
    fs::remove_all(dir);
}

}  // namespace
