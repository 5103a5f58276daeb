// Two-phase hierarchical-Z culling; see hzb_culler.h and docs/hzb.md.
#include "culling/cullers/hzb_culler.h"

#include "culling/cullers/gpu_driven_culler.h"
#include "occsim/culling/declaration/culler_row.h"
#include "occsim/culling/declaration/option_table.h"

namespace occsim {

HzbCuller::HzbCuller(const HzbOptions& options) : options_(options) {}

void HzbCuller::reset(const BspTree& tree) {
    object_visible_.assign(tree.objectCount(), 0);
    object_drawn_.assign(tree.objectCount(), 0);
    node_visible_.reset(tree);
    pass_ = 0;
}

bool HzbCuller::wasVisible(const Unit& u) const {
    const uint64_t stamp = u.is_node ? node_visible_[u.index] : object_visible_[u.index];
    return stamp != 0 && stamp == pass_ - 1;
}

void HzbCuller::markVisible(const Unit& u) {
    (u.is_node ? node_visible_[u.index] : object_visible_[u.index]) = pass_;
}

void HzbCuller::drawObject(uint32_t object, RenderDevice& device) {
    if (object_drawn_[object] == pass_) return;
    object_drawn_[object] = pass_;
    device.drawObject(object);
}

void HzbCuller::drawUnit(const BspTree& tree, const Unit& u, RenderDevice& device) {
    if (!u.is_node) {
        drawObject(u.index, device);
        return;
    }
    forEachObjectInFrustum(tree, u.index, view_, u.inside_frustum,
                           [&](uint32_t o) { drawObject(o, device); });
}

void HzbCuller::recordUnit(const Unit& u, Decision why) const {
    if (!view_.decisions) return;
    if (u.is_node) why.flags |= kDecisionNodeUnit;
    view_.decisions->add(u.is_node ? QueryTag::nodeObjects(u.index) : QueryTag::object(u.index),
                         why);
}

// The units in the frustum, front to back. Those the near plane may cut are visible without a
// test (rule 5): they are marked visible here, so phase 1 draws them.
void HzbCuller::collectUnits(const BspTree& tree, const CullFrame& frame) {
    units_.clear();
    const auto nearPlaneTouches = [&](const Aabb& box) {
        return nearPlaneTouchesBox(box, frame.view.eye, frame.view.near_radius);
    };
    const auto addObject = [&](uint32_t o) {
        const Unit u{o, false, false};
        if (nearPlaneTouches(tree.objectBox(o))) markVisible(u);  // this pass: phase 1 draws it
        units_.push_back(u);
    };
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        if (!options_.node_units || nearPlaneTouches(tree.bounds(visit.node))) {
            forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum, addObject);
        } else if (tree.firstObject(visit.node) != BspTree::kNone) {
            units_.push_back({visit.node, true, visit.inside_frustum});
        }
        return true;
    });
}

void HzbCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    if (object_visible_.size() != tree.objectCount()) reset(tree);
    node_visible_.sync(tree);
    view_ = prepareView(frame);
    ++pass_;
    // A run refuses this culler on a device without the capability (CullerRow::
    // device_needs); called on one anyway (a test looping over every culler), it draws
    // everything in the frustum.
    DepthPyramid* pyramid = device.depthPyramid();
    collectUnits(tree, frame);

    // Phase 1: what was visible last frame, and what the near plane reaches (marked this pass).
    bool drew_any = false;
    for (const Unit& u : units_) {
        const uint64_t stamp = u.is_node ? node_visible_[u.index] : object_visible_[u.index];
        if (stamp == pass_ || wasVisible(u)) {
            Decision why = decisionOf(stamp == pass_ ? DecisionKind::DrawnNearPlane
                                                     : DecisionKind::DrawnOnPyramid);
            why.phase = 1;
            recordUnit(u, why);
            drawUnit(tree, u, device);
            drew_any = true;
        }
    }

    // Phase 2: everything else in the frustum, against the pyramid of phase 1's depth.
    boxes_.clear();
    for (const Unit& u : units_) {
        const uint64_t stamp = u.is_node ? node_visible_[u.index] : object_visible_[u.index];
        if (stamp == pass_) continue;  // the near plane reaches it: visible, drawn
        boxes_.push_back(u.is_node ? tree.bounds(u.index) : tree.objectBox(u.index));
    }
    flags_.assign(boxes_.size(), 1);
    const bool tested = drew_any && pyramid && !boxes_.empty();
    if (tested) {
        pyramid->build();
        pyramid->testBounds(
            boxes_, options_.sphere_bounds ? PyramidBound::Sphere : PyramidBound::Box, flags_);
    }
    last_tested_ = static_cast<uint32_t>(drew_any ? boxes_.size() : 0);
    last_passed_ = 0;
    size_t next = 0;
    for (const Unit& u : units_) {
        const uint64_t stamp = u.is_node ? node_visible_[u.index] : object_visible_[u.index];
        if (stamp == pass_) continue;
        const bool passed = flags_[next] != 0;
        if (view_.decisions && !wasVisible(u)) {  // a unit phase 1 drew keeps phase 1's reason
            Decision why =
                decisionOf(passed ? DecisionKind::DrawnOnPyramid : DecisionKind::CulledOnPyramid);
            why.phase = 2;
            if (tested) {
                const uint32_t level =
                    pyramid->levelOf(boxes_[next], options_.sphere_bounds ? PyramidBound::Sphere
                                                                          : PyramidBound::Box);
                why.level =
                    level < Decision::kNoLevel ? static_cast<uint8_t>(level) : Decision::kNoLevel;
            } else {
                why.flags |= kDecisionNoPyramid;
            }
            recordUnit(u, why);
        }
        ++next;
        if (!passed) continue;  // hidden: it drops out of next frame's phase 1
        ++last_passed_;
        markVisible(u);
        drawUnit(tree, u, device);  // a unit drawn in phase 1 is not drawn again
    }
}

