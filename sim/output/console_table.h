// The console's first answer to "which culler, and did any draw wrong pixels?": a compact table
// that fits kConsoleWidth columns, sorted, each row saying whether the culler is conservative, then
// a verdict of two or three lines. Formatting only, like report.h; the full table
// (formatComparisonTable, `--wide`), report.md and summary.json keep every figure.
#pragma once

#include <string>
#include <vector>

#include "sim/run/results.h"

namespace occsim {

// The widest line the console tables print by default.
inline constexpr size_t kConsoleWidth = 100;

// The compact table: configuration, kind ("cons": conservative, "approx": may hide visible
// pixels, "oracle": the ground-truth bound), mean ms, speedup over VFC, ratio to Ideal, queries
// and objects a frame, and with error measured the error pixels and missed objects summed over
// the frames. Conservative rows first, then approximate ones, then oracles, each by mean time;
// rows without a timed frame last in their group. A label too long for the width is cut in the
// middle ("statistical+:bas...=0.5"), never a figure. Ends with a legend line.
std::string formatCompactTable(const std::vector<RunRecord>& runs);

// The columns a UTF-8 text takes on a terminal: one a code point ("×" is one, not two bytes).
size_t displayWidth(const std::string& text);

// Rows of cells as aligned text, one line each ending in a newline: two spaces between columns,
// the columns in `left_columns` padded on the right, the others on the left, widths in
// displayWidth() columns, no trailing spaces.
std::string alignColumns(const std::vector<std::vector<std::string>>& rows,
                         const std::vector<size_t>& left_columns);

// One line of text broken at spaces into lines of at most kConsoleWidth characters: the first
// keeps the text's indent, the later ones are indented two spaces more; a word longer than a line
// (a long path) stays whole. wrappedText() does so to every line of a text, blank lines kept,
// each line ending in a newline (empty text: empty).
std::vector<std::string> wrapped(const std::string& text);
std::string wrappedText(const std::string& text);

// How two configurations' times compare in one run.
struct TimeComparison {
    enum class Outcome { Faster, Tie, TooFewFrames } outcome = Outcome::TooFewFrames;
    // With repetitions: the ranges of the repetitions' means overlap (a tie) or not. With one:
    // a sign test over the frames both timed (they ran interleaved on the same frames): the first
    // is faster on `wins` of `frames`; a tie when that count lies within 1.96 standard deviations
    // of half (a fair coin's 95 % band), too few frames under 10.
    bool from_repetitions = false;
    uint32_t wins = 0, frames = 0;
};
TimeComparison compareTimes(const RunRecord& faster, const RunRecord& slower);

// The verdict: the fastest conservative culler and its margin over the next one (or that they
// tie, and by what rule); which cullers drew wrong pixels (a conservative one loudly: that is a
// bug); and the `occsim why` command to ask about the runner-up (with `--record objects` when the
// run did not record them). `out_dir` is the run's folder as the user named it. None at all when
// no conservative culler was timed.
// Each statement whole, one a line; the console breaks them with wrapped().
std::vector<std::string> verdictStatements(const BenchResult& result, const std::string& out_dir,
                                           bool objects_recorded);

}  // namespace occsim
