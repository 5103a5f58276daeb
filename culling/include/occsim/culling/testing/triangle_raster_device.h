// A RenderDevice that rasterises the objects' real triangles into an exact per-pixel depth buffer
// on the CPU: the reference a software depth buffer (occsim/culling/raster/masked_depth_buffer.h)
// is checked against. Written to be obviously right rather than fast: double precision throughout,
// one sample at each pixel centre, triangles clipped to the near and far planes (z = -w, z = w,
// OpenGL's clip convention), both faces drawn, depth as 1/w interpolated across the screen, and
// a sample exactly on an edge counted as covered (so the reference sees at least as much as any
// real rasteriser's image).
//
// drawObject() writes an object into the device's buffer (nearest 1/w kept); a query on boxes
// counts the pixel centres of their projected rectangles where the box's nearest point is at
// least as near as the buffer. groundTruth() renders every object into a buffer of its own: an
// object is visible when it holds the nearest depth (ties included) at some pixel centre.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/contract/render_device.h"
#include "occsim/culling/testing/command_latency_queries.h"

namespace occsim {

class TriangleRasterDevice final : public RenderDevice {
  public:
    TriangleRasterDevice(uint32_t width, uint32_t height, uint32_t latency_commands = 0);

    // Starts a frame: the camera (culling frame, OpenGL convention) and the meshes with this
    // frame's transforms (the spans must outlive the frame). Clears the buffer and the log. An
    // object without a mesh here is logged when drawn and writes nothing.
    void beginFrame(const glm::mat4& view_projection, const CullMeshes& meshes);

    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override;
    bool isQueryReady(QueryId id) override;
    QueryAnswer takeAnswer(QueryId id) override;

    // Per object, 1 when it holds the nearest depth at some pixel centre with every object
    // drawn. Also keeps that full render for boxHiddenInTruth().
    std::vector<uint8_t> groundTruth();
    // Whether the full render (groundTruth(), called first) hides `box` at every pixel centre of
    // its projected rectangle: what a full-resolution depth buffer culls.
    bool boxHiddenInTruth(const Aabb& box) const;
    const std::vector<uint32_t>& drawnObjects() const { return drawn_; }
    // 1/w per pixel of the device's own buffer (0: nothing drawn), row 0 at the bottom.
    const std::vector<double>& depth() const { return depth_; }

  private:
    template <class Fragment>
    void rasteriseObject(uint32_t object, Fragment&& fragment) const;
    uint64_t boxSamples(const Aabb& box, const std::vector<double>& depth) const;

    uint32_t width_, height_;
    glm::dmat4 view_projection_{1.0};
    CullMeshes meshes_;
    std::vector<double> depth_, truth_;
    CommandLatencyQueries queries_;
    std::vector<uint32_t> drawn_;
};

}  // namespace occsim
