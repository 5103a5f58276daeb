// A coarse, conservative software depth buffer in the manner of masked software occlusion culling
// (Hasselgren, Andersson & Akenine-Möller, "Masked Software Occlusion Culling", HPG 2016; the
// rules and every deviation from the paper: docs/masked.md). Occluder triangles are rasterised
// into it and boxes are tested against it; it never says a box is hidden when some pixel of
// what the box holds could be seen in front of the occluders it was given.
//
// Conventions:
// - Input is in the culling frame (CullView: the OpenGL-convention view-projection with clip z
//   from -w to w, the eye, the viewport in pixels). Depth is stored as 1/w (w: the view depth in
//   metres), so larger is nearer and 0 is infinitely far; "farther" comparisons are on 1/w.
// - The buffer has one pixel per k×k viewport pixels, k the smallest integer that makes it at
//   most max_width pixels wide (k = 1: one per viewport pixel). A buffer pixel counts as covered
//   by a triangle only when the triangle covers the centre of every viewport pixel in it, with
//   room to spare (kCoverageMarginPx, plus the projection's rounding): never more than the
//   triangle covers in a real rasteriser's image.
// - Tiles of 32×8 buffer pixels, each cut into depth cells (MaskedLayout: 8×4 by default, the
//   subtile of Intel's reference implementation, eight per tile as in its AVX2 build; its SSE
//   build's 32×4 tiles hold the same 8×4 subtiles). Per tile a 256-bit coverage mask; per cell
//   two depths: z0, which bounds every pixel of the cell (the nearest depth anything there can
//   hide behind is at least as near as z0), and z1, which bounds the cell's pixels whose mask bit
//   is set (z1 > z0). A triangle's depth in a cell is the farthest value of its plane over what it
//   covers there, never farther than its farthest vertex. It updates the cell by the paper's rule
//   (MaskedMerge::Quick): a triangle not nearer than z0 changes nothing; the working layer is
//   discarded (its pixels fall back to z0) when the triangle covers the whole cell or when the
//   working layer lies nearer to z0 than to the triangle (2·z1 − (z + z0) < 0), else merged
//   (mask |= coverage, z1 = the farther of z1 and the triangle); a full mask becomes the new z0.
//   MaskedMerge::Accurate keeps, of merging, discarding and dropping the triangle, the one that
//   leaves the nearest reference depth, then (where boxes are tested against the working layer
//   too) the nearest bounds in sum over the cell's pixels. Every step keeps: a pixel's true
//   occluder depth is at least as near as its bound.
// - A box is hidden only when its nearest depth is strictly farther than z0 of every cell its
//   projection may touch (its projected rectangle rounded outward and grown by the margin), as in
//   the paper, where only the reference layer culls; MaskedLayout::test_working_layer also lets
//   z1 hide it in a cell where every pixel it touches is in the mask. A box whose nearest point
//   is at or behind the eye, or that is not finite, is visible. Ties are visible.
// Triangles are clipped against a plane a little beyond the near plane (what a real rasteriser
// clips away is never an occluder here), both faces occlude (the renderer does not cull back
// faces), and a degenerate or non-finite triangle is skipped. Skipping an occluder is always safe.
//
// Nothing is allocated per frame once the viewport's size has been seen.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <string>
#include <vector>

#include "occsim/culling/geometry/aabb.h"

namespace occsim {

// The kernels that compute coverage: the plain C++ path, or AVX2 intrinsics beside it. Both give
// the same buffer, bit for bit (the tests run both); Avx2 is used only where the CPU has it.
enum class MaskedKernel : uint8_t { Plain, Avx2 };
// Whether this build and this CPU can run `kernel` (Plain: always).
bool maskedKernelAvailable(MaskedKernel kernel);

// How a cell takes a triangle (see the conventions above).
enum class MaskedMerge : uint8_t { Quick, Accurate };

// The buffer's depth resolution and rules. A cell is cell_width × cell_height buffer pixels,
// cell_width one of 8, 16, 32 and cell_height one of 4, 8 (validMaskedLayout).
struct MaskedLayout {
    uint32_t cell_width = 8;
    uint32_t cell_height = 4;
    MaskedMerge merge = MaskedMerge::Quick;
    bool test_working_layer = false;
};
// Empty when `layout` is one the buffer can keep, else what is wrong with it (one line).
std::string validMaskedLayout(const MaskedLayout& layout);

// What one frame of the buffer did: triangles given, rasterised (after clipping and skipping),
// tile updates, and boxes tested and found hidden.
struct MaskedBufferStats {
    uint64_t triangles = 0;
    uint64_t triangles_rasterised = 0;
    uint64_t tile_updates = 0;
    uint64_t boxes_tested = 0;
    uint64_t boxes_hidden = 0;
};

// Per edge of each triangle (edge i of triangle t, from its vertex i to vertex i + 1, at 3t + i):
// the index of the vertex opposite that edge in the one other triangle that shares it (either
// way round), or kNoNeighbour when no other triangle or more than one shares it. Built once per
// mesh.
inline constexpr uint32_t kNoNeighbour = 0xffffffffu;
std::vector<uint32_t> edgeNeighbours(std::span<const uint32_t> indices);
// `indices` with every vertex replaced by the first one at exactly the same position, so that
// triangles meeting at an edge share it by index (meshes repeat a vertex where its normal or
// texture coordinates differ, and recorded frames repeat them between batches' parts): what
// edgeNeighbours needs to find the edges a rasteriser leaves no gap along. An index past the end
// stays as it is.
std::vector<uint32_t> weldedIndices(std::span<const glm::vec3> positions,
                                    std::span<const uint32_t> indices);
std::vector<uint32_t> weldedIndices(std::span<const glm::dvec4> positions,
                                    std::span<const uint32_t> indices);

class MaskedDepthBuffer {
  public:
    static constexpr uint32_t kTileWidth = 32;  // buffer pixels
    static constexpr uint32_t kTileHeight = 8;
    // How far (viewport pixels) a sample point must lie inside every edge of an occluder
    // triangle: a rasteriser snaps vertices to a 1/256-pixel grid (8 sub-pixel bits, the
    // minimum OpenGL implementations use), which moves an edge by less than 1/128 of a pixel.
    static constexpr double kCoverageMarginPx = 1.0 / 16.0;
    // How far (viewport pixels) a box's projected rectangle is grown on every side: the same
    // snapping, for the occludee's own triangles.
    static constexpr double kBoxMarginPx = 1.0 / 16.0;
    // Relative depth margin: an occluder's stored 1/w is made this much farther, a box's nearest
    // 1/w this much nearer (a float depth buffer rounds by about 6·10^-8).
    static constexpr double kDepthMargin = 1e-5;

