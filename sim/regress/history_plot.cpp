#include "sim/regress/history_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <sstream>

namespace occsim {
namespace {

constexpr double kWidth = 900, kPanelHeight = 170, kLeft = 80, kRight = 200, kTop = 30, kGap = 40;
const char* const kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                               "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
const char* const kDashes[] = {"", "6,3", "2,2", "8,3,2,3"};

std::string esc(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '"')
            out += "&quot;";
        else
            out += c;
    }
    return out;
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

std::string label(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, std::abs(v) >= 100 ? "%.0f" : "%.3g", v);
    return buf;
}

struct Point {
    size_t run;
    double value;
};

// One panel: the figure of every (series, algorithm) of the scenario over the runs.
void panel(std::ostringstream& out, const HistoryAnalysis& a, const std::string& scenario,
           const std::vector<std::string>& algorithms, const HistoryFigure& figure, double top) {
    const size_t runs = a.runs.size();
    std::vector<std::vector<std::vector<Point>>> lines(
        a.series.size(), std::vector<std::vector<Point>>(algorithms.size()));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (size_t r = 0; r < runs; ++r) {
        const HistoryEntry& e = a.runs[r];
        const auto s = e.scenarios.find(scenario);
        if (s == e.scenarios.end()) continue;
        const size_t series =
            std::find(a.series.begin(), a.series.end(), e.series()) - a.series.begin();
        for (size_t k = 0; k < algorithms.size(); ++k) {
            const auto it = s->second.find(algorithms[k]);
            if (it == s->second.end()) continue;
            if (const auto v = figure.get(it->second)) {
                lines[series][k].push_back({r, *v});
                lo = std::min(lo, *v);
                hi = std::max(hi, *v);
            }
        }
    }
    if (!(lo <= hi)) lo = 0, hi = 1;
    if (hi - lo < 1e-9 * std::max(1.0, std::abs(hi)))
        lo -= std::max(0.5, 0.1 * std::abs(lo)), hi += std::max(0.5, 0.1 * std::abs(hi));
    const double pad = 0.08 * (hi - lo);
    lo -= pad;
    hi += pad;
    const double x0 = kLeft, x1 = kWidth - kRight, y0 = top, y1 = top + kPanelHeight;
    auto x = [&](size_t r) {
        return runs < 2 ? 0.5 * (x0 + x1)
                        : x0 + (x1 - x0) * static_cast<double>(r) / static_cast<double>(runs - 1);
    };
    auto y = [&](double v) { return y1 - (y1 - y0) * (v - lo) / (hi - lo); };
    out << "<g class=\"panel\" data-figure=\"" << figure.key << "\">\n"
        << "<rect x=\"" << num(x0) << "\" y=\"" << num(y0) << "\" width=\"" << num(x1 - x0)
        << "\" height=\"" << num(y1 - y0) << "\" fill=\"none\" stroke=\"#999\"/>\n"
        << "<text x=\"" << num(x0) << "\" y=\"" << num(y0 - 6) << "\" font-size=\"13\">"
        << esc(figure.name) << "</text>\n"
        << "<text x=\"" << num(x0 - 6) << "\" y=\"" << num(y0 + 10)
        << "\" font-size=\"10\" text-anchor=\"end\">" << label(hi - pad) << "</text>\n"
        << "<text x=\"" << num(x0 - 6) << "\" y=\"" << num(y1)
        << "\" font-size=\"10\" text-anchor=\"end\">" << label(lo + pad) << "</text>\n";
    for (size_t r = 0; r < runs; ++r) {
        out << "<text x=\"" << num(x(r)) << "\" y=\"" << num(y1 + 13)
            << "\" font-size=\"10\" text-anchor=\"middle\">" << r + 1 << "</text>\n";
    }
    for (size_t s = 0; s < lines.size(); ++s) {
        for (size_t k = 0; k < algorithms.size(); ++k) {
            const auto& pts = lines[s][k];
            if (pts.empty()) continue;
            const char* color = kColors[k % std::size(kColors)];
            out << "<polyline class=\"line\" data-algorithm=\"" << esc(algorithms[k])
                << "\" data-series=\"" << s + 1 << "\" fill=\"none\" stroke=\"" << color
                << "\" stroke-width=\"1.5\"";
            if (*kDashes[s % std::size(kDashes)])
                out << " stroke-dasharray=\"" << kDashes[s % std::size(kDashes)] << "\"";
            out << " points=\"";
            for (const Point& p : pts) out << num(x(p.run)) << "," << num(y(p.value)) << " ";
            out << "\"/>\n";
            for (const Point& p : pts) {
                out << "<circle class=\"point\" cx=\"" << num(x(p.run)) << "\" cy=\""
                    << num(y(p.value)) << "\" r=\"2.5\" fill=\"" << color << "\"><title>run "
                    << p.run + 1 << ", " << esc(algorithms[k]) << ": " << label(p.value)
                    << "</title></circle>\n";
            }
            const bool flagged =
                std::any_of(a.flagged.begin(), a.flagged.end(), [&](const FlaggedChange& c) {
                    return c.series == a.series[s] && c.scenario == scenario &&
                           c.algorithm == algorithms[k] && c.figure == figure.name;
                });
            if (flagged) {
                out << "<circle class=\"flagged\" cx=\"" << num(x(pts.back().run)) << "\" cy=\""
                    << num(y(pts.back().value))
                    << "\" r=\"7\" fill=\"none\" stroke=\"red\" stroke-width=\"2\"/>\n";
            }
        }
    }
    out << "</g>\n";
}

}  // namespace

