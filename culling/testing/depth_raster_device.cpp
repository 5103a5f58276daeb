#include "occsim/culling/testing/depth_raster_device.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace occsim {
namespace {

constexpr float kFar = std::numeric_limits<float>::infinity();

// A normalised device coordinate in [-1, 1] to a cell boundary, rounding outwards.
uint32_t cellFloor(float ndc, uint32_t cells) {
    const float c = std::floor((ndc + 1.0f) * 0.5f * static_cast<float>(cells));
    return static_cast<uint32_t>(std::clamp(c, 0.0f, static_cast<float>(cells)));
}
uint32_t cellCeil(float ndc, uint32_t cells) {
    const float c = std::ceil((ndc + 1.0f) * 0.5f * static_cast<float>(cells));
    return static_cast<uint32_t>(std::clamp(c, 0.0f, static_cast<float>(cells)));
}

}  // namespace

DepthRasterDevice::DepthRasterDevice(uint32_t width, uint32_t height, uint32_t latency_commands,
                                     bool with_pyramid)
    : width_(width),
      height_(height),
      depth_(width * height, kFar),
      queries_(latency_commands, "DepthRasterDevice"),
      with_pyramid_(with_pyramid) {}

void DepthRasterDevice::beginFrame(const glm::mat4& view_projection, glm::vec3 eye,
                                   std::span<const Aabb> object_boxes) {
    view_projection_ = view_projection;
    eye_ = eye;
    frustum_ = planeTableOf(frustumFromViewProjection(view_projection));
    boxes_.assign(object_boxes.begin(), object_boxes.end());
    std::fill(depth_.begin(), depth_.end(), kFar);
    drawn_.clear();
    skipped_.clear();
    query_log_.clear();
    pyramid_.clear();
}

DepthRasterDevice::Card DepthRasterDevice::cardOf(const Aabb& box) const {
    Card card;
    card.depth = std::sqrt(distanceSquared(box, eye_));
    glm::vec2 lo(kFar), hi(-kFar);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 p((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                          (i & 4) ? box.max.z : box.min.z);
        const glm::vec4 clip = view_projection_ * glm::vec4(p, 1.0f);
        if (!(clip.w > 1e-6f)) {  // at or behind the eye plane: the whole screen
            card.x1 = width_;
            card.y1 = height_;
            return card;
        }
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
    }
    card.x0 = cellFloor(lo.x, width_);
    card.x1 = cellCeil(hi.x, width_);
    card.y0 = cellFloor(lo.y, height_);
    card.y1 = cellCeil(hi.y, height_);
    return card;
}

void DepthRasterDevice::drawObject(uint32_t object) {
    queries_.countDraw();
    ++counters_.objects_drawn;
    rasterise(object);
}

void DepthRasterDevice::drawIf(QueryId id, std::span<const uint32_t> objects, ConditionWait wait) {
    const bool holds = queries_.conditionHolds(id, wait);  // decided when the draws are submitted
    for (uint32_t object : objects) {
        queries_.countDraw();
        ++counters_.objects_drawn;
        ++counters_.conditional_draws;
        if (holds) {
            rasterise(object);
        } else {
            skipped_.push_back(object);
        }
    }
}

void DepthRasterDevice::rasterise(uint32_t object) {
    assert(object < boxes_.size());
    drawn_.push_back(object);
    const Card c = cardOf(boxes_[object]);
    for (uint32_t y = c.y0; y < c.y1; ++y) {
        for (uint32_t x = c.x0; x < c.x1; ++x) {
            float& d = depth_[y * width_ + x];
            d = std::min(d, c.depth);
        }
    }
}

QueryId DepthRasterDevice::issueQuery(std::span<const Aabb> boxes,
                                      std::span<const QueryTag> subjects) {
    uint64_t samples = 0;
    for (const Aabb& box : boxes) samples += passingCells(box);
    query_log_.push_back(subjects.empty() ? QueryTag{} : subjects.front());
    return queries_.issue(samples, boxes.size(), counters_);
}

uint64_t DepthRasterDevice::passingCells(const Aabb& box) const {
    uint64_t cells = 0;
    const Card c = cardOf(box);
    for (uint32_t y = c.y0; y < c.y1; ++y) {
        for (uint32_t x = c.x0; x < c.x1; ++x) cells += c.depth <= depth_[y * width_ + x];
    }
    return cells;
}

