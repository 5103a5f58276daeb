#include "occsim/culling/testing/software_depth_pyramid.h"

#include <algorithm>
#include <cassert>

namespace occsim {
namespace {

// One level from the one below (or from the raster): each texel the farthest (largest) value of
// the cells it covers (rule 1 and 2).
void reduce(std::span<const float> fine, uint32_t fine_w, uint32_t fine_h, std::vector<float>& out,
            uint32_t out_w, uint32_t out_h) {
    out.assign(size_t{out_w} * out_h, 0.0f);
    for (uint32_t y = 0; y < out_h; ++y) {
        const uint32_t fy0 = hzb::firstCovered(y, fine_h, out_h);
        const uint32_t fy1 = hzb::lastCovered(y, fine_h, out_h);
        for (uint32_t x = 0; x < out_w; ++x) {
            const uint32_t fx0 = hzb::firstCovered(x, fine_w, out_w);
            const uint32_t fx1 = hzb::lastCovered(x, fine_w, out_w);
            float farthest = fine[size_t{fy0} * fine_w + fx0];
            for (uint32_t fy = fy0; fy <= fy1; ++fy) {
                for (uint32_t fx = fx0; fx <= fx1; ++fx) {
                    farthest = std::max(farthest, fine[size_t{fy} * fine_w + fx]);
                }
            }
            out[size_t{y} * out_w + x] = farthest;
        }
    }
}

}  // namespace

void SoftwareDepthPyramid::build(std::span<const float> depth, uint32_t width, uint32_t height) {
    assert(width > 0 && height > 0 && depth.size() == size_t{width} * height);
    viewport_w_ = width;
    viewport_h_ = height;
    const uint32_t base_w = hzb::pyramidBaseSize(width), base_h = hzb::pyramidBaseSize(height);
    const uint32_t count = hzb::pyramidLevelCount(base_w, base_h);
    levels_.resize(count);
    for (uint32_t l = 0; l < count; ++l) {
        Level& level = levels_[l];
        level.width = hzb::levelSize(base_w, l);
        level.height = hzb::levelSize(base_h, l);
        if (l == 0) {
            reduce(depth, width, height, level.depth, level.width, level.height);
        } else {
            const Level& below = levels_[l - 1];
            reduce(below.depth, below.width, below.height, level.depth, level.width, level.height);
        }
    }
    built_ = true;
}

uint32_t SoftwareDepthPyramid::levelFor(const hzb::TexelRect& pixels) const {
    return hzb::pyramidLevelFor(
        hzb::baseTexelsOf(pixels, viewport_w_, viewport_h_, levels_[0].width, levels_[0].height));
}

hzb::TexelRect SoftwareDepthPyramid::footprintFor(const hzb::TexelRect& pixels) const {
    const hzb::TexelRect base =
        hzb::baseTexelsOf(pixels, viewport_w_, viewport_h_, levels_[0].width, levels_[0].height);
    return hzb::footprintAt(base, hzb::pyramidLevelFor(base));
}

bool SoftwareDepthPyramid::mayShow(const hzb::TexelRect& pixels, float nearest) const {
    if (!built_) return true;
    return mayShowAt(footprintFor(pixels), levelFor(pixels), nearest);
}

bool SoftwareDepthPyramid::mayShowAt(const hzb::TexelRect& footprint, uint32_t level,
                                     float nearest) const {
    for (uint32_t y = footprint.y0; y <= footprint.y1; ++y) {
        for (uint32_t x = footprint.x0; x <= footprint.x1; ++x) {
            if (!(nearest > texel(level, x, y))) return true;  // NaN shows
        }
    }
    return false;
}

}  // namespace occsim