std::string historySvg(const HistoryAnalysis& a, const std::string& scenario) {
    std::set<std::string> names;
    for (const HistoryEntry& e : a.runs) {
        if (const auto s = e.scenarios.find(scenario); s != e.scenarios.end()) {
            for (const auto& [name, f] : s->second) names.insert(name);
        }
    }
    const std::vector<std::string> algorithms(names.begin(), names.end());
    const auto& figures = historyFigures();
    const double height = kTop + static_cast<double>(figures.size()) * (kPanelHeight + kGap) + 20;
    std::ostringstream out;
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(kWidth) << "\" height=\""
        << num(height)
        << "\" font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << "<text x=\"" << num(kLeft) << "\" y=\"18\" font-size=\"15\">" << esc(scenario) << ": "
        << a.runs.size() << " runs (x: run number; dash: series)</text>\n";
    for (size_t f = 0; f < figures.size(); ++f) {
        panel(out, a, scenario, algorithms, figures[f],
              kTop + 20 + static_cast<double>(f) * (kPanelHeight + kGap));
    }
    for (size_t k = 0; k < algorithms.size(); ++k) {
        const double ly = kTop + 30 + 18.0 * static_cast<double>(k);
        out << "<line x1=\"" << num(kWidth - kRight + 15) << "\" y1=\"" << num(ly) << "\" x2=\""
            << num(kWidth - kRight + 40) << "\" y2=\"" << num(ly) << "\" stroke=\""
            << kColors[k % std::size(kColors)] << "\" stroke-width=\"2\"/>\n"
            << "<text x=\"" << num(kWidth - kRight + 45) << "\" y=\"" << num(ly + 4)
            << "\" font-size=\"12\">" << esc(algorithms[k]) << "</text>\n";
    }
    for (size_t s = 0; s < a.series.size(); ++s) {
        const double ly = kTop + 40 + 18.0 * static_cast<double>(algorithms.size() + s);
        out << "<line x1=\"" << num(kWidth - kRight + 15) << "\" y1=\"" << num(ly) << "\" x2=\""
            << num(kWidth - kRight + 40) << "\" y2=\"" << num(ly) << "\" stroke=\"black\"";
        if (*kDashes[s % std::size(kDashes)])
            out << " stroke-dasharray=\"" << kDashes[s % std::size(kDashes)] << "\"";
        out << "/>\n<text x=\"" << num(kWidth - kRight + 45) << "\" y=\"" << num(ly + 4)
            << "\" font-size=\"12\">series " << s + 1 << "</text>\n";
    }
    out << "</svg>\n";
    return out.str();
}

}  // namespace occsim