bool DepthRasterDevice::isQueryReady(QueryId id) { return queries_.ready(id); }

QueryAnswer DepthRasterDevice::takeAnswer(QueryId id) {
    ++counters_.read_backs;
    return queries_.take(id, counters_);
}

DepthRasterDevice::Card DepthRasterDevice::cardOfSphere(const Aabb& box) const {
    const glm::dvec3 lo(box.min), hi(box.max);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = 0.5 * glm::length(hi - lo);
    Card card;
    card.depth = static_cast<float>(std::max(0.0, glm::length(centre - glm::dvec3(eye_)) - radius));
    const hzb::ScreenBound b = hzb::projectSphere(glm::dmat4(view_projection_), centre, radius);
    if (!hzb::testable(b, 1e-6)) {  // at or behind the eye plane: the whole screen
        card.x1 = width_;
        card.y1 = height_;
        return card;
    }
    card.x0 = cellFloor(static_cast<float>(b.x0), width_);
    card.x1 = cellCeil(static_cast<float>(b.x1), width_);
    card.y0 = cellFloor(static_cast<float>(b.y0), height_);
    card.y1 = cellCeil(static_cast<float>(b.y1), height_);
    return card;
}

void DepthRasterDevice::build() {
    ++counters_.pyramid_builds;
    pyramid_.build(depth_, width_, height_);
}

uint32_t DepthRasterDevice::levelOf(const Aabb& box, PyramidBound shape) const {
    if (!pyramid_.built()) return kNoLevel;
    const Card c = shape == PyramidBound::Sphere ? cardOfSphere(box) : cardOf(box);
    if (c.x0 >= c.x1 || c.y0 >= c.y1) return kNoLevel;
    return pyramid_.levelFor({c.x0, c.y0, c.x1 - 1, c.y1 - 1});
}

void DepthRasterDevice::testBounds(std::span<const Aabb> boxes, PyramidBound shape,
                                   std::span<uint8_t> visible) {
    ++counters_.read_backs;  // the flags go back to the culler
    testOnPyramid(boxes, shape, visible);
}

void DepthRasterDevice::testOnPyramid(std::span<const Aabb> boxes, PyramidBound shape,
                                      std::span<uint8_t> visible) {
    assert(visible.size() == boxes.size());
    counters_.pyramid_bounds += boxes.size();
    for (size_t i = 0; i < boxes.size(); ++i) {
        const Card c = shape == PyramidBound::Sphere ? cardOfSphere(boxes[i]) : cardOf(boxes[i]);
        if (c.x0 >= c.x1 || c.y0 >= c.y1) {  // no cell: it cannot show
            visible[i] = 0;
            continue;
        }
        visible[i] = pyramid_.mayShow({c.x0, c.y0, c.x1 - 1, c.y1 - 1}, c.depth) ? 1 : 0;
    }
}

uint32_t DepthRasterDevice::pendingQueries() const { return queries_.pending(); }

std::vector<uint8_t> DepthRasterDevice::groundTruth() const {
    std::vector<float> depth(width_ * height_, kFar);
    std::vector<Card> cards(boxes_.size());
    for (size_t o = 0; o < boxes_.size(); ++o) {
        if (classify(frustum_, boxes_[o]) == FrustumTest::Outside) continue;  // empty card
        cards[o] = cardOf(boxes_[o]);
        const Card& c = cards[o];
        for (uint32_t y = c.y0; y < c.y1; ++y) {
            for (uint32_t x = c.x0; x < c.x1; ++x) {
                depth[y * width_ + x] = std::min(depth[y * width_ + x], c.depth);
            }
        }
    }
    std::vector<uint8_t> visible(boxes_.size(), 0);
    for (size_t o = 0; o < boxes_.size(); ++o) {
        const Card& c = cards[o];
        for (uint32_t y = c.y0; y < c.y1 && !visible[o]; ++y) {
            for (uint32_t x = c.x0; x < c.x1; ++x) {
                if (c.depth <= depth[y * width_ + x]) {
                    visible[o] = 1;
                    break;
                }
            }
        }
    }
    return visible;
}

}  // namespace occsim
