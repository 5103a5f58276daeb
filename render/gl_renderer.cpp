#include "render/gl_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>

#include "occsim/culling/geometry/query_box.h"
#include "render/gl_api.h"
#include "render/gl_shader.h"

namespace occsim {
namespace {

// One program for every draw, direct (one object, its index as the base instance) or indirect
// (GPU-written commands, render/gl_gpu_driven_draws.h): each object's model-view matrix and ID
// are per-instance attributes read at the base instance, so both paths run the same shader on
// the same inputs and write the same fragments (ground truth and a culled frame compare bit for
// bit). Object colour comes from its ID so every object looks distinct in captures without
// per-object uniforms; lighting is a head light, two-sided because some meshes are open (the
// teapot's lid).
const char* kDrawVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in mat4 a_model_view;
layout(location = 6) in uint a_object_id;
uniform mat4 u_projection;
out vec3 v_normal;
out vec3 v_view_position;
flat out uint v_object_id;
void main() {
    vec4 p = a_model_view * vec4(a_position, 1.0);
    v_normal = mat3(a_model_view) * a_normal;
    v_view_position = p.xyz;
    v_object_id = a_object_id;
    gl_Position = u_projection * p;
}
)";

// The shadow term (setShadow): the fragment moved 1.5 texels along its normal turned toward the
// light (normal offset, against self-shadowing on slopes), into the light's clip space, and its
// depth there compared with the nearest caster's in the texel it falls in (texelFetch: no
// filtering, so a pixel's state names one texel and the caster there). Outside the map: lit.
// Output 2 is that texel + 1 where the fragment is in shadow, 0 where it is lit or has no term.
const char* kDrawFragmentShader = R"(#version 330 core
in vec3 v_normal;
in vec3 v_view_position;
flat in uint v_object_id;
uniform bool u_shadow_on;
uniform bool u_shadow_reverse;
uniform mat4 u_view_to_light;
uniform vec3 u_light_travel;
uniform sampler2D u_shadow_map;
uniform int u_shadow_size;
uniform float u_normal_offset;
uniform float u_depth_bias;
layout(location = 0) out vec4 o_color;
layout(location = 1) out uint o_object_id;
layout(location = 2) out uint o_shadow_texel;
vec3 idColor(uint id) {
    uint h = id * 2654435761u;
    h ^= h >> 15;
    return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0 * 0.6
           + 0.35;
}
uint shadowTexel() {
    vec3 n = normalize(v_normal);
    if (dot(n, u_light_travel) > 0.0) n = -n;
    vec4 clip = u_view_to_light * vec4(v_view_position + u_normal_offset * n, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return 0u;
    ivec2 t = min(ivec2(uv * float(u_shadow_size)), ivec2(u_shadow_size - 1));
    float stored = texelFetch(u_shadow_map, t, 0).r;
    float depth = u_shadow_reverse ? ndc.z : ndc.z * 0.5 + 0.5;
    bool shadowed = u_shadow_reverse ? depth + u_depth_bias < stored
                                     : depth - u_depth_bias > stored;
    return shadowed ? uint(t.y * u_shadow_size + t.x) + 1u : 0u;
}
void main() {
    float light = 0.25 + 0.75 * abs(normalize(v_normal).z);
    uint texel = u_shadow_on ? shadowTexel() : 0u;
    if (texel != 0u) light *= 0.45;
    o_color = vec4(idColor(v_object_id) * light, 1.0);
    o_object_id = v_object_id;
    o_shadow_texel = texel;
}
)";

const char* kQueryVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_model_view;
uniform mat4 u_projection;
void main() { gl_Position = u_projection * (u_model_view * vec4(a_position, 1.0)); }
)";

const char* kQueryFragmentShader = R"(#version 330 core
void main() {}
)";

void allocateRenderbuffer(GLuint rb, GLenum format, uint32_t width, uint32_t height) {
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, format, static_cast<GLsizei>(width),
                          static_cast<GLsizei>(height));
}

GLuint makeRenderbuffer(GLenum format, uint32_t width, uint32_t height) {
    GLuint rb = 0;
    glGenRenderbuffers(1, &rb);
    allocateRenderbuffer(rb, format, width, height);
    return rb;
}

// The formats of the three attachments, in one place for creation and resizing.
constexpr GLenum kColorFormat = GL_RGBA8;
constexpr GLenum kIdFormat = GL_R32UI;
GLenum depthFormatOf(DepthConvention depth) {
    return depth == DepthConvention::ReverseFloat ? GL_DEPTH_COMPONENT32F : GL_DEPTH_COMPONENT24;
}

}  // namespace

