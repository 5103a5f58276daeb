// The files a `run` or `bench` leaves behind, written from its result after it finished:
// frames.csv, summary.json, report.md and, when asked, the gnuplot charts. Each file is written
// atomically (whole or absent), into the folder given: the run's staging folder
// (run_folder.h), which then replaces the old run as a whole.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/output/object_highlights.h"
#include "sim/run/results.h"

namespace occsim {

struct OutputRequest {
    std::filesystem::path out_dir;             // the staging folder: written now, published later
    bool plots = false;                        // gnuplot charts (plots.h), when gnuplot is there
    std::vector<std::string> birds_eye_files;  // pictures already in out_dir, linked from report.md
    std::string extra_markdown;  // a section for report.md after the table (regress: its checks)
    // report.md's objects section, when objects.sqlite was recorded (sim/record/).
    std::optional<ObjectHighlights> objects;
};

struct OutputFiles {
    std::vector<std::string> files;  // names in out_dir, in the order written
    std::string plots_message;       // why plots were skipped or failed, or a remark
};

// report.md links every worst window's picture (windowPictureName(), PictureRecorder) that is in
// out_dir. Throws std::runtime_error naming the file when one cannot be written.
OutputFiles writeRunOutputs(const BenchResult& result, const OutputRequest& request);

}  // namespace occsim
