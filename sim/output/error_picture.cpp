#include "sim/output/error_picture.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "sim/output/raster_canvas.h"

namespace occsim {

std::vector<uint8_t> composeErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height) {
    const size_t pixels = size_t{width} * height;
    if (frame.culled_rgba.size() != pixels * 4 || frame.truth_rgba.size() != pixels * 4 ||
        frame.culled_ids.size() != pixels || frame.truth_ids.size() != pixels ||
        frame.differences.size() != pixels) {
        throw std::invalid_argument("composeErrorPicture: buffers do not match the frame size");
    }
    const size_t row_out = size_t{width} * 3 * 4;
    std::vector<uint8_t> out(row_out * height);
    for (uint32_t y = 0; y < height; ++y) {
        uint8_t* row = out.data() + y * row_out;
        const size_t in = size_t{y} * width * 4;
        std::copy_n(frame.culled_rgba.data() + in, width * 4, row);
        std::copy_n(frame.truth_rgba.data() + in, width * 4, row + width * 4);
        uint8_t* diff = row + 2 * width * 4;
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t{y} * width + x;
            uint8_t* p = diff + x * 4;
            const auto difference = static_cast<PixelDifference>(frame.differences[i]);
            if (difference == PixelDifference::Error) {
                p[0] = kErrorColour[0], p[1] = kErrorColour[1], p[2] = kErrorColour[2];
            } else if (difference == PixelDifference::Tie) {
                p[0] = kTieColour[0], p[1] = kTieColour[1], p[2] = kTieColour[2];
            } else if (difference == PixelDifference::Stray) {
                p[0] = kStrayColour[0], p[1] = kStrayColour[1], p[2] = kStrayColour[2];
            } else {
                for (int c = 0; c < 3; ++c) p[c] = frame.truth_rgba[i * 4 + c] / 3;
            }
            p[3] = 255;
        }
    }
    return out;
}

uint32_t errorPictureScale(uint32_t frame_width) {
    return std::clamp<uint32_t>(800 / std::max<uint32_t>(frame_width, 1), 1, 8);
}

std::vector<PixelCluster> errorClusters(const std::vector<uint8_t>& differences, uint32_t width,
                                        uint32_t height) {
    std::vector<PixelCluster> clusters;
    if (differences.size() != size_t{width} * height) return clusters;
    auto isError = [&](size_t i) {
        return static_cast<PixelDifference>(differences[i]) == PixelDifference::Error;
    };
    std::vector<uint8_t> seen(differences.size(), 0);
    std::vector<uint32_t> stack;
    for (size_t start = 0; start < differences.size(); ++start) {
        if (seen[start] || !isError(start)) continue;
        PixelCluster c;
        c.x0 = c.x1 = static_cast<uint32_t>(start % width);
        c.y0 = c.y1 = static_cast<uint32_t>(start / width);
        seen[start] = 1;
        stack.assign(1, static_cast<uint32_t>(start));
        while (!stack.empty()) {
            const uint32_t i = stack.back();
            stack.pop_back();
            const uint32_t x = i % width, y = i / width;
            ++c.pixels;
            c.x0 = std::min(c.x0, x), c.x1 = std::max(c.x1, x);
            c.y0 = std::min(c.y0, y), c.y1 = std::max(c.y1, y);
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int64_t nx = int64_t{x} + dx, ny = int64_t{y} + dy;
                    if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
                    const size_t n = static_cast<size_t>(ny) * width + static_cast<size_t>(nx);
                    if (seen[n] || !isError(n)) continue;
                    seen[n] = 1;
                    stack.push_back(static_cast<uint32_t>(n));
                }
            }
        }
        clusters.push_back(c);
    }
    std::stable_sort(
        clusters.begin(), clusters.end(),
        [](const PixelCluster& a, const PixelCluster& b) { return a.pixels > b.pixels; });
    return clusters;
}