glm::mat4 reverseZPerspective(float fov_y_radians, float aspect, float near_plane,
                              float far_plane) {
    const float f = 1.0f / std::tan(0.5f * fov_y_radians);
    glm::mat4 p(0.0f);
    p[0][0] = f / aspect;
    p[1][1] = f;
    p[2][2] = near_plane / (far_plane - near_plane);
    p[3][2] = far_plane * near_plane / (far_plane - near_plane);
    p[2][3] = -1.0f;
    return p;
}

glm::mat4 perspectiveFor(DepthConvention depth, float fov_y_radians, float aspect, float near_plane,
                         float far_plane) {
    return depth == DepthConvention::ReverseFloat
               ? reverseZPerspective(fov_y_radians, aspect, near_plane, far_plane)
               : glm::perspective(fov_y_radians, aspect, near_plane, far_plane);
}

glm::mat4 orthographicFor(DepthConvention depth, float left, float right, float bottom, float top,
                          float near_plane, float far_plane) {
    if (depth == DepthConvention::Conventional24) {
        return glm::ortho(left, right, bottom, top, near_plane, far_plane);
    }
    // Reverse-Z with clip control 0..1: view depth d = -z goes to (far - d) / (far - near).
    glm::mat4 p(1.0f);
    p[0][0] = 2.0f / (right - left);
    p[1][1] = 2.0f / (top - bottom);
    p[3][0] = -(right + left) / (right - left);
    p[3][1] = -(top + bottom) / (top - bottom);
    p[2][2] = 1.0f / (far_plane - near_plane);
    p[3][2] = far_plane / (far_plane - near_plane);
    return p;
}

glm::mat4 cameraToLightClip(const ViewSetup& camera, const ViewSetup& light) {
    // Camera view space -> world relative to the camera's eye -> relative to the light's eye ->
    // light view -> light clip, composed in double: the two eyes may be far from the origin and
    // from each other, and only their difference is cast to float.
    const glm::dmat4 camera_to_world = glm::transpose(glm::dmat4(camera.view_rotation));
    const glm::dmat4 eyes = glm::translate(glm::dmat4(1.0), camera.eye - light.eye);
    return glm::mat4(glm::dmat4(light.projection) * glm::dmat4(light.view_rotation) * eyes *
                     camera_to_world);
}

