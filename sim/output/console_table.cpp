#include "sim/output/console_table.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "sim/output/fixed_text.h"
#include "sim/output/shell_quote.h"

namespace occsim {
namespace {

enum class Kind { Conservative, Approximate, Oracle };

// What a configuration is: its row says conservative or oracle; the approximation knobs
// (threshold_pixels, stale_results) make any culler approximate.
Kind kindOf(const RunRecord& r) {
    if (r.algorithm && r.algorithm->oracle) return Kind::Oracle;
    if (r.algorithm && (!r.algorithm->conservative || r.approximation.active()))
        return Kind::Approximate;
    return Kind::Conservative;
}

const char* kindWord(Kind k) {
    switch (k) {
        case Kind::Conservative:
            return "cons";
        case Kind::Approximate:
            return "approx";
        case Kind::Oracle:
            return "oracle";
    }
    return "?";
}

bool timed(const RunRecord& r) { return r.summary.timed_frames > 0; }

// The rows in the table's order: conservative, approximate, oracles; each by mean time, rows
// without a timed frame last in their group, ties by the order they ran in.
std::vector<const RunRecord*> sortedRows(const std::vector<RunRecord>& runs) {
    std::vector<const RunRecord*> rows;
    for (const RunRecord& r : runs) rows.push_back(&r);
    std::stable_sort(rows.begin(), rows.end(), [](const RunRecord* a, const RunRecord* b) {
        const Kind ka = kindOf(*a), kb = kindOf(*b);
        if (ka != kb) return ka < kb;
        if (timed(*a) != timed(*b)) return timed(*a);
        return timed(*a) && a->summary.frame_ms.mean < b->summary.frame_ms.mean;
    });
    return rows;
}

// A label cut in its middle to `width` characters, so that both the culler's name and the
// swept value stay readable.
std::string fitLabel(const std::string& label, size_t width) {
    if (label.size() <= width) return label;
    const size_t keep = width - 3, head = (keep + 1) / 2;
    return label.substr(0, head) + "..." + label.substr(label.size() - (keep - head));
}

// The timed frame times of one record (its last timed_frames frames), by frame number.
std::map<uint32_t, double> timedFrames(const RunRecord& r) {
    std::map<uint32_t, double> t;
    const size_t timed_count = std::min<size_t>(r.summary.timed_frames, r.frames.size());
    for (size_t i = r.frames.size() - timed_count; i < r.frames.size(); ++i)
        t[r.frames[i].frame] = r.frames[i].frame_ms;
    return t;
}

std::string ms(double v) { return fixedNonZero(v, 2) + " ms"; }

}  // namespace

size_t displayWidth(const std::string& text) {
    size_t width = 0;
    for (const char c : text) width += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    return width;
}

std::string alignColumns(const std::vector<std::vector<std::string>>& rows,
                         const std::vector<size_t>& left_columns) {
    if (rows.empty()) return "";
    std::vector<size_t> width(rows.front().size(), 0);
    for (const auto& cells : rows)
        for (size_t c = 0; c < cells.size(); ++c)
            width[c] = std::max(width[c], displayWidth(cells[c]));
    std::string out;
    for (const auto& cells : rows) {
        std::string line;
        for (size_t c = 0; c < cells.size(); ++c) {
            const std::string pad(width[c] - displayWidth(cells[c]), ' ');
            const bool left =
                std::find(left_columns.begin(), left_columns.end(), c) != left_columns.end();
            line += left ? cells[c] + pad : pad + cells[c];
            if (c + 1 < cells.size()) line += "  ";
        }
        while (!line.empty() && line.back() == ' ') line.pop_back();
        out += line + "\n";
    }
    return out;
}

std::vector<std::string> wrapped(const std::string& text) {
    // The text's own indent starts its first line; the later ones are indented two more. Within a
    // line the text's own spacing stays (aligned columns keep their padding).
    const size_t start = std::min(text.find_first_not_of(' '), text.size());
    const std::string indent = text.substr(0, start);
    std::vector<std::string> lines;
    std::string line = indent;
    bool line_has_word = false;
    size_t at = start;
    while (at < text.size()) {
        const size_t word_at = std::min(text.find_first_not_of(' ', at), text.size());
        if (word_at == text.size()) break;  // trailing spaces
        const size_t word_end = std::min(text.find(' ', word_at), text.size());
        const std::string spaces = text.substr(at, word_at - at);
        const std::string word = text.substr(word_at, word_end - word_at);
        if (line_has_word &&
            displayWidth(line) + spaces.size() + displayWidth(word) > kConsoleWidth) {
            lines.push_back(line);
            line = indent + "  " + word;
        } else {
            line += (line_has_word ? spaces : "") + word;
        }
        line_has_word = true;
        at = word_end;
    }
    if (line_has_word) lines.push_back(line);
    return lines;
}

std::string wrappedText(const std::string& text) {
    std::string out;
    std::istringstream in(text);
    for (std::string paragraph; std::getline(in, paragraph);) {
        if (paragraph.find_first_not_of(' ') == std::string::npos) {
            out += "\n";  // blank lines stay
            continue;
        }
        for (const std::string& line : wrapped(paragraph)) out += line + "\n";
    }
    return out;
}

std::string formatCompactTable(const std::vector<RunRecord>& runs) {
    if (runs.empty()) return "";
    bool error = false;
    for (const RunRecord& r : runs) error |= r.summary.error_measured;
    std::vector<std::string> header = {"configuration", "kind",    "mean ms", "vs vfc",
                                       "vs ideal",      "queries", "objects"};
    if (error) {
        header.push_back("err px");
        header.push_back("missed");
    }
    const bool nothing_in_view = nothingInView(runs);
    std::vector<std::vector<std::string>> lines = {header};
    for (const RunRecord* r : sortedRows(runs)) {
        const RunSummary& s = r->summary;
        const double speedup = speedupOverReference(runs, s), ideal = ratioToOracle(runs, s);
        const std::string none = nothing_in_view ? "n/a" : "-";
        std::vector<std::string> row = {s.label,
                                        kindWord(kindOf(*r)),
                                        fixedNonZero(s.frame_ms.mean, 2),
                                        speedup > 0 ? fixed(speedup, 2) + "x" : none,
                                        ideal > 0 ? fixed(ideal, 2) + "x" : none,
                                        fixedNonZero(s.queries_mean, 1),
                                        fixedNonZero(s.objects_mean, 1)};
        // No timed frame: no figure to show (0.00 would read as measured).
        if (!timed(*r)) {
            row.resize(2);
            row.push_back("not timed");
            row.resize(header.size() - (error ? 2 : 0), "-");
        }
        if (error) {
            row.push_back(std::to_string(s.error_pixels_total));
            row.push_back(std::to_string(s.missed_objects_total));
        }
        lines.push_back(row);
    }
    // The label column gets what the figures leave of the width.
    size_t figures = 0;
    for (size_t c = 1; c < header.size(); ++c) {
        size_t w = 0;
        for (const auto& cells : lines) w = std::max(w, cells[c].size());
        figures += w + 2;
    }
    const size_t label_width =
        std::max<size_t>(kConsoleWidth > figures ? kConsoleWidth - figures : 0, 13);
    for (size_t i = 1; i < lines.size(); ++i) lines[i][0] = fitLabel(lines[i][0], label_width);
    std::string out = alignColumns(lines, {0, 1});  // names left, figures right
    out +=
        "kind: cons never hides a visible pixel, approx may, oracle is the ground-truth bound;\n"
        "queries and objects a frame, mean ms over the timed frames";
    out += error ? "; err px and missed summed over all frames\n" : "\n";
    return out;
}

TimeComparison compareTimes(const RunRecord& faster, const RunRecord& slower) {
    TimeComparison c;
    if (faster.summary.repetitions > 1 && slower.summary.repetitions > 1) {
        c.from_repetitions = true;
        c.frames = faster.summary.timed_frames;
        const bool overlap = faster.summary.frame_ms_mean_max >= slower.summary.frame_ms_mean_min;
        c.outcome = overlap ? TimeComparison::Outcome::Tie : TimeComparison::Outcome::Faster;
        return c;
    }
    // The frames both timed (the last timed_frames of each: warm-up frames come first), paired by
    // frame number: the configurations ran interleaved on the same frames.
    const std::map<uint32_t, double> a = timedFrames(faster), b = timedFrames(slower);
    for (const auto& [frame, t] : a) {
        const auto other = b.find(frame);
        if (other == b.end()) continue;
        ++c.frames;
        c.wins += t < other->second;
    }
    if (c.frames < 10) {
        c.outcome = TimeComparison::Outcome::TooFewFrames;
        return c;
    }
    const double half = c.frames / 2.0, band = 1.96 * std::sqrt(static_cast<double>(c.frames)) / 2;
    c.outcome =
        c.wins > half + band ? TimeComparison::Outcome::Faster : TimeComparison::Outcome::Tie;
    return c;
}

std::vector<std::string> verdictStatements(const BenchResult& result, const std::string& out_dir,
                                           bool objects_recorded) {
    std::vector<std::string> lines;
    const std::vector<const RunRecord*> rows = sortedRows(result.runs);
    std::vector<const RunRecord*> conservative;
    for (const RunRecord* r : rows)
        if (kindOf(*r) == Kind::Conservative && timed(*r)) conservative.push_back(r);
    if (conservative.empty()) return lines;

    const RunRecord& best = *conservative.front();
    const std::string best_name = best.summary.label;
    if (conservative.size() == 1) {
        lines.push_back("verdict: " + best_name + " is the only conservative culler timed (" +
                        ms(best.summary.frame_ms.mean) + ")");
    } else {
        const RunRecord& next = *conservative[1];
        const TimeComparison c = compareTimes(best, next);
        const double margin = best.summary.frame_ms.mean > 0
                                  ? next.summary.frame_ms.mean / best.summary.frame_ms.mean
                                  : 0.0;
        const std::string pair = best_name + " " + ms(best.summary.frame_ms.mean) + ", " +
                                 next.summary.label + " " + ms(next.summary.frame_ms.mean);
        std::string why;
        if (c.from_repetitions) {
            why = "their means over " + std::to_string(best.summary.repetitions) + " repetitions " +
                  (c.outcome == TimeComparison::Outcome::Tie ? "overlap" : "do not overlap");
        } else if (c.outcome == TimeComparison::Outcome::TooFewFrames) {
            why = "too few timed frames (" + std::to_string(c.frames) + ") to tell them apart";
        } else {
            why = "faster on " + std::to_string(c.wins) + " of " + std::to_string(c.frames) +
                  " frames; one repetition (--repetitions 3 for the run-to-run spread)";
        }
        if (c.outcome == TimeComparison::Outcome::Faster) {
            lines.push_back("verdict: fastest conservative culler " + best_name + ", " +
                            fixed(margin, 2) + "x faster than " + next.summary.label + " (" + pair +
                            "; " + why + ")");
        } else {
            lines.push_back("verdict: fastest conservative cullers " + best_name + " and " +
                            next.summary.label + " tie (" + pair + "; " + why + ")");
        }
    }

    // Wrong pixels: a conservative culler's are a bug; an approximate one's are its trade.
    if (result.metadata.error_measured) {
        std::string wrong_conservative, wrong_approximate;
        for (const RunRecord* r : rows) {
            const RunSummary& s = r->summary;
            if (s.error_pixels_total == 0 && s.missed_objects_total == 0) continue;
            const std::string item = s.label + " " + std::to_string(s.error_pixels_total) +
                                     " px, " + std::to_string(s.missed_objects_total) + " missed";
            std::string& list =
                kindOf(*r) == Kind::Conservative ? wrong_conservative : wrong_approximate;
            list += (list.empty() ? "" : "; ") + item;
        }
        if (!wrong_conservative.empty()) {
            lines.push_back(
                "WRONG PIXELS from conservative cullers (a bug): " + wrong_conservative +
                "; occsim why " + shellQuoted(out_dir) + " --missed");
        } else {
            lines.push_back("wrong pixels: none from a conservative culler" +
                            (wrong_approximate.empty() ? std::string(", none at all")
                                                       : "; approximate: " + wrong_approximate));
        }
    } else {
        lines.push_back(
            "wrong pixels: not measured (--error renders ground truth and counts them)");
    }

    // Asking why the runner-up lost: what it drew that was hidden.
    if (conservative.size() > 1) {
        const std::string loser = conservative[1]->summary.label;
        const std::string why =
            "occsim why " + shellQuoted(out_dir) + " --overdraw --algo " + shellQuoted(loser);
        lines.push_back(objects_recorded
                            ? "why " + loser + " lost: " + why
                            : "why " + loser + " lost: rerun with --record objects, then " + why);
    }
    return lines;
}

}  // namespace occsim
