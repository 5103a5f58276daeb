#include "sim/output/run_folder.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "sim/output/atomic_file.h"

namespace occsim {
namespace fs = std::filesystem;
namespace {

// "out/run/" and "out/run" are one folder; "." and ".." are made absolute so that they have a
// name to put a suffix on.
fs::path lexicalFolder(const fs::path& folder) {
    fs::path p = folder.lexically_normal();
    if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();
    if (p.empty() || p.filename() == "." || p.filename() == "..") {
        p = fs::absolute(p).lexically_normal();
        if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();
    }
    return p;
}

// Whether the process that named a staging folder .<name>.tmp-<pid> still runs: its folder is
// then another run's, in use, even where no lock says so.
bool ownerAlive(const std::string& staging_name, const std::string& prefix) {
    const std::string pid_text = staging_name.substr(prefix.size());
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos)
        return false;
    const long pid = std::strtol(pid_text.c_str(), nullptr, 10);
    if (pid <= 0 || pid == ::getpid()) return false;
    return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

// A hidden sibling of the folder: .<name><suffix> beside it. Hidden so that a glob over run
// folders (`occsim merge out/shard-*`, as docs/regression.md writes it) never picks up a lock,
// a staging folder or an old run set aside.
fs::path beside(const fs::path& folder, const std::string& suffix) {
    std::string name(1, '.');  // appended, not "." + ...: GCC 12 warns falsely (-Wrestrict)
    name += folder.filename().string();
    name += suffix;
    return folder.parent_path() / name;
}

fs::path parentOf(const fs::path& folder) {
    return folder.has_parent_path() ? folder.parent_path() : fs::path(".");
}

// Runs written before the marker existed: their summary.json names occsim.
bool holdsOlderOccsimSummary(const fs::path& folder) {
    std::ifstream in(folder / "summary.json", std::ios::binary);
    if (!in) return false;
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const nlohmann::json summary = nlohmann::json::parse(text, nullptr, false);
    return summary.is_object() && summary.contains("occsim") && summary["occsim"].is_object();
}

// Regress folders written before their marker existed: an occsim shard.json.
bool holdsOlderShard(const fs::path& folder) {
    std::ifstream in(folder / "shard.json", std::ios::binary);
    if (!in) return false;
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const nlohmann::json shard = nlohmann::json::parse(text, nullptr, false);
    return shard.is_object() && shard.value("format", std::string()) == "occsim-regress-shard";
}

bool holdsMarker(const fs::path& folder) {
    std::error_code ec;
    return fs::is_regular_file(folder / kRunMarker, ec);
}

bool isEmptyFolder(const fs::path& folder) {
    std::error_code ec;
    return fs::is_empty(folder, ec) && !ec;
}

// Leftovers of an interrupted run into `target` (the caller holds its lock, so no other run is
// using them): a staging folder of a run that died, and an old folder set aside by a publication
// that died between its two renames, put back when the target is missing.
void recoverInterrupted(const fs::path& target) {
    std::error_code ec;
    const fs::path old = beside(target, ".old");
    if (fs::is_directory(old, ec) && holdsMarker(old)) {
        if (!fs::exists(target, ec)) {
            fs::rename(old, target, ec);
        } else {
            fs::remove_all(old, ec);
        }
        if (ec) {
            throw RunFolderError(target.string() + ": cannot recover " + old.string() +
                                 " left by an interrupted run: " + ec.message());
        }
    }
    const std::string staging_prefix = beside(target, ".tmp-").filename().string();
    for (const fs::directory_entry& e : fs::directory_iterator(parentOf(target), ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(staging_prefix, 0) == 0 && e.is_directory(ec) &&
            (holdsMarker(e.path()) || isEmptyFolder(e.path())) &&
            !ownerAlive(name, staging_prefix)) {
            fs::remove_all(e.path(), ec);
        }
    }
}

}  // namespace

fs::path resolvedFolder(const fs::path& folder) {
    fs::path p = lexicalFolder(folder);
    std::error_code ec;
    // A bounded walk: a loop of links ends here and fails when the folder is made.
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        const fs::path to = fs::read_symlink(p, ec);
        if (ec) break;
        p = lexicalFolder(to.is_absolute() ? to : parentOf(p) / to);
    }
    return p;
}

void checkRegressFolder(const fs::path& folder) {
    const fs::path target = resolvedFolder(folder);
    std::error_code ec;
    const bool exists = fs::exists(target, ec);
    if (exists && !fs::is_directory(target, ec))
        throw RunFolderError(target.string() + ": is a file; expected a folder");
    const bool ours = !exists || isEmptyFolder(target) ||
                      fs::is_regular_file(target / kRegressMarker, ec) || holdsOlderShard(target);
    if (!ours) {
        throw RunFolderError(target.string() +
                             ": holds files that are not an occsim regress run (no " +
                             kRegressMarker +
                             " marker); expected an earlier regress --out, an empty folder or a "
                             "new name");
    }
    if (exists && ::access(target.c_str(), W_OK) != 0)
        throw RunFolderError("cannot write " + target.string() + ": " + std::strerror(errno));
}

