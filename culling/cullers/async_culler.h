// Per-object asynchronous occlusion queries: the "Simple Pseudo-code" of the PURE engine's
// occlusion-culling notes, after the ARB_occlusion_query
// specification's advice: "visible objects should be checked every N frames (where, say, N=5)
// to see if they have become occluded, while objects that were occluded last frame must be
// rechecked again in the current frame".
//
// The tree is used for frustum culling only; every object in the frustum is decided on its own,
// with one query on its own box, and no result is ever waited for:
//   - an object whose last result said occluded is queried again every frame and not drawn;
//   - an object whose last result said visible is drawn, and queried again every
//     `retest_interval_frames` frames (counted from the frame of its last query);
//   - an object never tested, or whose query is still pending and which was last visible, is
//     drawn;
//   - results are used when they arrive: ready results are collected (isQueryReady, in issue
//     order) at the start of each frame, after each node of the traversal and at the end of the
//     frame; an object in the frustum whose result arrives visible after it was passed over is
//     drawn then.
// So an object that turns visible behind an occluder is missing from every frame until its
// query's result arrives: this culler is NOT conservative, and its error is real.
//
// Beyond the pseudo-code:
//   - An object whose box the near plane may cut is drawn and not queried (a clipped query could
//     report zero samples for a visible box).
//   - An object that was outside the frustum in the previous frame counts as never tested: its
//     last result was measured from another view and says nothing about this one.
//   - At most one query per object is in flight; query ids live across frames and every one is
//     collected eventually, so the number of pending queries never exceeds the object count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {

// The per-object asynchronous scheme of the PURE engine notes ("Simple Pseudo-code"), with the
// re-test rule of the ARB_occlusion_query specification.
struct AsyncOptions {
    // N: a visible object is queried again this many frames after its last query. 1 = every frame.
    uint32_t retest_interval_frames = 5;
};

class AsyncCuller final : public Culler {
  public:
    explicit AsyncCuller(const AsyncOptions& options = {});
    void reset(const BspTree& tree) override;
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

    const AsyncOptions& options() const { return options_; }
    uint32_t pendingQueries() const { return pending_count_; }

  private:
    enum class Status : uint8_t { Untested, Visible, Occluded };
    // Stamps count calls of cullAndRender (0 = never), so "the previous frame" is the previous
    // call even if a caller repeats a frame index; query scheduling uses the frame index.
    struct ObjectState {
        uint64_t in_frustum = 0;    // stamp of the last frame it was in the frustum
        uint64_t drawn = 0;         // stamp of the last frame it was drawn
        uint64_t next_query = 0;    // first frame index in which it is queried again
        uint64_t query_frame = 0;   // the frame index its pending query was issued in
        uint64_t streak_start = 0;  // the frame index it last entered the frustum
        // The issue frame and samples of the answer `status` rests on (for decision logs).
        uint64_t answered_frame = 0;
        uint32_t answered_samples = 0;
        QueryId query = 0;
        bool pending = false;
        Status status = Status::Untested;
    };

    void decide(uint32_t object, const BspTree& tree, const CullFrame& frame, RenderDevice& device);
    void collectReadyResults(RenderDevice& device);
    // Draws the object unless it was drawn this frame, recording `why` when it does.
    void draw(uint32_t object, RenderDevice& device, const Decision& why);
    Decision answered(const ObjectState& s) const;

    AsyncOptions options_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
    std::vector<ObjectState> state_;
    // Objects with a query in flight, in issue order: a ring of capacity objectCount (one query
    // per object at most), so it never allocates after reset().
    std::vector<uint32_t> pending_;
    uint32_t pending_head_ = 0;
    uint32_t pending_count_ = 0;
    std::vector<NodeVisit> stack_;
    uint64_t frame_ = 0;  // the frame index being rendered
    uint64_t pass_ = 0;   // the stamp of the frame being rendered
};

}  // namespace occsim
