// Masked software occlusion culling on the CPU (Hasselgren, Andersson & Akenine-Möller, HPG 2016):
// a coarse software depth buffer (occsim/culling/raster/masked_depth_buffer.h) filled with the real
// triangles of chosen occluders, near to far, and tested with node and object boxes while the
// BSP tree is traversed front to back. No occlusion queries: the device only draws. How it
// works here and what differs from the paper: docs/masked.md.
#pragma once

#include <cstdint>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/raster/masked_depth_buffer.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {

struct MaskedOptions {
    // The software buffer's width at most (pixels): the viewport is divided by the smallest
    // whole number that makes it fit; 0: the viewport's own resolution.
    uint32_t width = 0;
    // A depth cell (two depths and the mask's pixels): 8×4 as in the reference implementation;
    // 32×8 is one cell per tile (this project's buffer before 2026-12-04).
    uint32_t cell_width = 8;
    uint32_t cell_height = 4;
    // The accurate merge instead of the paper's quick rule (masked_depth_buffer.h).
    bool accurate_merge = false;
    // Boxes tested against the working layer too where its mask holds them (the paper tests the
    // reference layer only).
    bool working_layer_test = false;
    // An object occludes when the larger side of its box's projection is at least this fraction
    // of the viewport's height.
    double occluder_size = 0.1;
    // How occluders are chosen. Off (the default, as engines do): an occluder pass before any box
    // is tested, over every object in the frustum that is large enough on screen, nearest first,
    // each skipped when the buffer already hides its box; the test pass then only tests and
    // draws. On: the drawn objects are the occluders, each rasterised right after it is drawn
    // (this project's masked before 2026-12-04).
    bool drawn_occluders = false;
    // Objects occlude with their inscribed occluder meshes (CullMeshes::object_occluder_mesh)
    // where they have one and the eye is outside their box; off: always with their own.
    bool simplified_occluders = true;
    // With drawn_occluders: last frame's drawn objects that qualify are rasterised first, before
    // the traversal (a depth pre-pass from coherence); the others as they are drawn.
    bool last_drawn_first = true;
    // Occluder triangles rasterised per frame at most; an object whose triangles no longer fit
    // is not an occluder this frame.
    uint32_t occluder_triangles = 200000;
    // The AVX2 kernels where the CPU has them (the same decisions as the plain path).
    bool simd = true;
};

class MaskedCuller final : public Culler {
  public:
    explicit MaskedCuller(const MaskedOptions& options = {});
    void reset(const BspTree& tree) override;
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

    // The buffer as the last frame left it (for tests and pictures).
    const MaskedDepthBuffer& buffer() const { return buffer_; }
    // Objects rasterised as occluders in the last frame.
    uint32_t occluders() const { return occluders_; }

  private:
    bool mayBeVisible(const Aabb& box, const CullView& view);
    void tryOccluder(const BspTree& tree, const CullMeshes& meshes, uint32_t object);
    // The occluder pass (drawn_occluders off): every large object in the frustum, nearest first.
    void rasteriseOccluders(const BspTree& tree, const CullFrame& frame);

    MaskedOptions options_;
    MaskedDepthBuffer buffer_;
    PreparedView view_;
    std::vector<NodeVisit> stack_;
    std::vector<uint32_t> drawn_last_, drawn_now_;  // in draw order (front to back)
    std::vector<uint64_t> rasterised_in_;           // per object: frame stamp it was tried in
    std::vector<uint64_t> occluder_in_;             // per object: frame stamp it was rasterised in
    struct Candidate {
        float distance2;  // from the eye to the object's box, squared
        uint32_t object;
    };
    std::vector<Candidate> candidates_;  // the occluder pass's, reused
    // Per mesh, built the first time it occludes: its indices welded by position
    // (weldedIndices), and their edges' neighbours (edgeNeighbours).
    std::vector<std::vector<uint32_t>> welded_;
    std::vector<std::vector<uint32_t>> neighbours_;
    std::vector<uint8_t> has_neighbours_;
    glm::vec3 view_eye_{0.0f};
    float view_near_radius_ = 0.0f;
    bool orthographic_view_ = false;  // a light's view
    glm::vec4 near_plane_{0.0f};      // the view's (Frustum's planes[4])
    uint64_t stamp_ = 0;
    uint64_t budget_ = 0;
    uint32_t occluders_ = 0;
};

}  // namespace occsim