void claimRegressFolder(const fs::path& folder) {
    checkRegressFolder(folder);
    const fs::path target = resolvedFolder(folder);
    std::error_code ec;
    fs::create_directories(target, ec);
    if (ec || ::access(target.c_str(), W_OK) != 0) {
        throw RunFolderError("cannot write " + target.string() + ": " +
                             (ec ? ec.message() : std::string(std::strerror(errno))));
    }
    try {
        writeFileAtomically(
            target / kRegressMarker,
            "An occsim regress --out folder: each scenario folder in it is replaced "
            "by the next regress that runs that scenario.\n");
    } catch (const std::runtime_error& e) {
        throw RunFolderError(target.string() + ": " + e.what());
    }
}

fs::path defaultOutputFolder(const std::string& scenario_name, const std::string& command_folder) {
    return fs::path("out") / safeFileName(scenario_name) / safeFileName(command_folder);
}

bool isReplaceableRunFolder(const fs::path& folder) {
    std::error_code ec;
    if (!fs::exists(folder, ec)) return true;
    if (!fs::is_directory(folder, ec)) return false;
    return isEmptyFolder(folder) || holdsMarker(folder) || holdsOlderOccsimSummary(folder);
}

void checkRunFolder(const fs::path& folder) {
    std::error_code ec;
    const bool exists = fs::exists(folder, ec);
    if (exists && !fs::is_directory(folder, ec))
        throw RunFolderError(folder.string() + ": is a file; expected a folder");
    if (!isReplaceableRunFolder(folder)) {
        throw RunFolderError(folder.string() + ": holds files that are not an occsim run (no " +
                             kRunMarker +
                             " marker); expected an earlier run's folder, an empty one or a new "
                             "name (a run replaces its folder as a whole)");
    }
    // The old run is deleted when the new one is published: that needs its folder writable.
    if (exists && ::access(folder.c_str(), W_OK) != 0)
        throw RunFolderError("cannot write " + folder.string() + ": " + std::strerror(errno));
}

FolderLock::FolderLock(const fs::path& folder, bool wait) {
    const fs::path target = resolvedFolder(folder);
    const fs::path lock = beside(target, ".lock");
    std::error_code ec;
    fs::create_directories(parentOf(target), ec);
    if (ec) {
        throw RunFolderError(target.string() + ": cannot create " + parentOf(target).string() +
                             ": " + ec.message());
    }
    fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) {
        throw RunFolderError(target.string() + ": cannot write its lock " + lock.string() + ": " +
                             std::strerror(errno));
    }
    int locked = 0;
    while ((locked = ::flock(fd_, LOCK_EX | (wait ? 0 : LOCK_NB))) != 0 && errno == EINTR) {
    }
    if (locked != 0) {
        const int err = errno;
        ::close(fd_);
        fd_ = -1;
        if (err == EWOULDBLOCK) {
            throw RunFolderBusy(target.string() + ": another occsim run is writing it (" +
                                lock.string() + " is locked); wait for it, or pass --wait-lock");
        }
        throw RunFolderError(target.string() + ": cannot lock " + lock.string() + ": " +
                             std::strerror(err));
    }
}

FolderLock::~FolderLock() {
    // The lock file stays: deleting it would let a waiting run and a new one lock two files.
    if (fd_ >= 0) ::close(fd_);
}

StagedRunFolder::StagedRunFolder(fs::path target) : target_(resolvedFolder(target)) {
    checkRunFolder(target_);
    recoverInterrupted(target_);
    staging_ = beside(target_, ".tmp-" + std::to_string(::getpid()));
    std::error_code ec;
    fs::create_directories(parentOf(target_), ec);
    if (!ec) fs::remove_all(staging_, ec);
    if (!ec) fs::create_directory(staging_, ec);
    if (ec) {
        throw RunFolderError(target_.string() + ": cannot write " + staging_.string() + ": " +
                             ec.message());
    }
    try {
        writeFileAtomically(staging_ / kRunMarker,
                            "An occsim run folder: the next run into it replaces it as a whole.\n");
    } catch (const std::runtime_error& e) {
        fs::remove_all(staging_, ec);
        throw RunFolderError(target_.string() + ": " + e.what());
    }
}

StagedRunFolder::~StagedRunFolder() {
    if (published_) return;
    std::error_code ec;
    fs::remove_all(staging_, ec);
}

void StagedRunFolder::publish() {
    const fs::path old = beside(target_, ".old");
    std::error_code ec;
    const bool had_old = fs::exists(target_, ec);
    if (had_old) {
        fs::rename(target_, old, ec);
        if (ec) {
            throw std::runtime_error("cannot move " + target_.string() + " aside to " +
                                     old.string() + ": " + ec.message());
        }
    }
    fs::rename(staging_, target_, ec);
    if (ec) {
        const std::string reason = ec.message();
        if (had_old) fs::rename(old, target_, ec);
        throw std::runtime_error("cannot move " + staging_.string() + " to " + target_.string() +
                                 ": " + reason);
    }
    published_ = true;
    // The new run is in place; an old folder that will not go is removed by the next run.
    if (had_old) fs::remove_all(old, ec);
}

}  // namespace occsim