    static constexpr uint32_t kMaxCellsPerTile = 8;  // 8×4 cells in a 32×8 tile

    // std::invalid_argument when `layout` is not valid (validMaskedLayout).
    explicit MaskedDepthBuffer(MaskedKernel kernel = MaskedKernel::Plain,
                               const MaskedLayout& layout = {});

    // Starts a frame: clears the buffer. `view_projection` in the culling frame (OpenGL clip
    // convention), `eye` the camera there, the viewport in pixels, `max_width` the buffer's
    // widest (0: the viewport's width, one buffer pixel per viewport pixel). A camera whose near
    // plane cannot be read from the matrix (not a perspective projection) or an empty viewport
    // leave the buffer off: nothing is rasterised, every box is visible.
    void beginFrame(const glm::mat4& view_projection, glm::vec3 eye, uint32_t viewport_width,
                    uint32_t viewport_height, uint32_t max_width);

    // Rasterises the triangles of one mesh as occluders, posed by `object_to_culling` (object
    // space to the culling frame). `indices` are relative to `positions` (three per triangle);
    // an index past the end skips its triangle. `neighbours` (edgeNeighbours(indices), or empty)
    // lets an edge shared with a triangle on its other side on screen go without the coverage
    // margin: a rasteriser covers every pixel centre near such an edge with one of the two. A
    // closed mesh (every edge shared) has its back faces skipped: its front faces lie nearer.
    void rasteriseMesh(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                       const glm::mat4& object_to_culling,
                       std::span<const uint32_t> neighbours = {});
    // One triangle, in the culling frame (for tests).
    void rasteriseTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c);

    // Starts a frame of an orthographic view (a light's: CullView::kind Light), `view_projection`
    // an OpenGL-convention orthographic projection (clip w constant, z from -1 at the near plane
    // to 1 at the far one after the divide). 1/w is not a depth there, so each point is stored at
    // the w of a stand-in, w' = s / (2 - z) with z its depth after the divide and s =
    // min(1, 1 / the metres per unit of z): the same screen point (x·w'/w' is x), 1/w' affine in
    // screen space as the view's depth is, nearer larger, and a metre's rounding moving w' by no
    // more than a metre, as the margins above take it. A triangle reaching past the far plane
    // (z >= 1) is not an occluder; a box's corner past it is taken at z = 1.5 (nearer: safe).
    // A matrix that is not orthographic or an empty viewport leave the buffer off.
    void beginOrthographicFrame(const glm::mat4& view_projection, uint32_t viewport_width,
                                uint32_t viewport_height, uint32_t max_width);

    // Starts a frame whose triangles come in clip coordinates (a recorded frame, such as those of
    // Intel's frame recorder): no camera; `near_w` is the w of the near plane. The inputs are
    // taken as exact: no rounding bound is added to the margins.
    void beginClipFrame(uint32_t viewport_width, uint32_t viewport_height, double near_w,
                        uint32_t max_width);
    // Occluder triangles in clip coordinates: x, y and w as OpenGL's (x/w and y/w from -1 to 1
    // across the viewport, w the view depth); z is not read. `indices` three per triangle into
    // `clip`; `neighbours` as for rasteriseMesh.
    void rasteriseClipMesh(std::span<const glm::dvec4> clip, std::span<const uint32_t> indices,
                           std::span<const uint32_t> neighbours = {});

