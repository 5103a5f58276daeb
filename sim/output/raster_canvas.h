// A tiny CPU raster for diagrams (the bird's-eye picture): an RGBA8 image with rows top-down,
// clipped pixel writes, Bresenham lines, rectangles, disks and text in an embedded 5x7 bitmap
// font. Nothing here knows about scenes; callers map their coordinates to pixels.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace occsim {

struct Rgb {
    uint8_t r = 0, g = 0, b = 0;
    bool operator==(const Rgb&) const = default;
};

class RasterCanvas {
  public:
    RasterCanvas(uint32_t width, uint32_t height, Rgb background);

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

    // Every drawing call clips to the image; coordinates outside are simply not painted.
    // alpha in [0, 1] blends over what is there (1 replaces).
    void pixel(int x, int y, Rgb c, float alpha = 1.0f);
    Rgb at(int x, int y) const;
    // Both end points included. The segment is clipped to the image first, so a line that runs
    // far outside costs only its visible length.
    void line(double x0, double y0, double x1, double y1, Rgb c, float alpha = 1.0f);
    void fillRect(int x0, int y0, int x1, int y1, Rgb c, float alpha = 1.0f);  // inclusive
    void outlineRect(int x0, int y0, int x1, int y1, Rgb c, float alpha = 1.0f);
    void disk(int cx, int cy, int radius, Rgb c);
    // Text in the 5x7 font, each font pixel drawn as scale x scale; (x, y) is the top left.
    // Lower case prints as upper case; characters without a glyph print as '?'.
    void text(int x, int y, std::string_view s, Rgb c, int scale = 1);
    static int textWidth(std::string_view s, int scale = 1) {
        return s.empty() ? 0 : static_cast<int>(s.size()) * 6 * scale - scale;
    }
    static int textHeight(int scale = 1) { return 7 * scale; }

    // RGBA8 with row 0 at the bottom, as encodePngBottomUp() expects.
    std::vector<uint8_t> rgbaBottomUp() const;

  private:
    uint32_t width_, height_;
    std::vector<Rgb> pixels_;  // row 0 at the top
};

}  // namespace occsim
