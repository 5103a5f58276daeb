// A number with a fixed count of decimals, as every table and report of occsim writes it.
#pragma once

#include <cstdio>
#include <string>

namespace occsim {

inline std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

}  // namespace occsim
