// A run's output folder is one unit (sim/output/run_folder.h): replaced as a whole or not at
// all, never someone else's folder, never two runs at once; names become one path component.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "sim/output/atomic_file.h"
#include "sim/output/run_folder.h"

namespace occsim {
namespace {
namespace fs = std::filesystem;

fs::path tempDir(const std::string& name) {
    const fs::path p = fs::temp_directory_path() /
                       ("occsim-run-folder-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

void write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

std::string read(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The names in `dir`, sorted, so a test can say exactly what is there.
std::vector<std::string> namesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// An earlier run's folder: the marker, a summary and a picture the next run will not take.
fs::path oldRun(const fs::path& dir) {
    const fs::path run = dir / "run";
    fs::create_directories(run);
    write(run / kRunMarker, "");
    write(run / "summary.json", "old");
    write(run / "frame-00000-vfc.png", "old picture");
    return run;
}

TEST(RunFolder, PublishingReplacesTheWholeFolderAndLeavesNothingBeside) {
    const fs::path dir = tempDir("publish");
    const fs::path run = oldRun(dir);
    {
        StagedRunFolder folder(run);
        EXPECT_EQ(folder.staging().parent_path(), dir) << "staged beside the target";
        write(folder.staging() / "summary.json", "new");
        EXPECT_EQ(read(run / "summary.json"), "old") << "nothing changes before publishing";
        folder.publish();
    }
    EXPECT_EQ(namesIn(run), (std::vector<std::string>{kRunMarker, "summary.json"}))
        << "no stale picture of the old run";
    EXPECT_EQ(read(run / "summary.json"), "new");
    EXPECT_EQ(namesIn(dir), std::vector<std::string>{"run"});
    fs::remove_all(dir);
}

TEST(RunFolder, ARunThatFailsBeforePublishingLeavesTheOldRunAsItWas) {
    const fs::path dir = tempDir("unpublished");
    const fs::path run = oldRun(dir);
    {
        StagedRunFolder folder(run);
        write(folder.staging() / "frames.csv", "half of a new run");
    }  // as when a write fails or a frame throws: no publish()
    EXPECT_EQ(namesIn(run),
              (std::vector<std::string>{kRunMarker, "frame-00000-vfc.png", "summary.json"}));
    EXPECT_EQ(read(run / "summary.json"), "old");
    EXPECT_EQ(namesIn(dir), std::vector<std::string>{"run"}) << "the staging folder is gone";
    fs::remove_all(dir);
}

TEST(RunFolder, AFolderThatIsNotAnOccsimRunIsRefusedAndLeftAlone) {
    const fs::path dir = tempDir("not-ours");
    const fs::path mine = dir / "mine";
    fs::create_directories(mine);
    write(mine / "notes.txt", "keep me");
    EXPECT_FALSE(isReplaceableRunFolder(mine));
    try {
        StagedRunFolder folder(mine);
        ADD_FAILURE() << "a folder of someone else's files was accepted";
    } catch (const RunFolderError& e) {
        EXPECT_NE(std::string(e.what()).find(mine.string() + ": holds files that are not an "
                                                             "occsim run"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(read(mine / "notes.txt"), "keep me");
    EXPECT_EQ(namesIn(dir), std::vector<std::string>{"mine"}) << "no staging folder was made";

    // Absent, empty, an earlier run's folder, and one from before the marker: all replaceable.
    EXPECT_TRUE(isReplaceableRunFolder(dir / "absent"));
    fs::create_directories(dir / "empty");
    EXPECT_TRUE(isReplaceableRunFolder(dir / "empty"));
    EXPECT_TRUE(isReplaceableRunFolder(oldRun(dir)));
    fs::create_directories(dir / "older");
    write(dir / "older" / "summary.json", R"({"occsim": {"version": "0.9"}, "runs": []})");
    EXPECT_TRUE(isReplaceableRunFolder(dir / "older"));
    fs::create_directories(dir / "other");
    write(dir / "other" / "summary.json", R"({"name": "someone else's"})");
    EXPECT_FALSE(isReplaceableRunFolder(dir / "other"));
    fs::remove_all(dir);
}

// A crash between the two renames of a publication leaves the old run aside as <target>.old, and
// a crash during a run leaves its staging folder: the next run into the target cleans up both.
TEST(RunFolder, TheNextRunRecoversWhatAnInterruptedOneLeft) {
    const fs::path dir = tempDir("recover");
    const fs::path run = oldRun(dir);
    fs::rename(run, dir / ".run.old");
    fs::create_directories(dir / ".run.tmp-999999");
    write(dir / ".run.tmp-999999" / kRunMarker, "");
    {
        StagedRunFolder folder(run);
        EXPECT_EQ(read(run / "summary.json"), "old") << "the old run is back in place";
    }
    EXPECT_EQ(namesIn(dir), std::vector<std::string>{"run"});

    fs::create_directories(dir / ".run.old");
    write(dir / ".run.old" / kRunMarker, "");  // published, but not yet deleted
    {
        StagedRunFolder folder(run);
        folder.publish();
    }
    EXPECT_EQ(namesIn(dir), std::vector<std::string>{"run"});
    fs::remove_all(dir);
}

// A staging folder is another run's while its process lives (a `run --out` into the folder of a
// regress in progress once deleted regress's live staging): only a dead owner's is removed.
TEST(RunFolder, AStagingFolderOfALiveProcessIsNeverRemoved) {
    const fs::path dir = tempDir("live-staging");
    const fs::path run = oldRun(dir);
    const std::string live = ".run.tmp-" + std::to_string(::getppid());  // our parent lives
    fs::create_directories(dir / live);
    write(dir / live / kRunMarker, "");
    write(dir / live / "frames.csv", "half written");
    {
        StagedRunFolder folder(run);
        folder.publish();
    }
    EXPECT_EQ(read(dir / live / "frames.csv"), "half written");
    EXPECT_EQ(namesIn(dir), (std::vector<std::string>{live, "run"}));
    fs::remove_all(dir);
}

// A symlink as --out is followed before any work: the run is staged beside where it points and
// published there, even when the link dangles (its target not yet made).
TEST(RunFolder, ASymlinkedFolderIsFollowedBeforeTheRunEvenWhenItDangles) {
    const fs::path dir = tempDir("symlink");
    fs::create_directories(dir / "real");
    fs::create_symlink(dir / "real" / "run", dir / "link");
    EXPECT_EQ(resolvedFolder(dir / "link"), dir / "real" / "run");
    {
        StagedRunFolder folder(dir / "link");
        EXPECT_EQ(folder.target(), dir / "real" / "run");
        EXPECT_EQ(folder.staging().parent_path(), dir / "real");
        write(folder.staging() / "summary.json", "new");
        folder.publish();
    }
    EXPECT_EQ(read(dir / "link" / "summary.json"), "new") << "reached through the link";
    EXPECT_TRUE(fs::is_symlink(dir / "link"));
    // A link into a folder that cannot be made is refused when staging, before any frame.
    write(dir / "file", "a file");
    fs::create_symlink(dir / "file" / "run", dir / "bad-link");
    EXPECT_THROW(StagedRunFolder(dir / "bad-link"), RunFolderError);
    fs::remove_all(dir);
}

// A regress --out holds its own marker; another folder's files are refused, not written beside.
TEST(RunFolder, ARegressFolderIsClaimedOnlyWhenEmptyNewOrAnEarlierRegresss) {
    const fs::path dir = tempDir("regress-folder");
    claimRegressFolder(dir / "new");
    EXPECT_TRUE(fs::exists(dir / "new" / kRegressMarker));
    claimRegressFolder(dir / "new");  // again: it is ours
    fs::create_directories(dir / "notes");
    write(dir / "notes" / "todo.txt", "mine");
    EXPECT_THROW(checkRegressFolder(dir / "notes"), RunFolderError);
    EXPECT_EQ(namesIn(dir / "notes"), std::vector<std::string>{"todo.txt"});
    fs::create_directories(dir / "older");
    write(dir / "older" / "shard.json", R"({"format": "occsim-regress-shard", "version": 1})");
    EXPECT_NO_THROW(claimRegressFolder(dir / "older"));
    fs::remove_all(dir);
}

TEST(RunFolder, TheLockKeepsASecondRunOutOrMakesItWait) {
    const fs::path dir = tempDir("lock");
    auto first = std::make_unique<FolderLock>(dir / "run", false);
    try {
        FolderLock second(dir / "run", false);
        ADD_FAILURE() << "two runs locked one folder";
    } catch (const RunFolderBusy& e) {
        EXPECT_NE(std::string(e.what()).find("another occsim run is writing it"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("--wait-lock"), std::string::npos) << e.what();
    }

    std::atomic<bool> locked{false};
    std::thread waiter([&] {
        FolderLock waiting(dir / "run", true);
        locked = true;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(locked) << "the waiting run got the lock while the first held it";
    first.reset();
    waiter.join();
    EXPECT_TRUE(locked);
    EXPECT_NO_THROW(FolderLock(dir / "run", false)) << "a released lock is free";
    fs::remove_all(dir);
}

TEST(RunFolder, APlaceThatCannotBeWrittenIsFoundWhenStagingWithTheReason) {
    const fs::path dir = tempDir("unwritable");
    write(dir / "a-file", "");
    try {
        StagedRunFolder folder(dir / "a-file" / "run");
        ADD_FAILURE() << "a folder inside a file was staged";
    } catch (const RunFolderError& e) {
        EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("Not a directory"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(RunFolder, AWriteErrorNamesThePathAndTheOsReason) {
    const fs::path file = tempDir("write-error") / "missing-folder" / "summary.json";
    try {
        writeFileAtomically(file, "x");
        ADD_FAILURE() << "wrote into a missing folder";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "cannot write " + file.string() + ": No such file or directory");
    }
    fs::remove_all(file.parent_path().parent_path());
}

// A scenario named "/abs/path" or "../.." must not write outside out/: every name is one path
// component of out/<scenario>/<command>.
TEST(RunFolder, ScenarioAndCommandNamesAreOnePathComponentEach) {
    for (const char* name : {"/abs/path", "../..", "..", ".", "a/../../b", ""}) {
        const fs::path p = defaultOutputFolder(name, name);
        EXPECT_FALSE(p.is_absolute()) << name;
        const fs::path normal = p.lexically_normal();
        EXPECT_EQ(std::distance(normal.begin(), normal.end()), 3) << name << ": " << p;
        EXPECT_EQ(*normal.begin(), "out") << name << ": " << p;
    }
    EXPECT_EQ(defaultOutputFolder("teapots", "run-vfc"), fs::path("out/teapots/run-vfc"));
}

}  // namespace
}  // namespace occsim
