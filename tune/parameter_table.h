// The tunable parameters of every registered culler (a plugin's included once loaded), as the
// Markdown table of docs/tuning.md: printed by `occtune --list-parameters --markdown` and compared
// with the page by a test, so that the page cannot drift from the descriptors.
#pragma once

#include <string>

namespace occsim::tune {

// One row per tunable option: culler, name, unit, default (the reference every sample is measured
// against), the default search range, the option's valid range, and what it does; then per culler
// the smallest --budget that tunes all of its parameters.
std::string tunableParametersMarkdown();

// The same as plain text, one line per parameter, for the terminal.
std::string tunableParametersText();

}  // namespace occsim::tune
