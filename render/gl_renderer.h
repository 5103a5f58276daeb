// The OpenGL renderer: one framebuffer with colour (RGBA8), object ID (R32UI: object index + 1,
// 0 = background) and float depth, and with a light's shadow term (setShadow) a fourth buffer of
// shadow-map texels (R32UI); all meshes in one vertex and one index buffer, every object's
// model-view matrix in one per-instance buffer; one draw call per object, or one multi-draw of
// GPU-written commands (drawIndirect). A stereo view (ViewSetup::eye_separation_m) draws each
// object once per eye, the two eyes one above the other. Needs a current GlContext.
//
// Conventions: right-handed world, y up, metres. Rendering is camera-relative (object matrices
// are computed in double relative to the eye, then cast to float) with reverse-Z (clip control
// 0..1, depth cleared to 0, GL_GREATER) into a 32-bit float depth buffer, so precision holds far
// from the origin and over large near/far ratios. Occlusion-query boxes use GL_GEQUAL, so a box
// face coplanar with an occluder counts as visible (conservative).
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "occsim/culling/geometry/aabb.h"
#include "render/mesh_data.h"

namespace occsim {

struct ViewSetup {
    glm::dvec3 eye{0.0};         // world coordinates
    glm::dvec3 box_origin{0.0};  // query boxes are given relative to this point (the culling frame)
    glm::mat4 view_rotation{1.0f};  // world to view without translation
    glm::mat4 projection{1.0f};     // reverse-Z, see reverseZPerspective()
    // Eye to a near-plane corner (nearPlaneCornerDistance): the query boxes within it of the eye,
    // as drawn, are answered visible (queryBoxNearEye). 0: no guard (pictures, tests).
    float near_radius = 0.0f;
    // Stereo (docs/views.md): two eyes on the view's x axis this far apart, `eye` midway between
    // them, their axes parallel. Draws then go to each eye's half of a framebuffer twice an eye's
    // height (stereoEyeFirstRow), through `projection` shifted by half the separation
    // (GlRenderer::setEyes says which eyes); the model-view matrices stay relative to `eye`.
    // 0: one eye, the whole framebuffer.
    double eye_separation_m = 0.0;
};

// Where each eye of a stereo view lies in a framebuffer of `height` rows (twice an eye's): the
// first row of its run in a read-back (row 0 at the bottom). The left eye is the upper half, so a
// picture of the framebuffer shows it on top.
inline uint32_t stereoEyeFirstRow(int eye, uint32_t height) { return eye == 0 ? height / 2 : 0; }
// That eye's pixels of a read-back of such a framebuffer, `width` x `height` (its half, one run);
// empty for an empty read-back (a buffer the frame did not fill, such as no stray fragments).
template <class T>
std::span<T> stereoEyePixels(std::span<T> pixels, int eye, uint32_t width, uint32_t height) {
    if (pixels.empty()) return pixels;
    return pixels.subspan(size_t{stereoEyeFirstRow(eye, height)} * width,
                          size_t{width} * (height / 2));
}

// Which eyes of a stereo view the draws that follow go to (GlRenderer::setEyes).
enum class StereoEyes : uint8_t { Both, Left, Right };

// Perspective projection with reverse-Z for clip control GL_ZERO_TO_ONE: near maps to depth 1,
// far to depth 0.
glm::mat4 reverseZPerspective(float fov_y_radians, float aspect, float near_plane, float far_plane);

// How depth is stored. Reverse-Z into a float buffer (the default) keeps nearly uniform relative
// precision from the near plane to the far one; the conventional mapping (near to -1, far to 1,
// clip control GL_NEGATIVE_ONE_TO_ONE) into a 24-bit fixed-point buffer is what many engines
// still do, and is kept to show the depth-precision trap: with a near/far ratio of 10^6, nearby
// surfaces tie in depth and whichever is drawn first wins, so two renders of the same frame in
// different orders disagree.
enum class DepthConvention : uint8_t { ReverseFloat, Conventional24 };

// The projection matching a convention (reverseZPerspective or glm::perspective).
glm::mat4 perspectiveFor(DepthConvention depth, float fov_y_radians, float aspect, float near_plane,
                         float far_plane);

// An orthographic projection for a light's box in view space (x in [left, right], y in [bottom,
// top], the view looking down -z from `near` to `far` metres), in `depth`'s convention: reverse-Z
// maps near to 1 and far to 0, as reverseZPerspective does.
glm::mat4 orthographicFor(DepthConvention depth, float left, float right, float bottom, float top,
                          float near_plane, float far_plane);

// The shadow term of a camera pass (setShadow, docs/views.md): where to look up a light's shadow
// map and how. A fragment is in shadow when its depth from the light, after a normal offset of
// 1.5 texels and `depth_bias`, lies behind the map's texel it falls in.
struct ShadowLookup {
    uint32_t texture = 0;              // the light's depth texture (GlShadowMap::depthTexture)
    uint32_t size = 0;                 // texels a side
    glm::mat4 view_to_light{1.0f};     // camera view space to light clip (cameraToLightClip)
    glm::vec3 light_travel{0, -1, 0};  // the way the light travels, in camera view space
    float texel_m = 0.0f;              // a texel's width in metres
    float depth_bias = 0.0f;           // in the map's stored depth units
};

// The matrix from the camera's view space (setView's model-view matrices give positions in it)
// to a light view's clip space, composed in double.
glm::mat4 cameraToLightClip(const ViewSetup& camera, const ViewSetup& light);

class GlRenderer {
  public:
    GlRenderer(uint32_t width, uint32_t height,
               DepthConvention depth = DepthConvention::ReverseFloat);
    ~GlRenderer();
    GlRenderer(const GlRenderer&) = delete;
    GlRenderer& operator=(const GlRenderer&) = delete;

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    uint32_t framebuffer() const { return fbo_; }
    // A new size for the framebuffer (a resized window). The meshes stay; what the buffers hold is
    // undefined until the next beginFrame().
    void resize(uint32_t width, uint32_t height);

