// A bird's-eye picture of one frame's culling decisions, like the classification figures of the
// CHC chapter (Bittner & Wimmer): the scene from above with rendered objects bright, the BSP
// nodes outlined in the colour of what the culler did with them, the camera and its view wedge.
//
// Contract
// - classifyNodes() gives one NodeClass per BSP node from the tree as the culler saw it, the
//   frame's view and a TracingDevice trace of that frame (see the enum for the rules). A query
//   counts for the nodes it was tagged with (QueryTag, occsim/culling/contract/render_device.h): a
//   multiquery for each of its nodes; a query on a node's own objects only when it found them
//   visible or is pending; a per-object query for no node.
// - renderBirdsEye() returns width * height * 4 bytes of RGBA8, row 0 at the bottom (for
//   encodePngBottomUp()). Orthographic top view: x to the right, -z up, uniform scale fitted to
//   the object boxes and the eye with a margin. Pure CPU drawing; deterministic.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <string>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/devices/tracing_device.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "sim/output/raster_canvas.h"

namespace occsim {

enum class NodeClass : uint8_t {
    Empty,              // no objects in the subtree (empty bounds); not drawn
    FrustumCulled,      // bounds outside the view frustum (classify() says Outside)
    OcclusionCulled,    // its bounds were queried and the fetched result was 0
    DrawnAfterQuery,    // queried, result > 0 (or its objects drawn under the query's condition),
                        // and objects drawn in it or below it
    DrawnWithoutQuery,  // own objects drawn without a fetched query (not queried, or pending)
    NotReached,         // inside the frustum, below an occlusion-culled node: never visited
    Passed,             // visited, nothing of its own drawn (e.g. an inner node, a visible query
                        // whose objects all failed the per-object frustum test)
    // In a frame without a single query (hzb's depth pyramid, masked's software buffer, the
    // oracle): inside the frustum, objects below it and none of them drawn, the topmost such
    // node. What culled it is the culler's own test; nodes below it are NotReached.
    CulledWithoutQuery,
};
constexpr int kNodeClassCount = 8;

const char* nodeClassName(NodeClass c);
Rgb nodeClassColour(NodeClass c);

// The other colours of the picture, for tests and legends.
constexpr Rgb kBirdsEyeBackground{18, 20, 28};
constexpr Rgb kDrawnObjectColour{255, 214, 40};  // yellow, as in the CHC figure
constexpr Rgb kHiddenObjectColour{96, 98, 104};  // grey: not drawn this frame
constexpr Rgb kCameraColour{255, 255, 255};
constexpr Rgb kWedgeColour{235, 235, 235};

std::vector<NodeClass> classifyNodes(const BspTree& tree, const CullView& view,
                                     const FrameTrace& trace);

struct BirdsEyeInput {
    const BspTree* tree = nullptr;
    std::span<const Aabb> object_boxes;       // world boxes, one per object
    std::span<const uint32_t> drawn_objects;  // objects drawn this frame (the trace's)
    std::span<const NodeClass> node_classes;  // classifyNodes(), one per node
    CullView view;                            // eye and frustum
    glm::vec3 forward{0.0f, 0.0f, -1.0f};     // camera viewing direction
    float fov_y_rad = 1.0f;
    float aspect = 1.0f;  // viewport width / height
    float near_m = 0.1f, far_m = 1000.0f;
    std::string title;        // printed at the top, e.g. "FRAME 20 CHC"
    bool draw_legend = true;  // off in tests that look for class colours
};

// A picture size whose aspect follows the fitted region (clamped so the legend has room), with
// the longer side `long_side` pixels.
struct PictureSize {
    uint32_t width, height;
};
PictureSize birdsEyeSize(const BirdsEyeInput& input, uint32_t long_side);

std::vector<uint8_t> renderBirdsEye(const BirdsEyeInput& input, uint32_t width, uint32_t height);

}  // namespace occsim