std::vector<MissedInFrame> missedObjects(const ErrorFrame& frame, uint32_t width, uint32_t height) {
    std::map<uint32_t, PixelCluster> by_object;
    const size_t pixels = size_t{width} * height;
    if (frame.differences.size() != pixels || frame.truth_ids.size() != pixels) return {};
    for (size_t i = 0; i < pixels; ++i) {
        if (static_cast<PixelDifference>(frame.differences[i]) != PixelDifference::Error) continue;
        const uint32_t id = frame.truth_ids[i];
        if (id == 0) continue;  // background is never nearer: no error comes from it
        const auto x = static_cast<uint32_t>(i % width), y = static_cast<uint32_t>(i / width);
        auto [it, fresh] = by_object.try_emplace(id - 1, PixelCluster{x, y, x, y, 0});
        PixelCluster& c = it->second;
        c.x0 = std::min(c.x0, x), c.x1 = std::max(c.x1, x);
        c.y0 = std::min(c.y0, y), c.y1 = std::max(c.y1, y);
        ++c.pixels;
    }
    std::vector<MissedInFrame> out;
    for (const auto& [object, where] : by_object) out.push_back({object, where});
    std::stable_sort(out.begin(), out.end(), [](const MissedInFrame& a, const MissedInFrame& b) {
        return a.where.pixels > b.where.pixels;
    });
    return out;
}

namespace {

constexpr size_t kLabelledObjects = 24;

// One panel of the labelled picture on the canvas: where its frame pixels go.
struct PanelPlace {
    int left = 0, top = 0, width = 0, height = 0;  // in canvas pixels, top-down
    uint32_t frame_height = 0, scale = 1;
    // Canvas bounds of frame pixels [x0, x1] x [y0, y1] (rows bottom-up, as the frame's).
    void bounds(const PixelCluster& c, int& cx0, int& cy0, int& cx1, int& cy1) const {
        const int s = static_cast<int>(scale);
        cx0 = left + static_cast<int>(c.x0) * s;
        cx1 = left + static_cast<int>(c.x1 + 1) * s - 1;
        cy0 = top + static_cast<int>(frame_height - 1 - c.y1) * s;
        cy1 = top + static_cast<int>(frame_height - c.y0) * s - 1;
    }
    bool inside(int x, int y) const {
        return x >= left && x < left + width && y >= top && y < top + height;
    }
};

// A box `margin` canvas pixels outside the bounds, two pixels of green on a black edge; an edge
// that would fall outside the panel is left out rather than drawn along its border, where it
// could cover the very pixels it points at.
void ring(RasterCanvas& canvas, const PanelPlace& panel, const PixelCluster& c, int margin) {
    int x0, y0, x1, y1;
    panel.bounds(c, x0, y0, x1, y1);
    const Rgb green{kRingColour[0], kRingColour[1], kRingColour[2]}, black{0, 0, 0};
    for (int k = 0; k < 4; ++k) {
        const int m = margin + k;
        const Rgb colour = k == 0 || k == 3 ? black : green;
        const int lx = x0 - m, rx = x1 + m, ty = y0 - m, by = y1 + m;
        auto row = [&](int y) {
            if (y < panel.top || y >= panel.top + panel.height) return;
            for (int x = std::max(lx, panel.left); x <= std::min(rx, panel.left + panel.width - 1);
                 ++x)
                canvas.pixel(x, y, colour);
        };
        auto column = [&](int x) {
            if (x < panel.left || x >= panel.left + panel.width) return;
            for (int y = std::max(ty, panel.top); y <= std::min(by, panel.top + panel.height - 1);
                 ++y)
                canvas.pixel(x, y, colour);
        };
        row(ty), row(by), column(lx), column(rx);
    }
}

// The object's label beside its ring: right of it where it fits in the panel, else left of it,
// green on black.
void label(RasterCanvas& canvas, const PanelPlace& panel, const PixelCluster& where, int margin,
           const std::string& text) {
    int x0, y0, x1, y1;
    panel.bounds(where, x0, y0, x1, y1);
    const int scale = 2, w = RasterCanvas::textWidth(text, scale) + 4,
              h = RasterCanvas::textHeight(scale) + 4;
    int x = x1 + margin + 5;
    if (x + w > panel.left + panel.width) x = x0 - margin - 5 - w;
    x = std::clamp(x, panel.left, std::max(panel.left, panel.left + panel.width - w));
    const int y =
        std::clamp(y0 - margin - 2, panel.top, std::max(panel.top, panel.top + panel.height - h));
    canvas.fillRect(x, y, x + w - 1, y + h - 1, Rgb{0, 0, 0});
    canvas.text(x + 2, y + 2, text, Rgb{kRingColour[0], kRingColour[1], kRingColour[2]}, scale);
}

std::string objectLabel(uint32_t object, const std::vector<std::string>* names) {
    std::string text(1, '#');
    text.append(std::to_string(object));
    if (names && object < names->size() && !(*names)[object].empty()) {
        text.push_back(' ');
        text.append((*names)[object]);
    }
    return text;
}

}  // namespace

