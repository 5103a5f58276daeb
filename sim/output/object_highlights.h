// What report.md says about objects when the run recorded them (`--record objects`): the objects
// each configuration drew most while ground truth saw nothing of them, and every object it missed.
// Filled from objects.sqlite by the recorder (sim/record/object_recorder.h); here only formatted.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace occsim {

// An object a configuration drew while ground truth saw none of its pixels.
struct OverdrawnObject {
    std::string config;
    uint32_t object = 0;
    std::string name;
    uint32_t triangles = 0;
    uint32_t frames = 0;          // frames drawn while hidden
    uint32_t longest_streak = 0;  // consecutive such frames, at most
    uint32_t streak_first = 0;    // the first frame of that streak
};

// An object ground truth saw and a configuration did not draw.
struct MissedObject {
    std::string config;
    uint32_t object = 0;
    std::string name;
    std::vector<uint32_t> frames;
    uint64_t error_pixels = 0;  // over those frames
};

// What the repetitions after the first, which are not recorded, missed: objects ground truth
// saw and the configuration did not draw, summed over their frames.
struct LaterMisses {
    std::string config;
    uint64_t objects = 0;
};

struct ObjectHighlights {
    std::vector<OverdrawnObject> overdrawn;  // per configuration, the most triangles first
    std::vector<MissedObject> missed;        // every one, per configuration (first repetition)
    uint32_t overdrawn_per_config = 0;       // how many over-drawn objects each lists at most
    uint32_t repetitions = 1;                // the run's; only the first is recorded
    std::vector<LaterMisses> later_misses;   // per configuration, with repetitions > 1
};

// With repetitions: which one the record covers and what the others missed, a sentence
// ("" with one repetition).
std::string laterRepetitionsNote(uint32_t repetitions, uint64_t missed_in_later);

// "3-5, 9, 12-14": sorted frames as ranges.
std::string frameRanges(const std::vector<uint32_t>& frames);

// The report's "Objects" section (empty text for no highlights at all).
std::string objectHighlightsMarkdown(const ObjectHighlights& highlights);

}  // namespace occsim