GlRenderer::GlRenderer(uint32_t width, uint32_t height, DepthConvention depth)
    : width_(width), height_(height), depth_(depth) {
    const bool reverse = depth_ == DepthConvention::ReverseFloat;
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    color_rb_ = makeRenderbuffer(kColorFormat, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb_);
    id_rb_ = makeRenderbuffer(kIdFormat, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, id_rb_);
    depth_rb_ = makeRenderbuffer(depthFormatOf(depth_), width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb_);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, buffers);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw std::runtime_error(
            "OpenGL: the colour + object-ID + depth framebuffer is incomplete");
    }
    checkGl("framebuffer set-up");

    draw_program_ = linkProgram(
        {{GL_VERTEX_SHADER, kDrawVertexShader}, {GL_FRAGMENT_SHADER, kDrawFragmentShader}},
        "the renderer's draw program");
    draw_projection_loc_ = glGetUniformLocation(draw_program_, "u_projection");
    shadow_locs_ = {glGetUniformLocation(draw_program_, "u_shadow_on"),
                    glGetUniformLocation(draw_program_, "u_shadow_reverse"),
                    glGetUniformLocation(draw_program_, "u_view_to_light"),
                    glGetUniformLocation(draw_program_, "u_light_travel"),
                    glGetUniformLocation(draw_program_, "u_shadow_map"),
                    glGetUniformLocation(draw_program_, "u_shadow_size"),
                    glGetUniformLocation(draw_program_, "u_normal_offset"),
                    glGetUniformLocation(draw_program_, "u_depth_bias")};
    query_program_ = linkProgram(
        {{GL_VERTEX_SHADER, kQueryVertexShader}, {GL_FRAGMENT_SHADER, kQueryFragmentShader}},
        "the renderer's query program");
    query_model_view_loc_ = glGetUniformLocation(query_program_, "u_model_view");
    query_projection_loc_ = glGetUniformLocation(query_program_, "u_projection");

    // The unit cube [0,1]^3 that every query box is drawn from.
    const float corners[8 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,
                                  0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
    const uint8_t faces[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                               2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    glGenVertexArrays(1, &box_vao_);
    glBindVertexArray(box_vao_);
    glGenBuffers(1, &box_vbo_);
    glBindBuffer(GL_ARRAY_BUFFER, box_vbo_);
    glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
    glGenBuffers(1, &box_ibo_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, box_ibo_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof faces, faces, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArray(0);

    glClipControl(GL_LOWER_LEFT, reverse ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, static_cast<GLsizei>(width), static_cast<GLsizei>(height));
    checkGl("renderer set-up");
}

GlRenderer::~GlRenderer() {
    glDeleteProgram(draw_program_);
    glDeleteProgram(query_program_);
    const GLuint buffers[] = {mesh_vbo_, mesh_ibo_, box_vbo_, box_ibo_, model_view_vbo_, id_vbo_};
    glDeleteBuffers(6, buffers);
    const GLuint arrays[] = {mesh_vao_, box_vao_};
    glDeleteVertexArrays(2, arrays);
    const GLuint rbs[] = {color_rb_, id_rb_, depth_rb_, shadow_texel_rb_};
    glDeleteRenderbuffers(shadow_texel_rb_ != 0 ? 4 : 3, rbs);
    glDeleteFramebuffers(1, &fbo_);
}

void GlRenderer::resize(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_) return;
    // Re-specifying the storage of attached renderbuffers keeps the framebuffer object and its
    // attachments; beginFrame() sets the viewport from the new size.
    allocateRenderbuffer(color_rb_, kColorFormat, width, height);
    allocateRenderbuffer(id_rb_, kIdFormat, width, height);
    allocateRenderbuffer(depth_rb_, depthFormatOf(depth_), width, height);
    if (shadow_texel_rb_ != 0) allocateRenderbuffer(shadow_texel_rb_, kIdFormat, width, height);
    width_ = width;
    height_ = height;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw std::runtime_error("OpenGL: the framebuffer is incomplete after resizing to " +
                                 std::to_string(width) + "x" + std::to_string(height));
    }
    checkGl("framebuffer resize");
}