LabelledPicture labelledErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height,
                                     const std::string& algorithm,
                                     const std::vector<std::string>* object_names) {
    const std::vector<uint8_t> panels = composeErrorPicture(frame, width, height);
    const uint32_t scale = errorPictureScale(width);
    const std::vector<PixelCluster> clusters = errorClusters(frame.differences, width, height);
    const std::vector<MissedInFrame> missed = missedObjects(frame, width, height);
    const int text_scale = 2, margin = 6;
    const int band = RasterCanvas::textHeight(text_scale) + 2 * margin;  // a label's strip
    const int panel_w = static_cast<int>(width * scale), panel_h = static_cast<int>(height * scale);
    // "..., ringed: 2 clusters, on #64, #12 (+3 more)": where the errors are, and whose.
    std::string where =
        std::to_string(clusters.size()) + (clusters.size() == 1 ? " cluster" : " clusters");
    for (size_t k = 0; k < missed.size() && k < kLabelledObjects; ++k)
        where += (k ? ", " : ", on ") + objectLabel(missed[k].object, object_names);
    if (missed.size() > kLabelledObjects)
        where += " (+" + std::to_string(missed.size() - kLabelledObjects) + " more)";
    const std::string labels[3] = {
        "culled: " + algorithm + ", frame " + std::to_string(frame.frame), "ground truth",
        "difference: " + std::to_string(frame.error_pixels) + " error px (magenta, ringed: " +
            where + "), " + std::to_string(frame.tie_pixels) + " tie px (yellow), stray (cyan)"};
    const int label_w = RasterCanvas::textWidth(labels[2], text_scale) + 2 * margin;
    RasterCanvas canvas(static_cast<uint32_t>(std::max(panel_w, label_w)),
                        static_cast<uint32_t>(3 * (band + panel_h)), Rgb{255, 255, 255});
    const size_t row_in = size_t{width} * 3 * 4;
    auto paint = [&](int p, uint32_t x, uint32_t y) {  // frame pixel (x, y top-down) of panel p
        const uint8_t* c = panels.data() + (height - 1 - y) * row_in +
                           static_cast<size_t>(p) * width * 4 + size_t{x} * 4;
        const int x0 = static_cast<int>(x * scale),
                  y0 = p * (band + panel_h) + band + static_cast<int>(y * scale);
        canvas.fillRect(x0, y0, x0 + static_cast<int>(scale) - 1, y0 + static_cast<int>(scale) - 1,
                        Rgb{c[0], c[1], c[2]});
    };
    // Rings stand a few picture pixels outside what they point at, whatever the scale.
    const int ring_margin = std::max(4, static_cast<int>(scale));
    for (int p = 0; p < 3; ++p) {
        const int top = p * (band + panel_h);
        canvas.text(margin, top + margin, labels[p], Rgb{0, 0, 0}, text_scale);
        // The panels' rows are bottom-up; the canvas's top-down.
        for (uint32_t y = 0; y < height; ++y) {
            for (uint32_t x = 0; x < width; ++x) paint(p, x, y);
        }
        const PanelPlace place{0, top + band, panel_w, panel_h, height, scale};
        for (const PixelCluster& c : clusters) ring(canvas, place, c, ring_margin);
        if (p == 0) continue;  // the culled frame does not show the missed objects
        for (size_t k = 0; k < missed.size() && k < kLabelledObjects; ++k) {
            label(canvas, place, missed[k].where, ring_margin + 3,
                  objectLabel(missed[k].object, object_names));
        }
    }
    // No ring or label hides an error pixel: they are painted again on top.
    for (size_t i = 0; i < frame.differences.size(); ++i) {
        if (static_cast<PixelDifference>(frame.differences[i]) != PixelDifference::Error) continue;
        const auto x = static_cast<uint32_t>(i % width), y = static_cast<uint32_t>(i / width);
        paint(2, x, height - 1 - y);
    }
    return {canvas.width(), canvas.height(), canvas.rgbaBottomUp()};
}

}  // namespace occsim
