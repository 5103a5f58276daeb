#include "sim/scenario/culling_file.h"

#include "sim/scenario/parser_parts.h"

namespace occsim {
namespace {

constexpr uint64_t kFormatVersion = 1;

// The whole file through the strict readers: the version, the required "culling" object, and
// nothing else.
void readInto(const CullingFile& culling, Scenario& scenario) {
    const std::string name = culling.file.string();
    JsonObjectReader top(culling.json, "", name);
    const JsonValueReader version = top.required("format_version");
    if (!(version.json().is_number() && version.json() == kFormatVersion)) {
        version.failExpected(std::to_string(kFormatVersion) +
                             " (the only format_version this program reads)");
    }
    top.required("culling").asObject();  // present, and an object
    readCulling(top, scenario);
    top.finish();
}

}  // namespace

CullingFile readCullingFile(const std::filesystem::path& file) {
    CullingFile culling{file, parseStrictJson(readScenarioFileText(file), file.string())};
    Scenario probe;
    readInto(culling, probe);
    return culling;
}

void applyCullingFile(const CullingFile& culling, Scenario& scenario) {
    readInto(culling, scenario);
}

}  // namespace occsim
