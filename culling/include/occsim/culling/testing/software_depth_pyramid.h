// A depth pyramid over a CPU raster, built and tested with the rules of
// occsim/culling/geometry/hzb_rules.h: what the CPU test devices offer as their DepthPyramid
// capability, and what the rules' tests read. Depths are distances: larger is farther, so each
// texel holds the maximum of what it covers.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "occsim/culling/geometry/hzb_rules.h"

namespace occsim {

class SoftwareDepthPyramid {
  public:
    // Reduces a width x height raster (row-major, row 0 at the bottom) into the pyramid.
    void build(std::span<const float> depth, uint32_t width, uint32_t height);
    // Forgets the pyramid (every bound passes again) and keeps its memory.
    void clear() { built_ = false; }
    bool built() const { return built_; }

    // Whether a bound covering the viewport's pixels `pixels` whose nearest depth is `nearest` may
    // show: nearest is not farther than some texel of its footprint (ties pass). Every bound
    // passes before the first build().
    bool mayShow(const hzb::TexelRect& pixels, float nearest) const;
    // The same from a footprint at `level`: whether nearest is not farther than one of its texels
    // (every one is read, rule 4).
    bool mayShowAt(const hzb::TexelRect& footprint, uint32_t level, float nearest) const;

    uint32_t levelCount() const { return static_cast<uint32_t>(levels_.size()); }
    uint32_t levelWidth(uint32_t level) const { return levels_[level].width; }
    uint32_t levelHeight(uint32_t level) const { return levels_[level].height; }
    float texel(uint32_t level, uint32_t x, uint32_t y) const {
        return levels_[level].depth[size_t{y} * levels_[level].width + x];
    }
    // The footprint mayShow() reads for `pixels`: its level and texels (rules 3 and 4).
    uint32_t levelFor(const hzb::TexelRect& pixels) const;
    hzb::TexelRect footprintFor(const hzb::TexelRect& pixels) const;

  private:
    struct Level {
        uint32_t width = 0, height = 0;
        std::vector<float> depth;
    };
    std::vector<Level> levels_;
    uint32_t viewport_w_ = 0, viewport_h_ = 0;
    bool built_ = false;
};

}  // namespace occsim
