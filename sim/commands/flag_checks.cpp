#include "sim/commands/flag_checks.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "occsim/culling/contract/input_error.h"

namespace occsim_cli {

// The one place a command-line algorithm name is checked.
const occsim::CullerRow& algorithmNamed(const std::string& flag, const std::string& name) {
    if (const occsim::CullerRow* a = occsim::findCuller(name)) return *a;
    throw occsim::InputError(flag + ": unknown algorithm '" + name +
                             "'; expected one of: " + occsim::cullerNameList());
}

// A whole number in [lo, hi], checked on the text before CLI11 converts it, so a bad value gets
// the same one-line message as a bad scenario value: what was expected, and what was given.
CLI::Validator integerIn(long long lo, long long hi) {
    const std::string expected =
        "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    return CLI::Validator(
        [lo, hi, expected](std::string& text) -> std::string {
            size_t used = 0;
            long long value = 0;
            try {
                value = std::stoll(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (text.empty() || used != text.size() || value < lo || value > hi) {
                return expected + ", got '" + text + "'";
            }
            return {};
        },
        "INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

// An output path is checked before any work, so that a run never ends on a path it cannot
// write: a folder flag must not name a file, a file flag not a folder, and neither may be empty
// when given.
void checkOutputFolder(const std::string& flag, const std::string& path, bool given) {
    if (given && path.empty())
        throw occsim::InputError(flag + ": empty; expected a folder (created when missing)");
    std::error_code ec;
    if (!path.empty() && std::filesystem::exists(path, ec) &&
        !std::filesystem::is_directory(path, ec)) {
        throw occsim::InputError(flag + " " + path +
                                 ": is a file; expected a folder (created when missing)");
    }
}

void checkOutputFile(const std::string& flag, const std::string& path, bool given) {
    if (given && path.empty()) throw occsim::InputError(flag + ": empty; expected a file name");
    std::error_code ec;
    if (!path.empty() && std::filesystem::is_directory(path, ec)) {
        throw occsim::InputError(flag + " " + path + ": is a folder; expected a file name");
    }
}

// --algos as given: every name registered, none twice, none empty (a trailing comma).
// The names come comma-separated, space-separated or both ("vfc,chc" or "vfc chc").
bool recordsObjects(const std::vector<std::string>& values) {
    bool objects = false;
    for (const std::string& v : values) {
        if (v != "objects") {
            throw occsim::InputError("--record: '" + v +
                                     "' is not something a run records; expected: objects");
        }
        objects = true;
    }
    return objects;
}

namespace {

namespace fs = std::filesystem;

fs::path absoluteResolved(const fs::path& p) {
    std::error_code ec;
    const fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
    return ec ? fs::absolute(p).lexically_normal() : r;
}

// `path` exists and is writable, or the nearest folder above it that exists is.
void checkWritable(const std::string& flag, const fs::path& path) {
    std::error_code ec;
    fs::path p = absoluteResolved(path);
    if (fs::exists(p, ec)) {
        if (::access(p.c_str(), W_OK) != 0) {
            throw occsim::InputError(flag + " " + path.string() + ": cannot be written (" +
                                     std::strerror(errno) +
                                     "); expected a place this user can write");
        }
        return;
    }
    fs::path above = p.parent_path();
    while (!above.empty() && !fs::exists(above, ec) && above != above.parent_path())
        above = above.parent_path();
    if (!fs::is_directory(above, ec)) {
        throw occsim::InputError(flag + " " + path.string() + ": " + above.string() +
                                 " is not a folder; expected a path whose folders can be made");
    }
    if (::access(above.c_str(), W_OK) != 0) {
        throw occsim::InputError(flag + " " + path.string() + ": cannot create it in " +
                                 above.string() + " (" + std::strerror(errno) +
                                 "); expected a place this user can write");
    }
}

}  // namespace

void checkWritableFile(const std::string& flag, const std::string& path) {
    if (path.empty()) return;
    checkOutputFile(flag, path, true);
    checkWritable(flag, path);
}

void checkWritableFolder(const std::string& flag, const std::string& path) {
    if (path.empty()) return;
    checkOutputFolder(flag, path, true);
    checkWritable(flag, path);
}

bool sameOrInside(const fs::path& inner, const fs::path& outer) {
    const fs::path rel = absoluteResolved(inner).lexically_relative(absoluteResolved(outer));
    return !rel.empty() && *rel.begin() != "..";
}

bool sameFolder(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::error_code ec;
    return std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec) &&
           std::filesystem::equivalent(a, b, ec);
}

}  // namespace occsim_cli
