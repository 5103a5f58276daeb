#include "sim/view/hud.h"

#include "sim/view/key_bindings.h"
#include "sim/view/node_boxes.h"

#include <algorithm>
#include <cstdio>

namespace occsim {
namespace {

constexpr Rgb kPanel{10, 12, 18};
constexpr Rgb kText{235, 235, 235};
constexpr Rgb kDim{150, 156, 170};
constexpr Rgb kRecording{255, 70, 70};

std::string format(const char* fmt, auto... args) {
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, args...);
    return buf;
}

// Thousands separated by commas: triangle counts run into the millions.
std::string grouped(int64_t value) {
    const std::string digits = std::to_string(value < 0 ? -value : value);
    std::string out = value < 0 ? "-" : "";
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

}  // namespace

std::vector<std::string> hudLines(const HudState& s) {
    std::vector<std::string> lines;
    std::string state = s.algorithm + format(" (%u/%u)", s.algorithm_place, s.algorithm_count) +
                        format("   frame %u  %.2f s", s.frame, s.time_s) + (s.paused ? "   paused" : "");
    state += s.flying ? format("   flying %.1f m/s", s.fly_speed_mps) : std::string("   path");
    if (s.recording) state += format("   rec %u frames", s.recorded_frames);
    lines.push_back(state);

    if (s.has_stats) {
        std::string figures = format("frame time %.2f ms   queries %llu   triangles ", s.stats.frame_ms,
                                     static_cast<unsigned long long>(s.stats.queries)) +
                              grouped(static_cast<int64_t>(s.stats.triangles));
        figures += s.error_on ? "   error px " + grouped(s.stats.error_pixels) + "   ties " +
                                    grouped(s.stats.tie_pixels) + "   missed " +
                                    grouped(s.stats.missed_objects)
                              : "   error off (g)";
        lines.push_back(figures);
    }
    if (!s.message.empty()) lines.push_back(s.message);
    if (s.help) {
        for (const KeyBinding& k : actionKeys()) lines.push_back(format("%-10s", std::string(k.keys).c_str()) + " " + std::string(k.description));
        for (const FlyKeyHelp& k : flyKeys()) lines.push_back(format("%-10s", std::string(k.keys).c_str()) + " " + std::string(k.description));
    } else {
        lines.push_back("h: keys");
    }
    return lines;
}

void drawHud(RasterCanvas& canvas, const HudState& state) {
    const int scale = canvas.width() >= 1000 ? 2 : 1;
    const int line_h = RasterCanvas::textHeight(scale) + 4 * scale;
    const int pad = 4 * scale;
    const int swatch = RasterCanvas::textHeight(scale);
    const std::vector<std::string> lines = hudLines(state);

    int width = 0;
    for (const std::string& l : lines) width = std::max(width, RasterCanvas::textWidth(l, scale));
    const auto legend = shownNodeBoxClasses();
    if (state.legend) {
        for (const NodeBoxClass& c : legend) {
            width = std::max(width, swatch + pad + RasterCanvas::textWidth(c.label, scale));
        }
    }
    const int rows = static_cast<int>(lines.size() + (state.legend ? legend.size() : 0));
    canvas.fillRect(0, 0, width + 2 * pad, rows * line_h + 2 * pad - 4 * scale, kPanel, 0.75f);

    int y = pad;
    for (size_t i = 0; i < lines.size(); ++i, y += line_h) {
        const bool first = i == 0;
        canvas.text(pad, y, lines[i], first && state.recording ? kRecording : first ? kText : kDim, scale);
    }
    if (!state.legend) return;
    for (const NodeBoxClass& c : legend) {
        canvas.outlineRect(pad, y, pad + swatch - 1, y + swatch - 1, nodeClassColour(c.node_class));
        canvas.text(pad + swatch + pad, y, c.label, kText, scale);
        y += line_h;
    }
}

}  // namespace occsim
