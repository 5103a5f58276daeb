// Writing objects.sqlite during a run (`occsim run|bench|regress --record objects`): the run's
// frame hook hands every configuration's frame to onFrame() (outside every timing), which inserts
// its objects' rows with prepared statements, one transaction per frame; finish() writes what the
// run ended as and the indexes, and reads back what report.md names.
//
// Contract
// - The file is created in the run's staging folder (sim/output/run_folder.h), so it is
//   published with the run's other files as one unit, or not at all.
// - Only the first repetition has rows; finish() writes how many repetitions the run made and,
//   per configuration, how many objects the later ones missed (summed over their frames, as
//   summary.json's missed_objects_total sums every repetition), so no reader takes the first
//   repetition's misses for the run's.
// - Until finish(), the run table says partial, and frames_recorded counts the frames whose every
//   configuration's rows are committed: a run that dies leaves a readable database of the frames
//   it finished. finish() on a run that stopped early removes the rows of the frame it dropped
//   and keeps it marked partial.
// - Errors (a disk that fills, a file that cannot be written) are std::runtime_error naming the
//   file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "sim/output/object_highlights.h"
#include "sim/run/results.h"
#include "sim/run/runner.h"

namespace occsim {

namespace sql {
class Database;
class Statement;
}  // namespace sql

class ObjectRecorder {
  public:
    // Creates <folder>/objects.sqlite (replacing a file of that name) with its schema.
    explicit ObjectRecorder(const std::filesystem::path& folder);
    ~ObjectRecorder();
    ObjectRecorder(const ObjectRecorder&) = delete;
    ObjectRecorder& operator=(const ObjectRecorder&) = delete;

    // One configuration's frame, just rendered (BenchOptions::on_frame; the simulation records
    // objects: BenchOptions::record_objects). Frames of later repetitions are ignored.
    void onFrame(const FrameEvent& event);
    // After the run: its metadata and how it ended, the indexes; the file is closed. Returns what
    // report.md names (the `overdrawn_per_config` most over-drawn objects of each configuration,
    // every missed one).
    ObjectHighlights finish(const BenchResult& result, uint32_t overdrawn_per_config = 5);

    const std::filesystem::path& file() const { return file_; }

  private:
    void start(const FrameEvent& event);
    uint32_t configId(const RunConfig& config);
    void commitFrame();

    std::filesystem::path file_;
    std::unique_ptr<sql::Database> db_;
    std::unique_ptr<sql::Statement> insert_;
    std::unique_ptr<sql::Statement> insert_right_eye_;
    std::unique_ptr<sql::Statement> insert_light_;
    std::map<std::string, uint32_t> configs_;
    bool started_ = false;
    bool in_frame_ = false;
    uint32_t frame_ = 0;  // the frame whose transaction is open
};

}  // namespace occsim
