#include "render/gl_depth_pyramid.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "occsim/culling/geometry/hzb_rules.h"
#include "occsim/culling/geometry/query_box.h"
#include "render/gl_api.h"
#include "render/gl_shader.h"
#include "render/steady_seconds.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

// One level from the cells below it (the depth texture for level 0, the level below otherwise):
// each texel the farthest of the cells it covers, by hzb_rules.h's firstCovered/lastCovered.
const char* kReduceShader = R"(#version 430 core
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32f, binding = 0) uniform writeonly image2D u_out;
layout(binding = 0) uniform sampler2D u_in;
uniform int u_in_level;
uniform ivec2 u_in_size;
uniform ivec2 u_out_size;
uniform int u_reverse;
void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (t.x >= u_out_size.x || t.y >= u_out_size.y) return;
    ivec2 first = (t * u_in_size) / u_out_size;
    ivec2 last = ((t + 1) * u_in_size + u_out_size - 1) / u_out_size - 1;
    float farthest = texelFetch(u_in, first, u_in_level).r;
    for (int y = first.y; y <= last.y; ++y) {
        for (int x = first.x; x <= last.x; ++x) {
            float d = texelFetch(u_in, ivec2(x, y), u_in_level).r;
            farthest = u_reverse != 0 ? min(farthest, d) : max(farthest, d);
        }
    }
    imageStore(u_out, t, vec4(farthest));
}
)";

// One flag per bound: 1 when its nearest depth is not farther than some texel of its footprint.
const char* kTestShader = R"(#version 430 core
layout(local_size_x = 64) in;
struct Test {
    ivec4 rect;
    int level;
    float depth;
    uint untested;
    uint pad;
};
layout(std430, binding = 0) readonly buffer Tests { Test tests[]; };
layout(std430, binding = 1) writeonly buffer Flags { uint flags[]; };
layout(binding = 0) uniform sampler2D u_pyramid;
uniform uint u_count;
uniform uint u_first_flag;
uniform int u_reverse;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    Test t = tests[i];
    uint visible = t.untested;
    for (int y = t.rect.y; y <= t.rect.w && visible == 0u; ++y) {
        for (int x = t.rect.x; x <= t.rect.z; ++x) {
            float farthest = texelFetch(u_pyramid, ivec2(x, y), t.level).r;
            bool shows = u_reverse != 0 ? !(t.depth < farthest) : !(t.depth > farthest);
            if (shows) {
                visible = 1u;
                break;
            }
        }
    }
    flags[u_first_flag + i] = visible;
}
)";

uint32_t computeProgram(const char* source) {
    return linkProgram({{GL_COMPUTE_SHADER, source}}, "depth pyramid");
}

GLuint groups(uint32_t n, uint32_t size) { return (n + size - 1) / size; }

}  // namespace

GlDepthPyramid::GlDepthPyramid(GlRenderer& renderer, DeviceCounters& counters)
    : renderer_(renderer), counters_(counters) {
    reduce_program_ = computeProgram(kReduceShader);
    try {
        test_program_ = computeProgram(kTestShader);
    } catch (...) {
        glDeleteProgram(reduce_program_);
        throw;
    }
    reduce_in_size_loc_ = glGetUniformLocation(reduce_program_, "u_in_size");
    reduce_out_size_loc_ = glGetUniformLocation(reduce_program_, "u_out_size");
    reduce_in_level_loc_ = glGetUniformLocation(reduce_program_, "u_in_level");
    reduce_reverse_loc_ = glGetUniformLocation(reduce_program_, "u_reverse");
    test_count_loc_ = glGetUniformLocation(test_program_, "u_count");
    test_first_flag_loc_ = glGetUniformLocation(test_program_, "u_first_flag");
    test_reverse_loc_ = glGetUniformLocation(test_program_, "u_reverse");
    glGenBuffers(1, &test_buffer_);
    glGenBuffers(1, &flag_buffer_);
    checkGl("depth pyramid set-up");
}

GlDepthPyramid::~GlDepthPyramid() {
    glDeleteProgram(reduce_program_);
    glDeleteProgram(test_program_);
    const GLuint buffers[] = {test_buffer_, flag_buffer_};
    glDeleteBuffers(2, buffers);
    const GLuint textures[] = {depth_copy_, pyramid_};
    glDeleteTextures(2, textures);
}

