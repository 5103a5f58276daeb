// Which shard of the scenario set this process runs: --shard i/n, or the scheduler's job variables.
#include <string>

#include "sim/regress/regress.h"

namespace occsim {

Shard parseShard(const std::string& text) {
    const auto slash = text.find('/');
    auto number = [&](const std::string& part) -> long {
        if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos ||
            part.size() > 6) {
            throw std::invalid_argument("expected a shard as i/n with 0 <= i < n, got '" + text +
                                        "'");
        }
        return std::stol(part);
    };
    if (slash == std::string::npos) {
        throw std::invalid_argument("expected a shard as i/n with 0 <= i < n, got '" + text + "'");
    }
    const long i = number(text.substr(0, slash)), n = number(text.substr(slash + 1));
    if (n < 1 || i >= n)
        throw std::invalid_argument("expected a shard as i/n with 0 <= i < n, got '" + text + "'");
    return {static_cast<uint32_t>(i), static_cast<uint32_t>(n)};
}

Shard shardFromEnvironment(const std::function<const char*(const char*)>& get) {
    auto value = [&](const char* name) -> std::optional<long> {
        const char* v = get(name);
        if (v == nullptr || *v == '\0') return std::nullopt;
        const std::string s(v);
        if (s.find_first_not_of("0123456789") != std::string::npos || s.size() > 9) {
            throw std::invalid_argument(std::string(name) +
                                        ": expected a non-negative integer, got '" + s + "'");
        }
        return std::stol(s);
    };
    if (const auto id = value("SLURM_ARRAY_TASK_ID")) {
        const auto count = value("SLURM_ARRAY_TASK_COUNT");
        if (!count)
            throw std::invalid_argument(
                "SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not");
        const long first = value("SLURM_ARRAY_TASK_MIN").value_or(0);
        return parseShard(std::to_string(*id - first) + "/" + std::to_string(*count));
    }
    if (const auto index = value("JOB_COMPLETION_INDEX")) {
        const auto count = value("OCCSIM_SHARD_COUNT");
        if (!count) {
            throw std::invalid_argument(
                "JOB_COMPLETION_INDEX is set but OCCSIM_SHARD_COUNT is not "
                "(set it to the Job's completions)");
        }
        return parseShard(std::to_string(*index) + "/" + std::to_string(*count));
    }
    return {};
}

}  // namespace occsim