void GlRenderer::uploadMeshes(std::span<const MeshData> meshes) {
    // Interleaved position + normal; all meshes share one buffer pair and one VAO so that a draw
    // is only a uniform update and a draw call.
    std::vector<float> vertices;
    std::vector<uint32_t> indices;
    meshes_.clear();
    for (const MeshData& mesh : meshes) {
        if (mesh.normals.size() != mesh.positions.size()) {
            throw std::invalid_argument("mesh has a different number of normals and positions");
        }
        MeshRange range{static_cast<uint32_t>(indices.size()),
                        static_cast<uint32_t>(mesh.indices.size()),
                        static_cast<int32_t>(vertices.size() / 6)};
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::vec3& p = mesh.positions[i];
            const glm::vec3& n = mesh.normals[i];
            vertices.insert(vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
        }
        indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
        meshes_.push_back(range);
    }
    if (mesh_vao_ == 0) {
        glGenVertexArrays(1, &mesh_vao_);
        glGenBuffers(1, &mesh_vbo_);
        glGenBuffers(1, &mesh_ibo_);
        glGenBuffers(1, &model_view_vbo_);
        glGenBuffers(1, &id_vbo_);
    }
    glBindVertexArray(mesh_vao_);
    glBindBuffer(GL_ARRAY_BUFFER, mesh_vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
                 vertices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh_ibo_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(indices.size() * sizeof(uint32_t)), indices.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    // Per instance: the model-view matrix (four columns) and the object ID, one each per object,
    // read at the draw's base instance (the object's index).
    glBindBuffer(GL_ARRAY_BUFFER, model_view_vbo_);
    for (GLuint column = 0; column < 4; ++column) {
        glEnableVertexAttribArray(2 + column);
        glVertexAttribPointer(2 + column, 4, GL_FLOAT, GL_FALSE, sizeof(glm::mat4),
                              reinterpret_cast<const void*>(column * sizeof(glm::vec4)));
        glVertexAttribDivisor(2 + column, 1);
    }
    glBindBuffer(GL_ARRAY_BUFFER, id_vbo_);
    glEnableVertexAttribArray(6);
    glVertexAttribIPointer(6, 1, GL_UNSIGNED_INT, sizeof(uint32_t), nullptr);
    glVertexAttribDivisor(6, 1);
    glBindVertexArray(0);
    state_ = State::None;
    checkGl("mesh upload");
}

void GlRenderer::setObjectMeshes(std::span<const uint32_t> mesh_of_object) {
    for (uint32_t m : mesh_of_object) {
        if (m >= meshes_.size()) throw std::out_of_range("object refers to a mesh never uploaded");
    }
    object_mesh_.assign(mesh_of_object.begin(), mesh_of_object.end());
    // Object i's ID is i + 1 (0 is the background).
    std::vector<uint32_t> ids(object_mesh_.size());
    for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<uint32_t>(i + 1);
    if (mesh_vao_ == 0) throw std::logic_error("setObjectMeshes before uploadMeshes");
    glBindBuffer(GL_ARRAY_BUFFER, id_vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(ids.size() * sizeof(uint32_t)),
                 ids.data(), GL_STATIC_DRAW);
    checkGl("object IDs");
}

GlRenderer::DrawCommand GlRenderer::drawCommandFor(uint32_t object) const {
    const MeshRange& mesh = meshes_[object_mesh_[object]];
    return {mesh.index_count, 1, mesh.first_index, static_cast<uint32_t>(mesh.base_vertex), object};
}

uint32_t GlRenderer::triangleCount(uint32_t object) const {
    return meshes_[object_mesh_[object]].index_count / 3;
}

void GlRenderer::setView(const ViewSetup& view, std::span<const glm::mat4> object_model_view) {
    view_ = view;
    // Copied to the GPU now, before any timing, as an engine keeps its transforms there: a draw is
    // then only a draw call, direct or indirect.
    if (mesh_vao_ != 0) {
        glBindBuffer(GL_ARRAY_BUFFER, model_view_vbo_);
        glBufferData(GL_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(object_model_view.size() * sizeof(glm::mat4)),
                     object_model_view.data(), GL_STREAM_DRAW);
    }
    state_ = State::None;  // the projection uniform must be re-sent
}

void GlRenderer::beginFrame() {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_));
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    const float background[4] = {0.12f, 0.13f, 0.16f, 1.0f};
    const GLuint no_object[4] = {0, 0, 0, 0};
    const float far_depth = depth_ == DepthConvention::ReverseFloat ? 0.0f : 1.0f;
    glClearBufferfv(GL_COLOR, 0, background);
    glClearBufferuiv(GL_COLOR, 1, no_object);
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    if (shadow_texel_rb_ != 0) glClearBufferuiv(GL_COLOR, 2, no_object);
    state_ = State::None;
}

void GlRenderer::resumeFrame() {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_));
    state_ = State::None;
}

void GlRenderer::setShadow(const ShadowLookup* lookup) {
    if (lookup != nullptr && shadow_texel_rb_ == 0) {
        // The shadow-texel attachment, made on the first frame with a shadow term: runs without
        // lights never have it.
        shadow_texel_rb_ = makeRenderbuffer(kIdFormat, width_, height_);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_RENDERBUFFER,
                                  shadow_texel_rb_);
        const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        glDrawBuffers(3, buffers);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw std::runtime_error(
                "OpenGL: the framebuffer with a shadow-texel buffer is incomplete");
        }
        checkGl("shadow-texel buffer");
    }
    const bool was_on = shadow_on_;
    shadow_on_ = lookup != nullptr;
    if (shadow_on_) shadow_ = *lookup;
    if (shadow_on_ || was_on) sendShadowUniforms();  // nothing at all for a run without lights
    state_ = State::None;  // the program and the shadow texture are bound again by the next draw
}

void GlRenderer::sendShadowUniforms() {
    // Uniforms are the program's own state: set once here, they hold across program switches.
    glUseProgram(draw_program_);
    glUniform1i(shadow_locs_[0], shadow_on_ ? 1 : 0);
    if (!shadow_on_) return;
    glUniform1i(shadow_locs_[1], depth_ == DepthConvention::ReverseFloat ? 1 : 0);
    glUniformMatrix4fv(shadow_locs_[2], 1, GL_FALSE, &shadow_.view_to_light[0][0]);
    glUniform3fv(shadow_locs_[3], 1, &shadow_.light_travel[0]);
    glUniform1i(shadow_locs_[4], 0);  // texture unit 0, bound by useState()
    glUniform1i(shadow_locs_[5], static_cast<GLint>(shadow_.size));
    glUniform1f(shadow_locs_[6], 1.5f * shadow_.texel_m);
    glUniform1f(shadow_locs_[7], shadow_.depth_bias);
}