// --- Registration -------------------------------------------------------------------------------

namespace {

// hzb's and raster's option of the same name.
constexpr const char* kNodeUnitsHelp =
    "test BSP nodes (their bounds; a node that passes draws its own objects) instead of objects";

const OptionTable<HzbOptions>& hzbOptionTable() {
    static const OptionTable<HzbOptions> table = {
        booleanOption(OCCSIM_OPTION_MEMBER(HzbOptions, sphere_bounds),
                      "test the sphere around each box (its exact projected rectangle) instead "
                      "of the box's 8 projected corners"),
        booleanOption(OCCSIM_OPTION_MEMBER(HzbOptions, node_units), kNodeUnitsHelp),
        booleanOption(OCCSIM_OPTION_MEMBER(HzbOptions, read_back),
                      "read the pyramid's flags back in the frame and draw phase 2 from the CPU "
                      "(the scheme before GPU-driven draws) instead of deciding and drawing both "
                      "phases on the device"),
    };
    return table;
}

const OptionTable<GpuDrivenOptions>& rasterOptionTable() {
    static const OptionTable<GpuDrivenOptions> table = {
        booleanOption(OCCSIM_OPTION_MEMBER(GpuDrivenOptions, node_units), kNodeUnitsHelp),
        integerOption(OCCSIM_OPTION_MEMBER(GpuDrivenOptions, batches), "batches", 1, 16,
                      "test and draw phase 2 in this many batches, front to back, each twice the "
                      "one before: a batch is tested against what the batches before it drew "
                      "(1: the two phases as published)"),
    };
    return table;
}

}  // namespace

CullerRow hzbRegistration() {
    CullerRow t;
    t.name = "hzb";
    t.summary =
        "two-phase hierarchical-Z culling: last frame's visible set, a depth pyramid, "
        "the rest tested on it";
    t.conservative = true;
    t.issues_queries = false;
    t.device_needs = kDepthPyramid | kGpuDrivenDraws;
    t.options = hzbOptionTable().descriptor(HzbOptions{});
    t.factory = [](const CullerContext& c) -> std::unique_ptr<Culler> {
        const HzbOptions options = hzbOptionTable().read(c.options);
        if (options.read_back) return std::make_unique<HzbCuller>(options);
        GpuDrivenOptions gpu;
        gpu.test = GpuTest::Pyramid;
        gpu.shape = options.sphere_bounds ? PyramidBound::Sphere : PyramidBound::Box;
        gpu.node_units = options.node_units;
        return std::make_unique<GpuDrivenCuller>(gpu);
    };
    return t;
}

CullerRow rasterRegistration() {
    CullerRow t;
    t.name = "raster";
    t.summary =
        "GPU-driven two-phase culling that rasterises each object's box against the depth "
        "buffer (last frame's visible set first)";
    t.conservative = true;
    t.issues_queries = false;
    t.device_needs = kGpuDrivenDraws | kBoxRaster;
    // Phase 2 in 4 batches by default (1 is nvpro-samples' two phases as published): measured in
    // docs/hzb.md, it draws a third to a fifth of the objects inside the house for the same time.
    GpuDrivenOptions defaults;
    defaults.batches = 4;
    t.options = rasterOptionTable().descriptor(defaults);
    t.factory = [](const CullerContext& c) -> std::unique_ptr<Culler> {
        GpuDrivenOptions options = rasterOptionTable().read(c.options);
        options.test = GpuTest::BoxRaster;
        return std::make_unique<GpuDrivenCuller>(options);
    };
    return t;
}

}  // namespace occsim
