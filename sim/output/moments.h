// The moments of a run as a person reads them: each segment's table (the comparison table over
// that segment's frames) and each configuration's worst windows against the reference, for the
// console, summary.json and report.md. Formatting only, like report.h.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/run/results.h"

namespace occsim {

// "corner: frames 120 to 137, 4.000 to 4.600 s (18 frames, 18 timed)", with the warm-up frames
// it holds and how a shortened run cut it, when so.
std::string segmentHeading(const Segment& segment, const RunMetadata& metadata);

// The console's segment tables: per segment its heading and the table over its frames, compact
// (console_table.h) or with `wide` the full comparison table; empty without segments.
std::string segmentTablesText(const BenchResult& result, bool wide = false);

// The console's worst windows: a heading line, then one line per configuration with its worst
// window, briefly (describeWindowBriefly) or with `wide` in full (describeWindow); empty when no
// reference ran or no configuration has a window.
std::string worstWindowsText(const BenchResult& result, bool wide = false);

// One window briefly, for a console line under a heading that names the reference: "frames
// 120-129: 2.71x, 12.3 / 4.5 ms, 412 / 35 objects, worst frame 124 (3.10x)", with ", N error px,
// M missed" where it had any.
std::string describeWindowBriefly(const WorstWindow& window);

// One window in words: "frames 120 to 129 (4.000 to 4.300 s): 2.71x ideal (12.31 / 4.54 ms per
// frame); objects 412 / 35, triangles 17162 / 190 per frame; 45.0 queries, 1.200 ms waiting per
// frame; worst frame 124 (3.10x)".
std::string describeWindow(const WorstWindow& window, const std::string& reference, double dt_s);

// summary.json's "segments": per segment its name, frames, seconds and origin, and per
// configuration the figures of summary.json's "algorithms" over the segment's frames (speedup and
// ratio to Ideal included).
nlohmann::json segmentsJson(const BenchResult& result);

// summary.json's "worst_windows": the reference, the window length, and per configuration its
// windows.
nlohmann::json worstWindowsJson(const BenchResult& result);

// The picture of a configuration's worst window's worst frame, with its validation overlay
// (PictureRecorder::onWindowFrame writes it): worst-window-<configuration>-frame-NNNNN.png.
std::string windowPictureName(const std::string& configuration, uint32_t frame);

}  // namespace occsim