    // False only when every pixel `box` (culling frame) may show in lies behind the occluders.
    bool testBox(const Aabb& box);
    // The same for a rectangle of the viewport whose content lies nowhere nearer than `w_min`:
    // x from x_lo to x_hi, y from y_lo to y_hi in viewport pixels (pixel (j, i) has its centre at
    // (j + 0.5, i + 0.5), row 0 at the bottom). A rectangle reaching within half the near
    // distance of the eye is visible.
    bool testRect(double x_lo, double x_hi, double y_lo, double y_hi, double w_min);

    // The larger side of the box's projected rectangle as a fraction of the viewport's height;
    // +inf when its nearest point is at or behind the eye (or the buffer is off), 0 when empty.
    double screenExtent(const Aabb& box) const;

    bool active() const { return active_; }
    uint32_t width() const { return width_; }  // buffer pixels
    uint32_t height() const { return height_; }
    uint32_t pixelSize() const { return k_; }  // viewport pixels per buffer pixel, each way
    MaskedKernel kernel() const { return kernel_; }
    const MaskedLayout& layout() const { return layout_; }
    const MaskedBufferStats& stats() const { return stats_; }

    // The depth (1/w) below which a box at buffer pixel (x, y) is hidden: the pixel's bound; 0
    // where nothing is known. For tests and pictures.
    float pixelBound(uint32_t x, uint32_t y) const;

    // Cell c of a tile covers columns (c % cellsAcross) · cell_width on and rows
    // (c / cellsAcross) · cell_height on; cells past kMaxCellsPerTile's count are unused (0).
    struct Tile {
        uint32_t mask[kTileHeight];  // bit x of row y: buffer pixel (x0 + x, y0 + y) is in layer 1
        float z0[kMaxCellsPerTile];  // bounds every pixel of the cell (1/w; 0: unknown)
        float z1[kMaxCellsPerTile];  // bounds the cell's pixels in the mask (> z0 while set)
    };
    std::span<const Tile> tiles() const { return tiles_; }
    uint32_t tilesAcross() const { return tiles_x_; }

  private:
    // `opposite[i]`: the clip position of the vertex opposite edge i (from vertex i to i + 1) in
    // the triangle sharing it, or nullptr.
    void rasteriseClipTriangle(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c,
                               double position_error, const glm::dvec4* const* opposite = nullptr);
    void rasteriseScreenTriangle(const glm::dvec4* v, double position_error,
                                 const glm::dvec4* const* opposite);
    // The box test from the projected rectangle on; `error` (metres) bounds the rounding of
    // its corners.
    bool testProjected(double x_lo, double x_hi, double y_lo, double y_hi, double w_min,
                       double error);
    // Works out k and the tiles for the viewport; false when it is empty.
    bool layOut(uint32_t viewport_width, uint32_t viewport_height, uint32_t max_width);
    // >0: skip triangles clockwise on screen, <0: counter-clockwise ones, 0: none (this mesh).
    int skip_facing_ = 0;
    // The cell's coverage (`coverage` holds bits of this cell only) merged at `depth`.
    void updateCell(uint32_t tile, uint32_t cell, const uint32_t (&coverage)[kTileHeight],
                    float depth);
    // Whether `mask` sets every pixel of the cell (pixels past the buffer's edge count as set).
    bool cellFull(uint32_t tile, uint32_t cell, const uint32_t (&mask)[kTileHeight]) const;
    uint32_t cellIndex(uint32_t column, uint32_t row) const {  // within a tile
        return (row / layout_.cell_height) * cells_across_ + column / layout_.cell_width;
    }

    MaskedKernel kernel_;
    MaskedLayout layout_;
    uint32_t cells_across_ = 4, cells_down_ = 2;    // per tile
    uint32_t cell_columns_[kMaxCellsPerTile] = {};  // per cell column: its bits of a row
    bool active_ = false;
    glm::dmat4 view_projection_{1.0};  // the frame's, in double
    glm::dvec3 eye_{0.0};
    // An orthographic frame's s (beginOrthographicFrame); 0 in a perspective one.
    double ortho_scale_ = 0.0;
    // A point's clip coordinates as the buffer takes them: as they are in a perspective frame,
    // at the stand-in w' in an orthographic one (NaN past the far plane: not an occluder).
    glm::dvec4 bufferClip(const glm::dvec4& clip) const;
    double near_ = 0.0;         // the near plane's view depth (metres)
    double clip_w_ = 0.0;       // triangles are clipped to w >= clip_w_ (a little beyond near_)
    double frame_error_ = 0.0;  // metres: the rounding of the eye and the matrix
    double focal_px_ = 0.0;     // viewport pixels per unit of x/w or y/w, the larger
    uint32_t viewport_width_ = 0, viewport_height_ = 0;
    uint32_t k_ = 1;
    uint32_t width_ = 0, height_ = 0;
    uint32_t tiles_x_ = 0, tiles_y_ = 0;
    std::vector<Tile> tiles_;
    uint32_t right_outside_[kTileHeight] = {};  // pixels of the last tile column past the edge
    uint32_t top_outside_rows_ = 0;             // rows of the last tile row past the edge
    MaskedBufferStats stats_;
    std::vector<glm::dvec4> clip_scratch_;  // a mesh's vertices in clip coordinates
};

}  // namespace occsim
