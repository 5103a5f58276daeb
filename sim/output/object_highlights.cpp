#include "sim/output/object_highlights.h"

#include <sstream>

#include "sim/output/fixed_text.h"

namespace occsim {
std::string frameRanges(const std::vector<uint32_t>& frames) {
    std::string out;
    for (size_t i = 0; i < frames.size();) {
        size_t j = i;
        while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
        if (!out.empty()) out.append(", ");
        out.append(std::to_string(frames[i]));
        if (j > i) {
            out.push_back('-');
            out.append(std::to_string(frames[j]));
        }
        i = j + 1;
    }
    return out;
}

std::string laterRepetitionsNote(uint32_t repetitions, uint64_t missed_in_later) {
    if (repetitions <= 1) return "";
    const std::string later =
        repetitions == 2 ? "repetition 2" : "repetitions 2-" + std::to_string(repetitions);
    return later + ", not recorded, missed " +
           (missed_in_later == 0 ? std::string("none")
                                 : std::to_string(missed_in_later) + " more (objects × frames)");
}

std::string objectHighlightsMarkdown(const ObjectHighlights& h) {
    std::ostringstream out;
    out << "## Objects\n\n"
        << "From `objects.sqlite` (docs/objects.md; `occsim why` answers for any object).\n\n";
    out << "**Drawn while hidden** (ground truth saw none of its pixels), the "
        << h.overdrawn_per_config
        << " objects with the most triangles drawn that way per configuration:\n\n";
    if (h.overdrawn.empty()) {
        out << "none.\n\n";
    } else {
        out << "| configuration | object | triangles | frames | longest streak |\n"
            << "|---|---|---:|---:|---|\n";
        for (const OverdrawnObject& o : h.overdrawn) {
            out << "| " << markdownCell(o.config) << " | " << o.object << " "
                << markdownCell(o.name) << " | " << o.triangles << " | " << o.frames << " | "
                << o.longest_streak << " (from frame " << o.streak_first << ") |\n";
        }
        out << "\n";
    }
    out << "**Missed** (ground truth saw it, the configuration did not draw it), every one";
    if (h.repetitions > 1) {
        out << " in the first of the " << h.repetitions
            << " repetitions (the one recorded; summary.json's missed objects count them all)";
    }
    out << ":\n\n";
    if (h.missed.empty()) {
        out << "none.\n\n";
    } else {
        out << "| configuration | object | frames | error px |\n|---|---|---|---:|\n";
        for (const MissedObject& m : h.missed) {
            out << "| " << markdownCell(m.config) << " | " << m.object << " "
                << markdownCell(m.name) << " | " << frameRanges(m.frames) << " | " << m.error_pixels
                << " |\n";
        }
        out << "\n";
    }
    for (const LaterMisses& l : h.later_misses) {
        out << "- " << markdownCell(l.config) << ": "
            << laterRepetitionsNote(h.repetitions, l.objects) << "\n";
    }
    if (!h.later_misses.empty()) out << "\n";
    return out.str();
}

}  // namespace occsim
