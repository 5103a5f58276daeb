// The text panel over the viewer's picture: the algorithm, the frame and its figures (frame time,
// queries, triangles, error pixels when ground truth is on), the camera and recording state, the
// box legend, the last message and the keys. Redrawn every frame from a plain description.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/output/raster_canvas.h"
#include "sim/run/frame_stats.h"

namespace occsim {

struct HudState {
    std::string scenario;
    std::string algorithm;
    uint32_t algorithm_place = 1, algorithm_count = 1;  // 1-based, for "3/7"
    uint32_t frame = 0;                                 // played frames since the (re)start
    double time_s = 0.0;                                // simulation time of the frame shown
    bool paused = false;
    bool flying = false;
    double fly_speed_mps = 0.0;
    bool recording = false;
    uint32_t recorded_frames = 0;
    bool error_on = false;
    bool has_stats = false;  // false before the first frame
    FrameStats stats;
    bool legend = false;             // node boxes are on: explain their colours
    bool validation_legend = false;  // the validation overlay is on: explain its colours
    bool help = false;
    std::string message;  // e.g. the file a screenshot went to; empty: none
};

// The lines of the panel, as printed (tests read them).
std::vector<std::string> hudLines(const HudState& state);

// Where each row of the panel goes in a width x height picture: the text lines first, then the
// legend entries when shown. Pure, so tests can check that every row lands inside the picture.
struct HudRow {
    int x = 0, y = 0;  // top left of the row's text (or of a legend swatch)
    int width = 0;     // of its text, swatch included
};
struct HudLayout {
    int scale = 1;
    int pad = 4;
    int swatch = 7;
    std::vector<HudRow> rows;
    int panel_width = 0, panel_height = 0;  // the dark panel behind them, from (0, 0)
};

// Font scale 2 on wide pictures when every row fits the height, 1 otherwise; rows that still do
// not fit go on in further columns to the right rather than past the bottom.
HudLayout layoutHud(uint32_t width, uint32_t height, const HudState& state);

// Draws the panel at the top left, as layoutHud() places it.
void drawHud(RasterCanvas& canvas, const HudState& state);

}  // namespace occsim
