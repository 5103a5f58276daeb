#include "sim/run/ground_truth.h"

#include <chrono>

#include "sim/run/stray_fragments.h"

namespace occsim {

GroundTruth::GroundTruth(GlRenderer& renderer)
    : renderer_(renderer), device_(renderer, LatencyMode{}) {}

const GroundTruthFrame& GroundTruth::of(const SharedWorld& world, bool with_colour) {
    if (serial_ == world.frameSerial() && (has_colour_ || !with_colour)) return frame_;
    const auto start = std::chrono::steady_clock::now();
    // Every object, in index order, with no culling code on the way: the GPU clips. A culler's
    // mistake (a frustum test rounding the wrong way) cannot hide itself in its own ground truth.
    const uint32_t objects = world.scene().objectCount();
    renderer_.setView(world.view().render, world.modelViews());
    renderer_.beginFrame();
    for (uint32_t o = 0; o < objects; ++o) device_.drawObject(o);
    renderer_.readObjectIds(frame_.ids);
    renderer_.readDepthRanks(frame_.depth);
    if (with_colour) renderer_.readColor(frame_.rgba);
    nearestLegitimateRanks(renderer_, world.view().render, world.state().boxes, nearest_rank_);
    frame_.stray_fragments =
        markStrayFragments(frame_.ids, frame_.depth, nearest_rank_, frame_.stray);
    frame_.visible.assign(objects, 0);
    for (size_t i = 0; i < frame_.ids.size(); ++i) {
        if (frame_.ids[i] != 0 && !frame_.stray[i]) frame_.visible[frame_.ids[i] - 1] = 1;
    }
    serial_ = world.frameSerial();
    has_colour_ = with_colour;
    ++renders_;
    ms_total_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return frame_;
}

}  // namespace occsim
