// Numbers typed as text, outside JSON: --sweep values and --params ranges (a double), and view
// script arguments (an integer). The whole text must be the number; what each accepts is the
// standard parser's syntax, so the flags and scripts that use these keep what they always took.
// Here, in the lowest layer that reads input, so the run layer, the viewer and the tuner share it.
#pragma once

#include <cstdint>
#include <string>

namespace occsim {

// std::stod's syntax (a decimal or hexadecimal floating-point number, leading spaces allowed),
// all of the text used, and finite. False (out unspecified) otherwise.
bool parseFiniteNumber(const std::string& text, double& out);

// std::from_chars' syntax for an integer (an optional '-', then decimal digits; no spaces, no
// '+'), all of the text used, and inside int64_t. False (out unspecified) otherwise.
bool parseInteger(const std::string& text, int64_t& out);

}  // namespace occsim