    // Uploads the meshes once (replacing earlier ones); object i draws mesh mesh_of_object[i].
    void uploadMeshes(std::span<const MeshData> meshes);
    void setObjectMeshes(std::span<const uint32_t> mesh_of_object);
    uint32_t triangleCount(uint32_t object) const;
    uint32_t objectCount() const { return static_cast<uint32_t>(object_mesh_.size()); }

    // Per frame: the view and every object's camera-relative model-view matrix (copied to the
    // GPU here).
    void setView(const ViewSetup& view, std::span<const glm::mat4> object_model_view);

    // Stereo views only: the eyes the draws and query boxes that follow go to (both: each draw
    // once per eye, and a query counts the samples of both). Both until changed.
    void setEyes(StereoEyes eyes) { eyes_ = eyes; }
    StereoEyes eyes() const { return eyes_; }

    void beginFrame();  // binds the framebuffer, clears colour, IDs, depth (and shadow texels)
    // Binds the framebuffer and its viewport again without clearing, to go on with the frame
    // after a pass into another framebuffer (a shadow map).
    void resumeFrame();
    // Draws an object drawn earlier in this frame again, with the current shadow term (a
    // shading pass after a depth pass): depth test GL_EQUAL, no depth write, so only its
    // fragments that won the depth test are shaded again, colour, ID and shadow texel alike.
    // The same program and inputs give the same depths (invariance).
    void redrawObject(uint32_t object);
    // The shadow term of the draws that follow (until the next call): nullptr, none (as before;
    // also while drawing into a shadow map, which the term would read). The first non-null call
    // adds the shadow-texel buffer to the framebuffer; beginFrame() clears it from then on.
    void setShadow(const ShadowLookup* lookup);
    void drawObject(uint32_t object);
    // One draw of an object as glMultiDrawElementsIndirect reads it (std430 and the GL layout
    // agree: five uints); base_instance is the object, which selects its matrix and ID.
    struct DrawCommand {
        uint32_t count, instance_count, first_index, base_vertex, base_instance;
    };
    DrawCommand drawCommandFor(uint32_t object) const;
    // Draws `count` commands of `command_buffer` (a GL buffer of DrawCommand) from command
    // `first` on in one call, with the state drawObject() uses: what a GPU-written command list
    // draws.
    void drawIndirect(uint32_t command_buffer, uint32_t count, uint32_t first = 0);
    // Binds the state query boxes are drawn with (no colour or depth writes, GL_GEQUAL / GL_LEQUAL
    // depth test) for a pass that draws boxes with its own program (box rasterisation).
    void useBoxState();
    // The box geometry query boxes are drawn from: the unit cube [0,1]^3 (3 floats a corner),
    // 36 byte indices.
    uint32_t boxVertexBuffer() const { return box_vbo_; }
    uint32_t boxIndexBuffer() const { return box_ibo_; }
    void drawQueryBox(const Aabb& box);  // inside glBeginQuery/glEndQuery, writes nothing
    // A query box (culling frame) as drawQueryBox() and box rasterisation draw it: grown by the
    // query-box pad, its min corner relative to the eye and its size, computed in double.
    struct EyeRelativeBox {
        glm::vec3 offset, size;
    };
    EyeRelativeBox queryBoxAsDrawn(const Aabb& box) const;
    // The near-plane rule (nearPlaneTouchesBox, occsim/culling/geometry/query_box.h) on a query box
    // in the culling frame, as this renderer draws it: a query on it cannot be trusted.
    bool queryBoxNearEye(const Aabb& box) const;
    void finish();  // glFinish

