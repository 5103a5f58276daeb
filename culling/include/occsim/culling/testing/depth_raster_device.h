// A RenderDevice whose answers depend on what was drawn before them: a coarse CPU depth raster,
// for testing culling logic where draw order matters (nearer drawn boxes hide farther ones). It
// knows no OpenGL and renders no triangles.
//
// The model, chosen so that it is self-consistent rather than photographic:
// - an object is a screen-aligned card: its box's projected bounding rectangle (rounded outwards
//   to whole cells), at one depth, the distance from the eye to the box (0 when the eye is inside);
// - drawObject() writes the card into the raster, keeping the smaller depth per cell;
// - a query on some boxes counts, per box, the cells of its card whose stored depth is >= the
//   box's depth (ties pass, like the GL device's GL_GEQUAL boxes), summed over the boxes;
// - a box with a corner at or behind the eye plane covers the whole screen.
// A box that contains another has a card containing the other's card and a depth no greater, so
// a query on a node's bounds passes whenever one of its objects would show. Ground truth draws
// every object in the frustum: an object is visible when it holds the smallest depth in at least
// one cell of its card. A culler that draws every such object leaves the same raster as ground
// truth, so "conservative" means the same here as with the GL device.
//
// Results become ready after a fixed number of later commands, like ScriptedQueryDevice.
//
// Conditional rendering (conditional_rendering.h) as a GPU evaluates it: a conditional draw
// executes (writes its card) iff its query passed a cell against the raster as it was when the
// query was issued, or unconditionally under NoWait while the answer is not ready. Executed draws
// join drawnObjects(), skipped ones skippedObjects(); both count as submitted draws.
// It offers the depth-pyramid capability (occsim/culling/contract/depth_pyramid.h) over its raster
// (software_depth_pyramid.h): a box's footprint is its card's cells, its nearest depth the
// card's; a sphere's footprint is its exact projected rectangle, its depth the distance from the
// eye to the sphere. Constructed with `with_pyramid` false it lacks the capability.
// It offers GPU-driven draws (occsim/culling/contract/gpu_driven_draws.h), both tests, over the
// same raster and the same rules: Pyramid through its own pyramid, BoxRaster as a query on the
// one box (a box passes when a cell of its card passes), each slot's visibility kept here.
// Drawn entries join drawnObjects() and the counters as the phases draw them (nothing to
// resolve); read_backs counts the query answers and pyramid flags handed to the culler.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/contract/depth_pyramid.h"
#include "occsim/culling/contract/gpu_driven_draws.h"
#include "occsim/culling/contract/render_device.h"
#include "occsim/culling/geometry/frustum.h"
#include "occsim/culling/testing/command_latency_queries.h"
#include "occsim/culling/testing/software_depth_pyramid.h"

namespace occsim {

class DepthRasterDevice final : public RenderDevice,
                                private ConditionalRendering,
                                private DepthPyramid,
                                private GpuDrivenDraws {
  public:
    DepthRasterDevice(uint32_t width, uint32_t height, uint32_t latency_commands = 0,
                      bool with_pyramid = true);

    // Starts a frame: the camera (OpenGL-convention view-projection and the eye) and every
    // object's box (copied into the device's own buffer, so a frame allocates nothing once it is
    // large enough). Clears the raster and the log.
    void beginFrame(const glm::mat4& view_projection, glm::vec3 eye,
                    std::span<const Aabb> object_boxes);

    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override;
    bool isQueryReady(QueryId id) override;
    QueryAnswer takeAnswer(QueryId id) override;
    ConditionalRendering* conditionalRendering() override { return this; }
    DepthPyramid* depthPyramid() override { return with_pyramid_ ? this : nullptr; }
    GpuDrivenDraws* gpuDrivenDraws() override { return this; }

    // The pyramid of the last build() this frame (empty before it).
    const SoftwareDepthPyramid& pyramid() const { return pyramid_; }

    // Per object, 1 when it is visible with every object in the frustum drawn (this frame's
    // camera and boxes; independent of what the culler drew).
    std::vector<uint8_t> groundTruth() const;
    // The objects drawn since beginFrame(), in order.
    const std::vector<uint32_t>& drawnObjects() const { return drawn_; }
    // Conditional draws since beginFrame() that the device skipped, in order.
    const std::vector<uint32_t>& skippedObjects() const { return skipped_; }
    // Queries issued since beginFrame(), in order, with what they were for.
    const std::vector<QueryTag>& queryLog() const { return query_log_; }
    uint32_t pendingQueries() const;

  private:
    struct Card {
        uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // cells [x0, x1) x [y0, y1); empty when x0 >= x1
        float depth = 0.0f;
    };
    Card cardOf(const Aabb& box) const;
    void rasterise(uint32_t object);
    void drawIf(QueryId id, std::span<const uint32_t> objects, ConditionWait wait) override;
    void release(QueryId id) override { queries_.release(id); }
    Card cardOfSphere(const Aabb& box) const;
    // DepthPyramid
    void build() override;
    uint32_t levelOf(const Aabb& box, PyramidBound shape) const override;
    void testBounds(std::span<const Aabb> boxes, PyramidBound shape,
                    std::span<uint8_t> visible) override;
    void testOnPyramid(std::span<const Aabb> boxes, PyramidBound shape, std::span<uint8_t> visible);
    // GpuDrivenDraws (depth_raster_gpu_draws.cpp)
    void resetVisibility() override;
    void drawFirstPhase(const GpuUnits& units) override;
    void drawSecondPhase(GpuTest test, PyramidBound shape) override;
    void readResults(std::span<uint8_t> first_phase, std::span<uint8_t> passed) override;
    bool offersBoxRaster() const override { return true; }
    // The cells of `box`'s card whose stored depth is >= the card's: what a query on it counts.
    uint64_t passingCells(const Aabb& box) const;

    uint32_t width_, height_;
    glm::mat4 view_projection_{1.0f};
    glm::vec3 eye_{0.0f};
    FrustumPlanes frustum_{};  // the plane table of this frame, built in beginFrame()
    std::vector<Aabb> boxes_;
    std::vector<float> depth_;  // width * height, +inf = nothing drawn
    CommandLatencyQueries queries_;
    std::vector<uint32_t> drawn_;
    std::vector<uint32_t> skipped_;
    std::vector<QueryTag> query_log_;
    bool with_pyramid_ = true;
    SoftwareDepthPyramid pyramid_;
    // GPU-driven draws: per slot, the frame its unit last passed (0: never); this frame's units,
    // and per unit whether phase 1 drew it and whether it passed; per entry, drawn in phase 1.
    std::vector<uint64_t> slot_passed_;
    uint64_t gpu_frame_ = 1;
    GpuUnits units_;
    std::vector<uint8_t> unit_first_phase_, unit_passed_, entry_drawn_, flags_;
};

}  // namespace occsim
