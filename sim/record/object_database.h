// A run's objects.sqlite opened for reading (`occsim why`), checked before any question is
// answered: the folder and the file exist, the file is a whole SQLite database (not truncated,
// not corrupt) and this version of occsim wrote it. Each failure is bad input: one line naming
// the folder or file and what was expected.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "occsim/culling/contract/input_error.h"
#include "sim/record/sqlite.h"

namespace occsim {

struct ObjectsDatabaseError : InputError {
    using InputError::InputError;
};

// The run table.
struct RecordedRun {
    int format_version = 0;
    std::string occsim_version;
    std::string command;
    std::string scenario;
    uint32_t frames = 0;           // the run's frames as planned
    uint32_t frames_recorded = 0;  // frames 0 .. frames_recorded - 1 are in the file
    bool partial = false;
    std::string partial_reason;
    std::optional<uint32_t> deterministic_latency;
    uint32_t repetitions = 1;  // the run's; the rows are the first one's
};

class ObjectDatabase {
  public:
    // Opens <run_folder>/objects.sqlite read-only. Throws ObjectsDatabaseError.
    explicit ObjectDatabase(const std::filesystem::path& run_folder);

    sql::Database& db() { return *db_; }
    const RecordedRun& run() const { return run_; }
    const std::filesystem::path& file() const { return file_; }

  private:
    std::filesystem::path file_;
    std::unique_ptr<sql::Database> db_;
    RecordedRun run_;
};

// The file's header against its size: empty when whole, else why not ("truncated: 8192 bytes of
// the 40960 its header declares", "not an SQLite database"). Exposed for tests.
std::string sqliteFileProblem(const std::filesystem::path& file);

}  // namespace occsim