    // Read back the last frame (row 0 at the bottom, as GL returns it).
    void readObjectIds(std::vector<uint32_t>& ids) const;
    void readColor(std::vector<uint8_t>& rgba) const;
    // Per pixel: the shadow-map texel (y * size + x) + 1 whose caster shadows it, 0 where it is
    // lit, background or drawn without a shadow term (all 0 before the first setShadow()).
    void readShadowTexels(std::vector<uint32_t>& texels) const;
    // Each pixel's stored depth as its rank among the values the depth format can hold, nearer is
    // larger, so that "one step" means the same in both formats: reverse-Z float, the float's bit
    // pattern (non-negative floats order as their bits); conventional 24-bit, 2^24 - 1 minus the
    // fixed-point value. The cleared background is rank 0. Exact: no conversion rounds.
    void readDepthRanks(std::vector<uint32_t>& ranks) const;
    // The rank (as readDepthRanks gives it) a fragment at `view_depth` metres in front of the eye
    // (along the view axis) stores under the current view's projection (setView); the nearest
    // rank for a depth at or before the near plane.
    uint32_t depthRankAt(double view_depth) const;
    DepthConvention depthConvention() const { return depth_; }
    // For passes that read the depth buffer (render/gl_depth_pyramid.h): the depth attachment,
    // the current view, and forgetting which program and state are bound after such a pass
    // bound its own (the next draw or query box binds the renderer's again).
    uint32_t depthRenderbuffer() const { return depth_rb_; }
    const ViewSetup& view() const { return view_; }
    void forgetBoundState() { state_ = State::None; }

  private:
    enum class State : uint8_t { None, Draw, Query, Redraw };
    void useState(State wanted);
    void sendShadowUniforms();
    // Runs `draw` once per eye the draws go to, with that eye's viewport and projection (stereo),
    // or once as it is (one eye).
    template <typename Draw>
    void forEachEye(Draw draw);
    void drawMesh(uint32_t object);  // one draw of the object's mesh in the bound state
    // An R32UI colour attachment (GL_COLOR_ATTACHMENTn), width * height values.
    void readUintAttachment(uint32_t attachment, std::vector<uint32_t>& out,
                            const char* what) const;

    uint32_t width_ = 0, height_ = 0;
    DepthConvention depth_ = DepthConvention::ReverseFloat;
    uint32_t fbo_ = 0, color_rb_ = 0, id_rb_ = 0, depth_rb_ = 0;
    uint32_t draw_program_ = 0, query_program_ = 0;
    int draw_projection_loc_ = -1;
    int query_model_view_loc_ = -1, query_projection_loc_ = -1;
    uint32_t mesh_vao_ = 0, mesh_vbo_ = 0, mesh_ibo_ = 0;
    uint32_t model_view_vbo_ = 0, id_vbo_ = 0;  // per object (instance)
    uint32_t box_vao_ = 0, box_vbo_ = 0, box_ibo_ = 0;
    uint32_t shadow_texel_rb_ = 0;  // made by the first setShadow()
    std::array<int, 8> shadow_locs_{};
    ShadowLookup shadow_;
    bool shadow_on_ = false;
    StereoEyes eyes_ = StereoEyes::Both;

    struct MeshRange {
        uint32_t first_index;
        uint32_t index_count;
        int32_t base_vertex;
    };
    std::vector<MeshRange> meshes_;
    std::vector<uint32_t> object_mesh_;
    ViewSetup view_;
    State state_ = State::None;
};

}  // namespace occsim
