#include "sim/view/hud.h"

#include <algorithm>
#include <cstdio>

#include "sim/output/validation_overlay.h"
#include "sim/view/key_bindings.h"
#include "sim/view/node_boxes.h"

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
                        format("   frame %u  %.2f s", s.frame, s.time_s) +
                        (s.paused ? "   paused" : "");
    state += s.flying ? format("   flying %.1f m/s", s.fly_speed_mps) : std::string("   path");
    if (s.recording) state += format("   rec %u frames", s.recorded_frames);
    lines.push_back(state);

    if (s.has_stats) {
        std::string figures =
            format("frame time %.2f ms   queries %llu   triangles ", s.stats.frame_ms,
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
        for (const KeyBinding& k : actionKeys())
            lines.push_back(format("%-10s", std::string(k.keys).c_str()) + " " +
                            std::string(k.description));
        for (const FlyKeyHelp& k : flyKeys())
            lines.push_back(format("%-10s", std::string(k.keys).c_str()) + " " +
                            std::string(k.description));
    } else {
        lines.push_back("h: keys");
    }
    return lines;
}

namespace {

// Rows at this scale in as few columns of rows_per_column as the height allows.
HudLayout placeRows(const std::vector<int>& widths, int scale, uint32_t height) {
    HudLayout layout;
    layout.scale = scale;
    layout.pad = 4 * scale;
    layout.swatch = RasterCanvas::textHeight(scale);
    const int line_h = RasterCanvas::textHeight(scale) + 4 * scale;
    const int usable = static_cast<int>(height) - 2 * layout.pad + 4 * scale;
    const size_t per_column = static_cast<size_t>(std::max(1, usable / line_h));
    int x = layout.pad, column_width = 0, deepest = 0;
    for (size_t i = 0; i < widths.size(); ++i) {
        if (i > 0 && i % per_column == 0) {
            x += column_width + 3 * layout.pad;
            column_width = 0;
        }
        const int y = layout.pad + static_cast<int>(i % per_column) * line_h;
        layout.rows.push_back({x, y, widths[i]});
        column_width = std::max(column_width, widths[i]);
        deepest = std::max(deepest, y + RasterCanvas::textHeight(scale));
    }
    layout.panel_width = x + column_width + layout.pad;
    layout.panel_height = deepest + layout.pad;
    return layout;
}

}  // namespace

HudLayout layoutHud(uint32_t width, uint32_t height, const HudState& state) {
    const int large = width >= 1000 ? 2 : 1;
    for (int scale = large;; --scale) {
        std::vector<int> widths;
        for (const std::string& l : hudLines(state))
            widths.push_back(RasterCanvas::textWidth(l, scale));
        if (state.legend) {
            for (const NodeBoxClass& c : shownNodeBoxClasses()) {
                widths.push_back(RasterCanvas::textHeight(scale) + 4 * scale +
                                 RasterCanvas::textWidth(c.label, scale));
            }
        }
        if (state.validation_legend) {
            for (const ValidationClass& c : validationClasses()) {
                widths.push_back(RasterCanvas::textHeight(scale) + 4 * scale +
                                 RasterCanvas::textWidth(c.label, scale));
            }
        }
        HudLayout layout = placeRows(widths, scale, height);
        // The large font only where one column holds every row; the small one wraps.
        const bool one_column = layout.rows.empty() || layout.rows.back().x == layout.pad;
        if (scale == 1 || one_column) return layout;
    }
}

void drawHud(RasterCanvas& canvas, const HudState& state) {
    const HudLayout layout = layoutHud(canvas.width(), canvas.height(), state);
    const int scale = layout.scale;
    const std::vector<std::string> lines = hudLines(state);
    canvas.fillRect(0, 0, layout.panel_width - 1, layout.panel_height - 1, kPanel, 0.75f);
    for (size_t i = 0; i < lines.size(); ++i) {
        const bool first = i == 0;
        canvas.text(layout.rows[i].x, layout.rows[i].y, lines[i],
                    first && state.recording ? kRecording
                    : first                  ? kText
                                             : kDim,
                    scale);
    }
    size_t i = lines.size();
    if (state.legend) {
        for (const NodeBoxClass& c : shownNodeBoxClasses()) {
            const HudRow& r = layout.rows[i++];
            canvas.outlineRect(r.x, r.y, r.x + layout.swatch - 1, r.y + layout.swatch - 1,
                               nodeClassColour(c.node_class));
            canvas.text(r.x + layout.swatch + layout.pad, r.y, c.label, kText, scale);
        }
    }
    if (state.validation_legend) {
        for (const ValidationClass& c : validationClasses()) {
            const HudRow& r = layout.rows[i++];
            canvas.outlineRect(r.x, r.y, r.x + layout.swatch - 1, r.y + layout.swatch - 1,
                               c.colour);
            canvas.text(r.x + layout.swatch + layout.pad, r.y, c.label, kText, scale);
        }
    }
}

}  // namespace occsim