void GlRenderer::useState(State wanted) {
    if (state_ == wanted) return;
    // Drawing writes colour, IDs and depth; a redraw writes colour and IDs where the depth is
    // equal; query boxes write nothing and pass on equal depth.
    const bool draw = wanted != State::Query;
    glUseProgram(draw ? draw_program_ : query_program_);
    glUniformMatrix4fv(draw ? draw_projection_loc_ : query_projection_loc_, 1, GL_FALSE,
                       &view_.projection[0][0]);
    if (draw && shadow_on_) {
        // Unit 0 is context state other passes bind their own textures to (the depth pyramid).
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, shadow_.texture);
    }
    glBindVertexArray(draw ? mesh_vao_ : box_vao_);
    const GLboolean write = draw ? GL_TRUE : GL_FALSE;
    glColorMask(write, write, write, write);
    glDepthMask(wanted == State::Draw ? GL_TRUE : GL_FALSE);
    if (wanted == State::Redraw) {
        glDepthFunc(GL_EQUAL);
    } else if (depth_ == DepthConvention::ReverseFloat) {
        glDepthFunc(draw ? GL_GREATER : GL_GEQUAL);
    } else {
        glDepthFunc(draw ? GL_LESS : GL_LEQUAL);
    }
    state_ = wanted;
}

void GlRenderer::drawObject(uint32_t object) {
    useState(State::Draw);
    drawMesh(object);
}

void GlRenderer::redrawObject(uint32_t object) {
    useState(State::Redraw);
    drawMesh(object);
}

template <typename Draw>
void GlRenderer::forEachEye(Draw draw) {
    if (view_.eye_separation_m == 0.0) {
        draw();
        return;
    }
    // Each eye sees the scene from half the separation to its side: a point's position relative
    // to the left eye is its position relative to the midpoint plus half the separation along x.
    // The shift is applied after the model-view matrices, in view space, where values are small.
    const int projection_loc =
        state_ == State::Query ? query_projection_loc_ : draw_projection_loc_;
    // The left eye in the upper half (read back second: rows come bottom-up), the right in the
    // lower, so that each eye's pixels are one run of a read-back (stereoEyeFirstRow).
    const auto eye_height = static_cast<GLsizei>(height_ / 2);
    const auto half = static_cast<float>(0.5 * view_.eye_separation_m);
    for (int eye = 0; eye < 2; ++eye) {
        if ((eye == 0 && eyes_ == StereoEyes::Right) || (eye == 1 && eyes_ == StereoEyes::Left))
            continue;
        glViewport(0, eye == 0 ? eye_height : 0, static_cast<GLsizei>(width_), eye_height);
        const glm::mat4 projection =
            view_.projection *
            glm::translate(glm::mat4(1.0f), glm::vec3(eye == 0 ? half : -half, 0.0f, 0.0f));
        glUniformMatrix4fv(projection_loc, 1, GL_FALSE, &projection[0][0]);
        draw();
    }
}

void GlRenderer::drawMesh(uint32_t object) {
    // The object's index is the base instance: it selects its matrix and ID.
    const MeshRange& mesh = meshes_[object_mesh_[object]];
    forEachEye([&] {
        glDrawElementsInstancedBaseVertexBaseInstance(
            GL_TRIANGLES, static_cast<GLsizei>(mesh.index_count), GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(size_t{mesh.first_index} * 4), 1, mesh.base_vertex,
            object);
    });
}

void GlRenderer::drawIndirect(uint32_t command_buffer, uint32_t count, uint32_t first) {
    if (count == 0) return;
    useState(State::Draw);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, command_buffer);
    forEachEye([&] {
        glMultiDrawElementsIndirect(
            GL_TRIANGLES, GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(uintptr_t{first} * sizeof(DrawCommand)),
            static_cast<GLsizei>(count), 0);
    });
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

void GlRenderer::useBoxState() { useState(State::Query); }