void GlDepthPyramid::ensureTextures() {
    const uint32_t w = renderer_.width(), h = renderer_.height();
    if (w == viewport_w_ && h == viewport_h_ && pyramid_ != 0) return;
    const GLuint textures[] = {depth_copy_, pyramid_};
    glDeleteTextures(2, textures);
    viewport_w_ = w;
    viewport_h_ = h;
    base_w_ = hzb::pyramidBaseSize(w);
    base_h_ = hzb::pyramidBaseSize(h);
    level_count_ = hzb::pyramidLevelCount(base_w_, base_h_);
    const bool reverse = renderer_.depthConvention() == DepthConvention::ReverseFloat;
    // The copy's format must be the depth attachment's own for glCopyImageSubData.
    glGenTextures(1, &depth_copy_);
    glBindTexture(GL_TEXTURE_2D, depth_copy_);
    glTexStorage2D(GL_TEXTURE_2D, 1, reverse ? GL_DEPTH_COMPONENT32F : GL_DEPTH_COMPONENT24,
                   static_cast<GLsizei>(w), static_cast<GLsizei>(h));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glGenTextures(1, &pyramid_);
    glBindTexture(GL_TEXTURE_2D, pyramid_);
    glTexStorage2D(GL_TEXTURE_2D, static_cast<GLsizei>(level_count_), GL_R32F,
                   static_cast<GLsizei>(base_w_), static_cast<GLsizei>(base_h_));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    checkGl("depth pyramid textures");
}

void GlDepthPyramid::build() {
    const auto start = Clock::now();
    ensureTextures();
    const bool reverse = renderer_.depthConvention() == DepthConvention::ReverseFloat;
    glCopyImageSubData(renderer_.depthRenderbuffer(), GL_RENDERBUFFER, 0, 0, 0, 0, depth_copy_,
                       GL_TEXTURE_2D, 0, 0, 0, 0, static_cast<GLsizei>(viewport_w_),
                       static_cast<GLsizei>(viewport_h_), 1);
    glUseProgram(reduce_program_);
    glUniform1i(reduce_reverse_loc_, reverse ? 1 : 0);
    glActiveTexture(GL_TEXTURE0);
    uint32_t in_w = viewport_w_, in_h = viewport_h_;
    for (uint32_t level = 0; level < level_count_; ++level) {
        const uint32_t out_w = hzb::levelSize(base_w_, level);
        const uint32_t out_h = hzb::levelSize(base_h_, level);
        glBindTexture(GL_TEXTURE_2D, level == 0 ? depth_copy_ : pyramid_);
        glUniform1i(reduce_in_level_loc_, level == 0 ? 0 : static_cast<GLint>(level - 1));
        glUniform2i(reduce_in_size_loc_, static_cast<GLint>(in_w), static_cast<GLint>(in_h));
        glUniform2i(reduce_out_size_loc_, static_cast<GLint>(out_w), static_cast<GLint>(out_h));
        glBindImageTexture(0, pyramid_, static_cast<GLint>(level), GL_FALSE, 0, GL_WRITE_ONLY,
                           GL_R32F);
        glDispatchCompute(groups(out_w, 8), groups(out_h, 8), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        in_w = out_w;
        in_h = out_h;
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    renderer_.forgetBoundState();
    built_ = true;
    ++counters_.pyramid_builds;
    counters_.submit_seconds += steadySecondsSince(start);
}

GlDepthPyramid::Test GlDepthPyramid::testFor(const Aabb& box, PyramidBound shape) const {
    Test t{0, 0, 0, 0, 0, 0.0f, 1, 0};
    if (!built_ || !isFiniteAndOrdered(box)) return t;
    const ViewSetup& view = renderer_.view();
    const glm::dmat4 projection(view.projection);
    // Relative to the eye, in double: far from the origin the box is small numbers again.
    const glm::dvec3 lo = glm::dvec3(box.min) + view.box_origin - view.eye;
    const glm::dvec3 hi = glm::dvec3(box.max) + view.box_origin - view.eye;
    const double pad = queryBoxPad(lo, hi, glm::dvec3(0.0));
    const glm::dmat4 view_projection = projection * glm::dmat4(view.view_rotation);
    const hzb::ScreenBound b =
        shape == PyramidBound::Sphere
            ? hzb::projectSphere(view_projection, 0.5 * (lo + hi), 0.5 * glm::length(hi - lo) + pad)
            : hzb::projectBox(view_projection, lo - pad, hi + pad);
    // The near plane's w, from the projection (reverse-Z: depth 1 there; conventional: -1).
    const bool reverse = renderer_.depthConvention() == DepthConvention::ReverseFloat;
    const double p22 = projection[2][2], p32 = projection[3][2];
    const double near_w = reverse ? p32 / (1.0 + p22) : p32 / (p22 - 1.0);
    if (!hzb::testable(b, std::max(near_w, double(view.near_radius)))) return t;  // rule 5

    const hzb::TexelRect pixels = hzb::pixelsOf(b, viewport_w_, viewport_h_);
    const hzb::TexelRect base =
        hzb::baseTexelsOf(pixels, viewport_w_, viewport_h_, base_w_, base_h_);
    const uint32_t level = hzb::pyramidLevelFor(base);
    const hzb::TexelRect footprint = hzb::footprintAt(base, level);
    // The depth stored at the nearest w, moved a few steps nearer for the rounding of the
    // fragments' float depths.
    const double ndc = (-p22 * b.min_w + p32) / b.min_w;
    float depth = 0.0f;
    if (reverse) {
        depth = static_cast<float>(ndc);
        for (int i = 0; i < 4; ++i) depth = std::nextafter(depth, INFINITY);
    } else {
        depth = static_cast<float>(0.5 * (ndc + 1.0) - 4.0 / double(1 << 24));
    }
    return Test{static_cast<int32_t>(footprint.x0),
                static_cast<int32_t>(footprint.y0),
                static_cast<int32_t>(footprint.x1),
                static_cast<int32_t>(footprint.y1),
                static_cast<int32_t>(level),
                depth,
                0,
                0};
}

uint32_t GlDepthPyramid::levelOf(const Aabb& box, PyramidBound shape) const {
    const Test t = testFor(box, shape);
    return built_ && !t.untested ? static_cast<uint32_t>(t.level) : kNoLevel;
}

void GlDepthPyramid::testBounds(std::span<const Aabb> boxes, PyramidBound shape,
                                std::span<uint8_t> visible) {
    assert(visible.size() == boxes.size());
    const auto start = Clock::now();
    counters_.pyramid_bounds += boxes.size();
    if (boxes.empty()) return;
    if (!built_) {
        std::fill(visible.begin(), visible.end(), uint8_t{1});
        return;
    }
    tests_.resize(boxes.size());
    for (size_t i = 0; i < boxes.size(); ++i) tests_[i] = testFor(boxes[i], shape);
    const uint32_t count = static_cast<uint32_t>(boxes.size());
    if (count > flag_capacity_) {
        flag_capacity_ = std::max<size_t>(count, 2 * flag_capacity_);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, flag_buffer_);
        glBufferData(GL_SHADER_STORAGE_BUFFER,
                     static_cast<GLsizeiptr>(flag_capacity_ * sizeof(uint32_t)), nullptr,
                     GL_STREAM_READ);
    }
    dispatchTests(tests_, flag_buffer_);
    counters_.submit_seconds += steadySecondsSince(start);

    const auto wait_start = Clock::now();
    ++counters_.read_backs;
    flags_.resize(count);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, flag_buffer_);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                       static_cast<GLsizeiptr>(count * sizeof(uint32_t)), flags_.data());
    for (size_t i = 0; i < count; ++i) visible[i] = flags_[i] != 0 ? 1 : 0;
    counters_.wait_seconds += steadySecondsSince(wait_start);
}

