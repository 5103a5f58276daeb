// Colour on the console, only where it is read by a person: standard output a terminal, NO_COLOR
// unset or empty (https://no-color.org) and TERM not "dumb". Never in files or pipes: report.md,
// summary.json and a redirected console stay plain text. Only the first word of a line gets a
// colour, after the text was wrapped, so no column or width changes.
#pragma once

#include <string>

namespace occsim {

// The rule, on what the caller found: whether the stream is a terminal, NO_COLOR's and TERM's
// values (nullptr when unset).
bool colourWanted(bool is_terminal, const char* no_color, const char* term);

// colourWanted() for standard output of this process.
bool stdoutWantsColour();

// `text` (lines ending in newlines) with the console's answers marked: "verdict:" bold, "WRONG
// PIXELS" (a conservative culler's, a bug) bold red, "busy machine:" and "warning:" yellow. Every
// other line unchanged.
std::string colouredConsoleText(const std::string& text);

}  // namespace occsim
