// Text as every table and report of occsim writes it: numbers with a fixed count of decimals,
// Markdown table cells.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace occsim {

inline std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

// fixed(), except that a figure that is not zero never reads as zero: where `decimals` would round
// it to zero it prints as "<0.1" (one decimal; "<1" with none, ">-0.1" below zero), so one error
// pixel in 240 frames shows as an error. Figures that are zero print as fixed() does.
inline std::string fixedNonZero(double v, int decimals) {
    std::string text = fixed(v, decimals);
    if (v == 0 || std::strtod(text.c_str(), nullptr) != 0) return text;
    return (v > 0 ? "<" : ">-") + fixed(std::pow(10.0, -decimals), decimals);
}

// A Markdown table cell: a bare '|' would end the cell, so it is escaped.
inline std::string markdownCell(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '|') out += '\\';
        out += c;
    }
    return out;
}

}  // namespace occsim
