// A run's output folder as one unit: the folder holds the previous run or the new one, never a
// mix. A run writes into a fresh staging folder beside its target (<parent>/.<name>.tmp-<pid>) and
// publishes it as a whole at the end (the old folder renamed aside to <parent>/.<name>.old, the new
// one renamed in, the old one deleted); whatever fails before, the old folder stays as it was. A
// lock file beside the target (<parent>/.<name>.lock, flock(2), so a dead process never holds it)
// keeps two runs out of one folder. Only folders that hold an occsim run (the .occsim-run marker
// every run folder gets, or an older occsim summary.json), empty folders and absent ones are
// replaced: anything else is not ours to delete.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "occsim/culling/contract/input_error.h"

namespace occsim {

// The target cannot be used: it holds something other than an occsim run, or it (or its parent)
// cannot be written. Found before any work; the message starts with the target's path.
struct RunFolderError : InputError {
    using InputError::InputError;
};

// Another run holds the target's lock (and the caller asked not to wait).
struct RunFolderBusy : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The marker file a published run folder holds.
inline constexpr const char* kRunMarker = ".occsim-run";
// The marker file a regress --out folder holds: its scenario folders are run folders, each
// replaced on its own, and shard.json and junit.xml beside them are rewritten by every regress.
inline constexpr const char* kRegressMarker = ".occsim-regress";

// The folder a path names once its symlinks are followed (a link to a link, a link to a folder
// not yet made), "out/run/" and "out/run" one folder: what a run writes is found where the link
// points, before the run, never after its last frame.
std::filesystem::path resolvedFolder(const std::filesystem::path& folder);

// A regress --out folder: absent, empty, or one an earlier regress wrote (its marker, or an older
// occsim shard.json). checkRegressFolder() throws RunFolderError otherwise, or when it cannot be
// written; claimRegressFolder() checks, then creates the folder and its marker.
void checkRegressFolder(const std::filesystem::path& folder);
void claimRegressFolder(const std::filesystem::path& folder);

// out/<scenario name>/<command folder>, each name made one safe path component, so that a
// scenario named "/abs" or "../.." still writes under out/.
std::filesystem::path defaultOutputFolder(const std::string& scenario_name,
                                          const std::string& command_folder);

// True when `folder` is absent, empty, or holds an occsim run (see above).
bool isReplaceableRunFolder(const std::filesystem::path& folder);

// Throws RunFolderError when `folder` exists and is not replaceable, or cannot be written.
void checkRunFolder(const std::filesystem::path& folder);

// An exclusive lock on <parent>/.<name>.lock, held until destroyed. With wait, blocks until the
// holder lets go; without, throws RunFolderBusy. Throws RunFolderError when the lock file cannot be
// created (the parent folder is created when missing).
class FolderLock {
  public:
    FolderLock(const std::filesystem::path& folder, bool wait);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

  private:
    int fd_ = -1;
};

// The staging folder of one run into `target` (its symlinks followed: resolvedFolder()). The
// caller holds the target's lock (FolderLock). The constructor checks the target
// (checkRunFolder), finishes a publication a crash interrupted (a staging folder left by a run
// whose process is gone), and creates the staging folder with its marker, so that an unwritable
// place is found before any work. Destroyed unpublished, the staging folder is removed and the
// target left as it was.
class StagedRunFolder {
  public:
    explicit StagedRunFolder(std::filesystem::path target);
    ~StagedRunFolder();
    StagedRunFolder(const StagedRunFolder&) = delete;
    StagedRunFolder& operator=(const StagedRunFolder&) = delete;

    const std::filesystem::path& staging() const { return staging_; }  // write here
    const std::filesystem::path& target() const { return target_; }

    // Swaps the staging folder in place of the target. Throws std::runtime_error naming the
    // path and the OS reason; the target then holds the old run (or, after a crash between the
    // two renames, <parent>/.<name>.old does, and the next run puts it back).
    void publish();

  private:
    std::filesystem::path target_, staging_;
    bool published_ = false;
};

}  // namespace occsim
