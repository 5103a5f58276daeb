// Reads back the JUnit XML that junitXml() writes, far enough to tell a whole file from a
// truncated or corrupt one: every element closed in order, the declared counts equal to the
// testcases present. Not a general XML parser: no DTDs, no CDATA, no namespaces (occsim never
// writes them).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace occsim {

struct JunitSuite {
    std::string name;
    size_t testcases = 0;  // <testcase> elements present
    size_t failures = 0;   // of those, with a <failure>
    size_t skipped = 0;    // of those, with a <skipped>
};

// Throws ResultFileError "<file>: line L: <what was expected>".
std::vector<JunitSuite> readJunit(const std::filesystem::path& file);
// The same on text in memory; `name` is the file named in messages.
std::vector<JunitSuite> parseJunit(const std::string& text, const std::string& name);

}  // namespace occsim
