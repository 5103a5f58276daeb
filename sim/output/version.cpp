#include "sim/output/version.h"

#include "sim/output/build_info.h"

namespace occsim {

const char* occsimVersion() { return OCCSIM_VERSION; }

const char* occsimCommit() { return OCCSIM_GIT_COMMIT; }

std::string versionLine(const std::string& program) {
    return program + " " + occsimVersion() + " (commit " + occsimCommit() + ")";
}

}  // namespace occsim
