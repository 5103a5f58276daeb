// The registry as text: `occsim cullers` prints it, and docs/cullers.md holds the Markdown form
// (a test checks that the page's tables are this program's output, so the docs' options tables
// are read off the descriptors like everything else).
#pragma once

#include <string>

namespace occsim {

// Every registered culler: name, traits, summary, and one line per option.
std::string cullersText();
// The same as Markdown: one table of cullers, then one options table per culler that has options.
std::string cullersMarkdown();

}  // namespace occsim
