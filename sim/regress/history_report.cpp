#include "sim/regress/history_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "sim/output/atomic_file.h"
#include "sim/output/fixed_text.h"
#include "sim/regress/history_plot.h"

namespace occsim {
namespace {

// The values of one figure over one series' runs, oldest first (runs without it left out).
std::vector<double> seriesValues(const std::vector<HistoryEntry>& runs, const std::string& series,
                                 const std::string& scenario, const std::string& algorithm,
                                 const HistoryFigure& figure) {
    std::vector<double> values;
    for (const HistoryEntry& e : runs) {
        if (e.series() != series) continue;
        const auto s = e.scenarios.find(scenario);
        if (s == e.scenarios.end()) continue;
        const auto a = s->second.find(algorithm);
        if (a == s->second.end()) continue;
        if (const auto v = figure.get(a->second)) values.push_back(*v);
    }
    return values;
}

std::optional<FlaggedChange> compareWindows(const std::vector<double>& values,
                                            const HistoryOptions& options) {
    const size_t n = options.window;
    if (values.size() < n + 2 || values.size() < 2 * n) return std::nullopt;
    const size_t last = values.size() - n;
    double spread = 0;
    for (size_t i = 1; i < last; ++i)
        spread = std::max(spread, std::abs(values[i] - values[i - 1]));
    FlaggedChange c;
    c.before = median(
        {values.begin() + static_cast<long>(last - n), values.begin() + static_cast<long>(last)});
    c.after = median({values.begin() + static_cast<long>(last), values.end()});
    c.spread = spread;
    const double change = std::abs(c.after - c.before);
    if (change <= spread || change <= options.min_change * std::abs(c.before)) return std::nullopt;
    return c;
}

}  // namespace

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const size_t m = values.size() / 2;
    return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

const std::vector<HistoryFigure>& historyFigures() {
    static const std::vector<HistoryFigure> figures = {
        {"speedup over VFC", "speedup", true, [](const AlgorithmFigures& f) { return f.speedup; }},
        {"queries per frame", "queries", false,
         [](const AlgorithmFigures& f) { return std::optional<double>(f.queries); }},
        {"objects per frame", "objects", false,
         [](const AlgorithmFigures& f) { return std::optional<double>(f.objects); }},
        {"error pixels per frame", "error", false,
         [](const AlgorithmFigures& f) { return std::optional<double>(f.error); }},
    };
    return figures;
}

std::string FlaggedChange::text() const {
    const double relative = before != 0 ? 100.0 * (after - before) / std::abs(before) : 0.0;
    return scenario + " " + algorithm + ": " + figure + " " + fixed(before, 3) + " -> " +
           fixed(after, 3) + " (" + (relative >= 0 ? "+" : "") + fixed(relative, 1) + "%, " +
           (worse ? "worse" : "better") + "), beyond the run-to-run spread " + fixed(spread, 3) +
           " [" + series + "]";
}

HistoryAnalysis analyseHistory(std::vector<HistoryEntry> runs, const HistoryOptions& options) {
    HistoryAnalysis a;
    a.runs = std::move(runs);
    std::set<std::string> scenarios;
    for (const HistoryEntry& e : a.runs) {
        if (std::find(a.series.begin(), a.series.end(), e.series()) == a.series.end())
            a.series.push_back(e.series());
        for (const auto& [s, algorithms] : e.scenarios) scenarios.insert(s);
    }
    a.scenarios.assign(scenarios.begin(), scenarios.end());
    for (const std::string& series : a.series) {
        const size_t count =
            std::count_if(a.runs.begin(), a.runs.end(),
                          [&](const HistoryEntry& e) { return e.series() == series; });
        if (count < std::max(options.window + 2, 2 * options.window)) {
            a.not_compared.push_back(
                series + ": " + std::to_string(count) + " runs, " +
                std::to_string(std::max(options.window + 2, 2 * options.window)) +
                " needed for a window of " + std::to_string(options.window));
            continue;
        }
        for (const std::string& scenario : a.scenarios) {
            std::set<std::string> algorithms;
            for (const HistoryEntry& e : a.runs) {
                if (e.series() != series || !e.scenarios.count(scenario)) continue;
                for (const auto& [name, f] : e.scenarios.at(scenario)) algorithms.insert(name);
            }
            for (const std::string& algorithm : algorithms) {
                for (const HistoryFigure& figure : historyFigures()) {
                    // VFC's speedup over itself is 1 by definition.
                    if (algorithm == "vfc" && std::string(figure.key) == "speedup") continue;
                    auto c = compareWindows(
                        seriesValues(a.runs, series, scenario, algorithm, figure), options);
                    if (!c) continue;
                    c->series = series;
                    c->scenario = scenario;
                    c->algorithm = algorithm;
                    c->figure = figure.name;
                    c->worse =
                        figure.higher_is_better ? c->after < c->before : c->after > c->before;
                    a.flagged.push_back(*c);
                }
            }
        }
    }
    return a;
}

std::string historyMarkdown(const HistoryAnalysis& a, const HistoryOptions& options) {
    std::ostringstream out;
    out << "# Regression history\n\n"
        << a.runs.size() << " runs in " << a.series.size()
        << " series (machine and backend; figures of different series are never averaged). Each "
           "figure's "
        << "median over the last " << options.window << " runs is compared with the "
        << options.window
        << " before; flagged when the change exceeds the largest change between consecutive "
           "earlier runs "
        << "and " << fixed(100 * options.min_change, 0) << "% of the earlier median.\n\n";
    out << "## Changes beyond the run-to-run spread\n\n";
    if (a.flagged.empty()) out << "None.\n";
    for (const FlaggedChange& c : a.flagged)
        out << "- " << (c.worse ? "**" : "") << c.text() << (c.worse ? "**" : "") << "\n";
    for (const std::string& s : a.not_compared) out << "- not compared: " << s << "\n";
    out << "\n## Runs\n\n| run | date | commit | series |\n|---|---|---|---|\n";
    for (size_t i = 0; i < a.runs.size(); ++i) {
        const HistoryEntry& e = a.runs[i];
        const size_t series =
            std::find(a.series.begin(), a.series.end(), e.series()) - a.series.begin();
        out << "| " << i + 1 << " | " << e.date << " | `" << e.commit.substr(0, 12) << "` | "
            << series + 1 << " |\n";
    }
    out << "\n| series | machine (host, CPU, renderer), backend |\n|---|---|\n";
    for (size_t i = 0; i < a.series.size(); ++i)
        out << "| " << i + 1 << " | " << a.series[i] << " |\n";
    for (const std::string& scenario : a.scenarios) {
        out << "\n## " << scenario << "\n\n![" << scenario << "](history-"
            << distinctFileName(scenario) << ".svg)\n\n"
            << "Speedup over VFC per run:\n\n";
        std::set<std::string> algorithms;
        for (const HistoryEntry& e : a.runs) {
            if (!e.scenarios.count(scenario)) continue;
            for (const auto& [name, f] : e.scenarios.at(scenario)) algorithms.insert(name);
        }
        out << "| run | series |";
        for (const auto& name : algorithms) out << " " << name << " |";
        out << "\n|---|---|";
        for (size_t k = 0; k < algorithms.size(); ++k) out << "---|";
        out << "\n";
        for (size_t i = 0; i < a.runs.size(); ++i) {
            const HistoryEntry& e = a.runs[i];
            if (!e.scenarios.count(scenario)) continue;
            out << "| " << i + 1 << " | "
                << std::find(a.series.begin(), a.series.end(), e.series()) - a.series.begin() + 1
                << " |";
            for (const auto& name : algorithms) {
                const auto& m = e.scenarios.at(scenario);
                const auto it = m.find(name);
                out << " "
                    << (it != m.end() && it->second.speedup ? fixed(*it->second.speedup, 3) : "-")
                    << " |";
            }
            out << "\n";
        }
    }
    return out.str();
}

std::vector<std::string> writeHistoryReport(const std::filesystem::path& out,
                                            const HistoryAnalysis& a,
                                            const HistoryOptions& options) {
    std::filesystem::create_directories(out);
    std::vector<std::string> files;
    for (const std::string& scenario : a.scenarios) {
        const std::string name = "history-" + distinctFileName(scenario) + ".svg";
        writeFileAtomically(out / name, historySvg(a, scenario));
        files.push_back(name);
    }
    writeFileAtomically(out / "report.md", historyMarkdown(a, options));
    files.push_back("report.md");
    return files;
}

}  // namespace occsim
