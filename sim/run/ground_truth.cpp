#include "sim/run/ground_truth.h"

#include <chrono>
#include <stdexcept>

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
    const ShadowView* shadow = world.shadowView();
    frame_.has_shadow = shadow != nullptr && !shadow->box.empty;
    ShadowLookup lookup;
    if (frame_.has_shadow) {
        // Every object into the shadow map, with the ID of the one nearest the light per texel.
        if (!shadow_map_ || shadow_map_->size() != shadow->map_size) {
            shadow_map_ = std::make_unique<GlShadowMap>(shadow->map_size, /*caster_ids=*/true);
        }
        renderer_.setView(shadow->render, shadow->model_views);
        shadow_map_->begin(renderer_);
        for (uint32_t o = 0; o < objects; ++o) renderer_.drawObject(o);
        lookup = shadow_map_->lookupFor(world.view().render, shadow->render,
                                        renderer_.depthConvention());
    }
    renderer_.setView(world.view().render, world.modelViews());
    renderer_.setShadow(frame_.has_shadow ? &lookup : nullptr);
    renderer_.beginFrame();
    for (uint32_t o = 0; o < objects; ++o) device_.drawObject(o);
    renderer_.readObjectIds(frame_.ids);
    renderer_.readDepthRanks(frame_.depth);
    if (frame_.has_shadow) {
        renderer_.readShadowTexels(frame_.shadow_texels);
        shadow_map_->readCasterIds(frame_.shadow_casters);
    }
    renderer_.setShadow(nullptr);
    if (with_colour) renderer_.readColor(frame_.rgba);
    nearestLegitimateRanks(renderer_, world.view().render, world.state().boxes, nearest_rank_);
    frame_.stray_fragments =
        markStrayFragments(frame_.ids, frame_.depth, nearest_rank_, frame_.stray);
    frame_.visible.assign(objects, 0);
    const bool stereo = world.stereoViews() != nullptr;
    frame_.eye_visible.assign(stereo ? objects : 0, 0);
    // Stereo: the left eye's pixels are those from its first row on (stereoEyeFirstRow).
    const size_t left_first = size_t{stereoEyeFirstRow(0, renderer_.height())} * renderer_.width();
    for (size_t i = 0; i < frame_.ids.size(); ++i) {
        if (frame_.ids[i] == 0 || frame_.stray[i]) continue;
        frame_.visible[frame_.ids[i] - 1] = 1;
        if (stereo) frame_.eye_visible[frame_.ids[i] - 1] |= i >= left_first ? 1 : 2;
    }
    frame_.shadow_pixels.assign(frame_.has_shadow ? objects : 0, 0);
    if (frame_.has_shadow) {
        for (size_t i = 0; i < frame_.ids.size(); ++i) {
            const uint32_t texel = frame_.shadow_texels[i];
            if (frame_.ids[i] == 0 || frame_.stray[i] || texel == 0) continue;
            const uint32_t caster = frame_.shadow_casters[texel - 1];
            if (caster != 0 && caster <= objects) ++frame_.shadow_pixels[caster - 1];
        }
    }
    serial_ = world.frameSerial();
    has_colour_ = with_colour;
    ++renders_;
    ms_total_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return frame_;
}

void GroundTruth::readShadowDepth(std::vector<float>& depth) const {
    if (!frame_.has_shadow || !shadow_map_) {
        throw std::logic_error("GroundTruth::readShadowDepth: the frame had no shadow pass");
    }
    shadow_map_->readDepth(depth);
}

}  // namespace occsim