void GlDepthPyramid::dispatchTests(std::span<const Test> tests, uint32_t flag_buffer,
                                   uint32_t first_flag) {
    const uint32_t count = static_cast<uint32_t>(tests.size());
    if (count == 0) return;
    if (count > buffer_capacity_) {
        buffer_capacity_ = std::max<size_t>(count, 2 * buffer_capacity_);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, test_buffer_);
        glBufferData(GL_SHADER_STORAGE_BUFFER,
                     static_cast<GLsizeiptr>(buffer_capacity_ * sizeof(Test)), nullptr,
                     GL_STREAM_DRAW);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, test_buffer_);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(Test)),
                    tests.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, test_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, flag_buffer);
    glUseProgram(test_program_);
    glUniform1ui(test_count_loc_, count);
    glUniform1ui(test_first_flag_loc_, first_flag);
    glUniform1i(test_reverse_loc_,
                renderer_.depthConvention() == DepthConvention::ReverseFloat ? 1 : 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, pyramid_);
    glDispatchCompute(groups(count, 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    glBindTexture(GL_TEXTURE_2D, 0);
    renderer_.forgetBoundState();
}

void GlDepthPyramid::readLevel(uint32_t level, std::vector<float>& texels, uint32_t* width,
                               uint32_t* height) const {
    *width = hzb::levelSize(base_w_, level);
    *height = hzb::levelSize(base_h_, level);
    texels.resize(size_t{*width} * *height);
    // A framebuffer over the level, read like any colour buffer.
    GLuint fbo = 0;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, pyramid_,
                           static_cast<GLint>(level));
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, static_cast<GLsizei>(*width), static_cast<GLsizei>(*height), GL_RED,
                 GL_FLOAT, texels.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, renderer_.framebuffer());
    glDeleteFramebuffers(1, &fbo);
    checkGl("depth pyramid read-back");
}

}  // namespace occsim
