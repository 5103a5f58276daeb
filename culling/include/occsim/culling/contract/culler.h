// The culler interface: one frame's visibility decisions over a BspTree, carried out through a
// RenderDevice. What each algorithm is (conservative, query-based, oracle) is stated by its
// registration (occsim/culling/declaration/culler_row.h). Implementations keep their own
// per-node state (sized by reset()), use simulation time (never wall-clock time) for every
// decision, and are deterministic given the device's answers.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "occsim/culling/contract/decision_log.h"
#include "occsim/culling/contract/render_device.h"
#include "occsim/culling/geometry/frustum.h"

namespace occsim {

// The tree a culler reads (tree/bsp_tree.h). Only named here: the contract does not depend on the
// tree's layout, and the tree's traversal helpers (tree/traversal.h) build on this contract.
class BspTree;

// Which of a frame's views a CullView is (docs/views.md). A culler culls each view with its own
// state: the host gives every view a culler instance of its own, so a culler needs the kind only
// to say what its decisions were for, or to treat a view apart.
enum class ViewKind : uint8_t {
    Camera,   // the camera's view (one pass for a single eye, or for a frustum around both)
    Light,    // a directional light's shadow view: orthographic, its eye far behind (below)
    LeftEye,  // one eye of a stereo pair culled on its own
    RightEye,
};

struct CullView {
    ViewKind kind = ViewKind::Camera;
    // The eye. An orthographic view (a light's) has none: its eye stands far behind the near
    // plane along the view's direction (makeLightCullView, sim/run/frame_view.h), so that the
    // front-to-back orders and distances the cullers take from an eye follow that direction.
    glm::vec3 eye{0.0f};
    Frustum frustum{};
    float near_radius = 0.0f;  // eye to a near-plane corner; see nearPlaneTouchesBox()
    // The frustum's OpenGL-convention view-projection (clip z from -w at the near plane to w at
    // the far one), in the culling frame: what a culler that projects boxes or triangles itself
    // (a software depth buffer) needs. Identity when the caller gives no camera.
    glm::mat4 view_projection{1.0f};
    // The viewport in pixels, the size a device's depth buffer has. 0 when unknown.
    uint32_t viewport_width = 0;
    uint32_t viewport_height = 0;
};

// A CullView as the cullers read it during a frame: the frustum as its plane table, built once
// when the culler begins the frame (prepareView), so that the frame's node and object tests only
// run the kernel. Built by the culler rather than carried in CullView, so whoever fills a CullView
// (the simulation, a test moving its planes) cannot leave a stale table behind.
struct PreparedView {
    glm::vec3 eye{0.0f};
    FrustumPlanes frustum{};
    float near_radius = 0.0f;
    // The frame's decision log (CullFrame::decisions), or null: the traversal helpers
    // (tree/traversal.h) record the frustum's decisions in it.
    DecisionLog* decisions = nullptr;
};

inline PreparedView prepareView(const CullView& view) {
    return PreparedView{view.eye, planeTableOf(view.frustum), view.near_radius, nullptr};
}

// One mesh of CullMeshes' flat arrays: its triangles are indices[first_index, first_index +
// index_count), three per triangle, each relative to first_vertex in positions.
struct MeshRange {
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    uint32_t first_vertex = 0;
    uint32_t vertex_count = 0;
};

// The scene's triangles, for a culler that rasterises them itself (a software depth buffer; it
// asks for them with CullerRow::needs_meshes,
// occsim/culling/declaration/culler_row.h). The arrays are built once by the simulation and
// stay valid for the whole run; only object_to_culling changes per frame. Empty (every span) for a
// culler that did not ask.
struct CullMeshes {
    std::span<const glm::vec3> positions;   // every mesh's vertices, object-local, metres
    std::span<const uint32_t> indices;      // triangle lists, counter-clockwise front faces
    std::span<const MeshRange> meshes;      // per mesh, its part of positions and indices
    std::span<const uint32_t> object_mesh;  // per object, an index into meshes
    // Per object, this frame: object-local to the culling frame (the frame of the object boxes,
    // relative to the scene's culling origin), composed in double and then rounded to float, so
    // that a scene far from the world origin keeps its precision.
    std::span<const glm::mat4> object_to_culling;
    // Per object, whether a software depth buffer may rasterise it as an occluder:
    // kOccluderBySize (when large enough on screen), kOccluderAlways, kOccluderNever. Empty:
    // every object by size.
    std::span<const uint8_t> object_occluder;
    // Per object, a mesh (into meshes) to rasterise in its place as an occluder: one inscribed
    // in its own, with fewer triangles, that covers no pixel the object does not and lies behind
    // it, seen from any eye outside the object's box; kNoOccluderMesh where it has none. Empty:
    // none has one.
    std::span<const uint32_t> object_occluder_mesh;

    bool empty() const { return object_mesh.empty(); }
};
inline constexpr uint8_t kOccluderBySize = 0, kOccluderAlways = 1, kOccluderNever = 2;
inline constexpr uint32_t kNoOccluderMesh = 0xffffffffu;

struct CullFrame {
    uint64_t frame_index = 0;
    double time_s = 0.0;  // simulation time: frame_index * dt
    CullView view;
    // Per object, 1 when ground truth saw at least one of its pixels this frame. Filled only for
    // oracles (CullerRow::oracle, occsim/culling/declaration/culler_row.h); empty
    // otherwise.
    std::span<const uint8_t> ground_truth_visible;
    // Per object, its triangle count. The culling layer knows no meshes, so the simulation passes
    // a view of a table it builds once (per frame, beside the view, rather than through reset():
    // no culler that ignores it has to change). Empty when unknown; a culler weighing draw costs
    // (StatisticalOptions::cost_model) then leaves its cost model off.
    std::span<const uint32_t> object_triangles;
    // The meshes and this frame's object transforms: filled only for cullers whose traits ask
    // (CullerRow::needs_meshes), so that no other culler pays for the transforms.
    CullMeshes meshes;
    // Where the culler may say why it drew or left out each object (decision_log.h): null when
    // nobody records, which is every frame but those of `occsim run|bench|regress --record
    // objects`. The log is cleared by the host before the frame.
    DecisionLog* decisions = nullptr;
};

// The frame's view with its plane table and the frame's decision log: what a culler that
// records its reasons prepares (the traversal helpers then record the frustum's decisions).
inline PreparedView prepareView(const CullFrame& frame) {
    PreparedView view = prepareView(frame.view);
    view.decisions = frame.decisions;
    return view;
}

class Culler {
  public:
    virtual ~Culler() = default;
    // Called once the tree is built, before the first frame; clears all per-node state.
    virtual void reset(const BspTree& tree) = 0;
    virtual void cullAndRender(const BspTree& tree, const CullFrame& frame,
                               RenderDevice& device) = 0;
    // Called once the frame's timing has ended and the device has resolved it, before error is
    // measured: a culler whose decisions were taken on the device (GPU-driven draws,
    // gpu_driven_draws.h) reads them back here, to record its reasons in the frame's decision
    // log. Nothing it does here is timed.
    virtual void afterFrame(RenderDevice& /*device*/) {}
};

}  // namespace occsim
