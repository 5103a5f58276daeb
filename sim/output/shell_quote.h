// A command line as a POSIX shell reads it back: words that need quoting are single-quoted, so
// that the command recorded in summary.json and report.md can be pasted and runs the same.
#pragma once

#include <string>
#include <vector>

namespace occsim {

// "abc" stays; "" becomes ''; "a b" becomes 'a b'; "it's" becomes 'it'\''s'.
std::string shellQuoted(const std::string& word);
std::string shellCommand(const std::vector<std::string>& words);

}  // namespace occsim
