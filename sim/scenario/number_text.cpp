#include "sim/scenario/number_text.h"

#include <charconv>
#include <cmath>
#include <exception>

namespace occsim {

bool parseFiniteNumber(const std::string& text, double& out) {
    size_t used = 0;
    try {
        out = std::stod(text, &used);
    } catch (const std::exception&) {
        return false;
    }
    return used == text.size() && std::isfinite(out);
}

bool parseInteger(const std::string& text, int64_t& out) {
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, out);
    return error == std::errc{} && stop == end;
}

}  // namespace occsim
