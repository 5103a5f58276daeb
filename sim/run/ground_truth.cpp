#include "sim/run/ground_truth.h"

#include <chrono>

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
    frame_.visible.assign(objects, 0);
    for (uint32_t id : frame_.ids) {
        if (id != 0) frame_.visible[id - 1] = 1;
    }
    serial_ = world.frameSerial();
    has_colour_ = with_colour;
    ++renders_;
    ms_total_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return frame_;
}

}  // namespace occsim
