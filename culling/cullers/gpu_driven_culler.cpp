// GPU-driven two-phase culling; see gpu_driven_culler.h and docs/hzb.md.
#include "culling/cullers/gpu_driven_culler.h"

#include <algorithm>
#include <cmath>

#include "occsim/culling/contract/depth_pyramid.h"
#include "occsim/culling/contract/render_device.h"

namespace occsim {

void secondPhaseBatchEnds(uint32_t units, uint32_t batches, std::vector<uint32_t>& ends) {
    ends.clear();
    batches = std::max<uint32_t>(batches, 1);
    // Batch b holds 2^b shares of 2^batches - 1 (in doubles: batches may exceed 63).
    const double shares = std::exp2(static_cast<double>(batches)) - 1.0;
    double share_end = 0.0;
    for (uint32_t b = 0; b + 1 < batches; ++b) {
        share_end += std::exp2(static_cast<double>(b));
        const auto end = static_cast<uint32_t>(static_cast<double>(units) * share_end / shares);
        if (end > (ends.empty() ? 0 : ends.back()) && end < units) ends.push_back(end);
    }
    ends.push_back(units);
}

GpuDrivenCuller::GpuDrivenCuller(const GpuDrivenOptions& options) : options_(options) {}

void GpuDrivenCuller::reset(const BspTree& tree) {
    object_count_ = tree.objectCount();
    reset_device_ = true;
    node_generation_.clear();  // every slot is forgotten: no node's needs forgetting again
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        node_generation_.push_back(tree.node(n).generation);
    }
    structure_version_ = tree.structureVersion();
}

// A node index the tree reused (a merge freed it, a split took it) stands for another node: its
// slot still holds the old node's answer, which would draw the new node's objects in phase 1
// (harmless, but not what the read-back hzb draws, whose NodeStateArray forgets it). New indices
// need nothing: a slot beyond the device's old count starts unseen.
void GpuDrivenCuller::forgetReusedNodes(const BspTree& tree) {
    forgotten_slots_.clear();
    if (!options_.node_units || structure_version_ == tree.structureVersion()) return;
    structure_version_ = tree.structureVersion();
    // Never shrunk: an index beyond `known` has never had a slot written since the reset.
    const auto known = static_cast<uint32_t>(node_generation_.size());
    if (tree.nodeCount() > known) node_generation_.resize(tree.nodeCount(), 0);
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const uint32_t generation = tree.node(n).generation;
        if (node_generation_[n] == generation) continue;
        node_generation_[n] = generation;
        if (n < known) forgotten_slots_.push_back(object_count_ + n);
    }
}

void GpuDrivenCuller::addUnit(const Aabb& bound, uint32_t slot, bool forced, QueryTag tag) {
    bounds_.push_back(bound);
    slots_.push_back(slot);
    forced_.push_back(forced ? 1 : 0);
    tags_.push_back(tag);
}

// The units in the frustum, front to back (the device draws in the draw list's order), and every
// object to draw with its unit. An object's slot is its index; a node's comes after the objects'.
void GpuDrivenCuller::collectUnits(const BspTree& tree, const CullFrame& frame) {
    bounds_.clear();
    slots_.clear();
    forced_.clear();
    tags_.clear();
    objects_.clear();
    object_units_.clear();
    const auto nearPlaneTouches = [&](const Aabb& box) {
        return nearPlaneTouchesBox(box, frame.view.eye, frame.view.near_radius);
    };
    const auto addObject = [&](uint32_t o) {
        const Aabb& box = tree.objectBox(o);
        objects_.push_back(o);
        object_units_.push_back(static_cast<uint32_t>(bounds_.size()));
        addUnit(box, o, nearPlaneTouches(box), QueryTag::object(o));
    };
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        if (!options_.node_units || nearPlaneTouches(tree.bounds(visit.node))) {
            forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum, addObject);
        } else if (tree.firstObject(visit.node) != BspTree::kNone) {
            // A node none of whose objects is in the frustum is tested all the same, as the
            // read-back HzbCuller tests it: its answer decides whether next frame's phase 1 draws
            // those of its objects that come into view.
            const auto unit = static_cast<uint32_t>(bounds_.size());
            forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum, [&](uint32_t o) {
                objects_.push_back(o);
                object_units_.push_back(unit);
            });
            addUnit(tree.bounds(visit.node), object_count_ + visit.node, false,
                    QueryTag::nodeObjects(visit.node));
        }
        return true;
    });
}

