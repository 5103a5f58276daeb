// The per-object asynchronous scheme of the PURE engine's occlusion-culling notes ("Simple
// Pseudo-code"), with the re-test rule of the ARB_occlusion_query specification. See
// async_culler.h for the rules.
#include "culling/cullers/async_culler.h"

#include "occsim/culling/declaration/culler_row.h"
#include "occsim/culling/declaration/option_table.h"
namespace occsim {

AsyncCuller::AsyncCuller(const AsyncOptions& options) : options_(options) {}

void AsyncCuller::reset(const BspTree& tree) {
    state_.assign(tree.objectCount(), ObjectState{});
    pending_.assign(tree.objectCount(), 0);
    pending_head_ = 0;
    pending_count_ = 0;
    pass_ = 0;
}

void AsyncCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    if (state_.size() != tree.objectCount()) reset(tree);
    frame_ = frame.frame_index;
    view_ = prepareView(frame);
    ++pass_;
    // Whatever arrived since the last frame decides this frame.
    collectReadyResults(device);
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum,
                               [&](uint32_t o) { decide(o, tree, frame, device); });
        collectReadyResults(device);
        return true;
    });
    collectReadyResults(device);
}

void AsyncCuller::decide(uint32_t object, const BspTree& tree, const CullFrame& frame,
                         RenderDevice& device) {
    ObjectState& s = state_[object];
    if (s.in_frustum != pass_ - 1) {
        // Back in the frustum: what was measured from an earlier view says nothing about this one.
        s.status = Status::Untested;
        s.next_query = 0;
        s.streak_start = frame_;
    }
    s.in_frustum = pass_;

    const Aabb& box = tree.objectBox(object);
    if (nearPlaneTouchesBox(box, frame.view.eye, frame.view.near_radius)) {
        draw(object, device, decisionOf(DecisionKind::DrawnNearPlane));
        return;
    }
    if (!s.pending && frame_ >= s.next_query) {
        s.query = device.issueQuery(box, QueryTag::object(object));
        s.pending = true;
        s.query_frame = frame_;
        pending_[(pending_head_ + pending_count_) % pending_.size()] = object;
        ++pending_count_;
        collectReadyResults(device);  // with no latency the answer is already there
    }
    switch (s.status) {
        case Status::Occluded:  // a later answer this frame may still draw it
            recordDecision(view_.decisions, QueryTag::object(object), answered(s));
            break;
        case Status::Visible:
            draw(object, device, answered(s));
            break;
        case Status::Untested:
            draw(object, device,
                 s.pending ? inFlightDecision(s.query_frame)
                           : decisionOf(DecisionKind::DrawnNoTest));
            break;
    }
}

Decision AsyncCuller::answered(const ObjectState& s) const {
    Decision d;
    d.kind = s.status == Status::Visible ? DecisionKind::DrawnOnQuery : DecisionKind::CulledOnQuery;
    d.query_frame = static_cast<uint32_t>(s.answered_frame);
    d.samples = s.answered_samples;
    d.next_query_frame = static_cast<uint32_t>(s.next_query);
    return d;
}

void AsyncCuller::collectReadyResults(RenderDevice& device) {
    // Results become ready in issue order: stop at the first that is not.
    while (pending_count_ > 0) {
        const uint32_t object = pending_[pending_head_];
        ObjectState& s = state_[object];
        if (!device.isQueryReady(s.query)) break;
        pending_head_ = static_cast<uint32_t>((pending_head_ + 1) % pending_.size());
        --pending_count_;
        const QueryAnswer answer = device.takeAnswer(s.query);
        const bool visible = answer.visible;
        s.pending = false;
        if (s.query_frame < s.streak_start) {
            s.next_query = 0;  // asked before the object left the frustum: ask again
            continue;
        }
        s.answered_frame = s.query_frame;
        s.answered_samples =
            answer.samples > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(answer.samples);
        if (visible) {
            s.status = Status::Visible;
            s.next_query = s.query_frame + options_.retest_interval_frames;
            // Passed over earlier in this frame while its answer was on the way: draw it now.
            if (s.in_frustum == pass_) draw(object, device, answered(s));
        } else {
            s.status = Status::Occluded;
            s.next_query = s.query_frame + 1;
        }
    }
}

void AsyncCuller::draw(uint32_t object, RenderDevice& device, const Decision& why) {
    ObjectState& s = state_[object];
    if (s.drawn == pass_) return;
    s.drawn = pass_;
    recordDecision(view_.decisions, QueryTag::object(object), why);
    device.drawObject(object);
}

// --- Registration -------------------------------------------------------------------------------

namespace {

const OptionTable<AsyncOptions>& asyncOptionTable() {
    static const OptionTable<AsyncOptions> table = {
        integerOption(OCCSIM_OPTION_MEMBER(AsyncOptions, retest_interval_frames), "frames", 1,
                      1000000,
                      "N: a visible object is queried again this many frames after its last "
                      "query; 1 = every frame"),
    };
    return table;
}

}  // namespace

CullerRow asyncRegistration() {
    CullerRow t;
    t.name = "async";
    t.summary = "one asynchronous query per object (not conservative)";
    t.conservative = false;
    t.issues_queries = true;
    t.options = asyncOptionTable().descriptor(AsyncOptions{});
    t.factory = [](const CullerContext& c) -> std::unique_ptr<Culler> {
        return std::make_unique<AsyncCuller>(asyncOptionTable().read(c.options));
    };
    return t;
}

}  // namespace occsim