void GlRenderer::drawQueryBox(const Aabb& box) {
    useState(State::Query);
    // Dilated by queryBoxPad (occsim/culling/geometry/query_box.h), the pad the cullers' near-plane
    // rule assumes, so that zero-extent boxes still rasterise and edges shared with occluders count
    // as visible; a larger box only makes the query more conservative. The box arrives in the
    // culling frame; relative to the eye it is small again, so the float model-view matrix keeps
    // its precision far from the world origin.
    const EyeRelativeBox drawn = queryBoxAsDrawn(box);
    glm::mat4 model_view = view_.view_rotation * glm::translate(glm::mat4(1.0f), drawn.offset) *
                           glm::scale(glm::mat4(1.0f), drawn.size);
    glUniformMatrix4fv(query_model_view_loc_, 1, GL_FALSE, &model_view[0][0]);
    forEachEye([] { glDrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_BYTE, nullptr); });
}

GlRenderer::EyeRelativeBox GlRenderer::queryBoxAsDrawn(const Aabb& box) const {
    const glm::dvec3 lo = glm::dvec3(box.min) + view_.box_origin;
    const glm::dvec3 hi = glm::dvec3(box.max) + view_.box_origin;
    const double pad = queryBoxPad(lo, hi, view_.eye);
    return {glm::vec3(lo - pad - view_.eye), glm::vec3(hi - lo + 2.0 * pad)};
}

bool GlRenderer::queryBoxNearEye(const Aabb& box) const {
    if (!(view_.near_radius > 0.0f)) return false;
    return nearPlaneTouchesBox(box, glm::vec3(view_.eye - view_.box_origin), view_.near_radius);
}

void GlRenderer::finish() { glFinish(); }

void GlRenderer::readUintAttachment(uint32_t attachment, std::vector<uint32_t>& out,
                                    const char* what) const {
    out.resize(size_t{width_} * height_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glReadBuffer(attachment);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_), GL_RED_INTEGER,
                 GL_UNSIGNED_INT, out.data());
    checkGl(what);
}

void GlRenderer::readObjectIds(std::vector<uint32_t>& ids) const {
    readUintAttachment(GL_COLOR_ATTACHMENT1, ids, "glReadPixels(object IDs)");
}

void GlRenderer::readShadowTexels(std::vector<uint32_t>& texels) const {
    if (shadow_texel_rb_ == 0) {
        texels.assign(size_t{width_} * height_, 0);
        return;
    }
    readUintAttachment(GL_COLOR_ATTACHMENT2, texels, "glReadPixels(shadow texels)");
}

void GlRenderer::readColor(std::vector<uint8_t>& rgba) const {
    rgba.resize(size_t{width_} * height_ * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_), GL_RGBA,
                 GL_UNSIGNED_BYTE, rgba.data());
    checkGl("glReadPixels(colour)");
}

void GlRenderer::readDepthRanks(std::vector<uint32_t>& ranks) const {
    ranks.resize(size_t{width_} * height_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    const GLsizei w = static_cast<GLsizei>(width_), h = static_cast<GLsizei>(height_);
    if (depth_ == DepthConvention::ReverseFloat) {
        // A 32-bit float buffer read as GL_FLOAT is the stored value itself; its bits are its rank.
        static_assert(sizeof(float) == sizeof(uint32_t));
        glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, ranks.data());
        checkGl("glReadPixels(depth)");
        return;
    }
    // A 24-bit buffer read as GL_UNSIGNED_INT comes back scaled to 32 bits: the stored value is
    // the top 24 (a float read would round values near 1, where float steps are as coarse as
    // the buffer's).
    glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, ranks.data());
    checkGl("glReadPixels(depth)");
    for (uint32_t& r : ranks) r = 0xFFFFFFu - (r >> 8);
}

uint32_t GlRenderer::depthRankAt(double view_depth) const {
    // Clip z and w of a point at view z = -view_depth (both projections put -z_view in w).
    const bool reverse = depth_ == DepthConvention::ReverseFloat;
    const glm::mat4& p = view_.projection;
    const double z_clip = -double(p[2][2]) * view_depth + double(p[3][2]);
    // At or behind the eye: nearer than the near plane, so the nearest rank.
    const double ndc = view_depth > 0.0 ? z_clip / view_depth : (reverse ? 1.0 : -1.0);
    if (reverse) {
        const float stored = static_cast<float>(std::clamp(ndc, 0.0, 1.0));
        uint32_t rank = 0;
        std::memcpy(&rank, &stored, sizeof rank);
        return rank;
    }
    constexpr double kMaxFixed = double(0xFFFFFFu);
    const double window = std::clamp(0.5 * (ndc + 1.0), 0.0, 1.0);
    return 0xFFFFFFu - static_cast<uint32_t>(std::floor(window * kMaxFixed));
}

}  // namespace occsim