void GpuDrivenCuller::drawEverythingInFrustum(const BspTree& tree, RenderDevice& device) {
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum, [&](uint32_t o) {
            if (view_.decisions) {
                view_.decisions->add(QueryTag::object(o), decisionOf(DecisionKind::DrawnNoTest));
            }
            device.drawObject(o);
        });
        return true;
    });
}

void GpuDrivenCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                    RenderDevice& device) {
    if (object_count_ != tree.objectCount()) reset(tree);
    view_ = prepareView(frame);
    used_device_ = false;
    GpuDrivenDraws* gpu = device.gpuDrivenDraws();
    const bool capable =
        gpu && (options_.test == GpuTest::Pyramid ? device.depthPyramid() != nullptr
                                                  : gpu->offersBoxRaster());
    // A run refuses this culler on a device without the capability (CullerRow::
    // device_needs); called on one anyway (a test looping over every culler), it draws
    // everything in the frustum.
    if (!capable) {
        bounds_.clear();
        first_phase_.clear();
        passed_.clear();
        drawEverythingInFrustum(tree, device);
        return;
    }
    if (reset_device_) {
        gpu->resetVisibility();
        reset_device_ = false;
    }
    collectUnits(tree, frame);
    forgetReusedNodes(tree);
    GpuUnits units;
    units.bounds = bounds_;
    units.slots = slots_;
    units.forced = forced_;
    units.objects = objects_;
    units.object_units = object_units_;
    secondPhaseBatchEnds(static_cast<uint32_t>(bounds_.size()), options_.batches, batch_ends_);
    units.batch_ends = batch_ends_;
    units.forgotten_slots = forgotten_slots_;
    units.slot_count = object_count_ + tree.nodeCount();
    gpu->drawFirstPhase(units);
    gpu->drawSecondPhase(options_.test, options_.shape);
    used_device_ = true;
}

void GpuDrivenCuller::afterFrame(RenderDevice& device) {
    if (!used_device_) return;
    GpuDrivenDraws* gpu = device.gpuDrivenDraws();
    if (!gpu) return;
    // Read back only for someone who records: outside the timing, but not free.
    if (!view_.decisions) return;
    first_phase_.assign(bounds_.size(), 0);
    passed_.assign(bounds_.size(), 0);
    gpu->readResults(first_phase_, passed_);
    const bool boxes = options_.test == GpuTest::BoxRaster;
    // With nothing drawn in phase 1 the pyramid held only the far plane and hid nothing: said as
    // the read-back `hzb` says it, which builds none then.
    const bool empty_pyramid = !boxes && std::none_of(first_phase_.begin(), first_phase_.end(),
                                                      [](uint8_t drew) { return drew != 0; });
    const DepthPyramid* pyramid = boxes || empty_pyramid ? nullptr : device.depthPyramid();
    for (size_t u = 0; u < bounds_.size(); ++u) {
        Decision why;
        if (forced_[u]) {
            why = decisionOf(DecisionKind::DrawnNearPlane);
            why.phase = 1;
        } else if (first_phase_[u]) {
            why = decisionOf(boxes ? DecisionKind::DrawnOnBoxRaster : DecisionKind::DrawnOnPyramid);
            why.phase = 1;
        } else {
            why = decisionOf(
                passed_[u]
                    ? (boxes ? DecisionKind::DrawnOnBoxRaster : DecisionKind::DrawnOnPyramid)
                    : (boxes ? DecisionKind::CulledOnBoxRaster : DecisionKind::CulledOnPyramid));
            why.phase = 2;
            if (empty_pyramid) why.flags |= kDecisionNoPyramid;
            if (pyramid) {
                const uint32_t level = pyramid->levelOf(bounds_[u], options_.shape);
                why.level =
                    level < Decision::kNoLevel ? static_cast<uint8_t>(level) : Decision::kNoLevel;
            }
        }
        if (tags_[u].subject == QueryTag::Subject::NodeObjects) why.flags |= kDecisionNodeUnit;
        view_.decisions->add(tags_[u], why);
    }
}

}  // namespace occsim
