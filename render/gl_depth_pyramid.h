// The depth-pyramid capability (occsim/culling/contract/depth_pyramid.h) on OpenGL 4.5: compute
// shaders build the pyramid from the renderer's depth buffer and test bounds against it.
// GlQueryDevice offers it (GlQueryDevice::depthPyramid()).
//
// - build(): the depth renderbuffer is copied into a depth texture (glCopyImageSubData); one
//   compute dispatch per level reduces it, each texel the farthest depth of the cells it covers
//   (occsim/culling/geometry/hzb_rules.h rules 1 and 2: level 0 the power of two at or below the
//   viewport, covering up to 3x3 pixels; every later level 2x2). Farthest is the minimum with
//   reverse-Z (the default) and the maximum with the conventional 24-bit mapping.
// - testBounds(): each bound is projected on the CPU, in double and relative to the eye (so that
//   scenes far from the origin keep their precision), grown by the query-box pad
//   (geometry/query_box.h); the rules give its level and footprint and its nearest depth is
//   converted to the stored depth and moved a few steps nearer. One compute dispatch reads every
//   footprint texel of every bound and writes one flag each; the flags are read back once per
//   call. A bound the near plane reaches (rule 5) is visible without a test.
// Time spent here counts in the device's counters as submission (building, projecting,
// dispatching) and waiting (the read-back, which waits for the frame's draws so far).
#pragma once

#include <cstdint>
#include <vector>

#include "occsim/culling/contract/depth_pyramid.h"
#include "occsim/culling/contract/render_device.h"
#include "render/gl_renderer.h"

namespace occsim {

class GlDepthPyramid final : public DepthPyramid {
  public:
    // Compiles the shaders (std::runtime_error when the context cannot). The renderer and the
    // counters must outlive it.
    GlDepthPyramid(GlRenderer& renderer, DeviceCounters& counters);
    ~GlDepthPyramid() override;
    GlDepthPyramid(const GlDepthPyramid&) = delete;
    GlDepthPyramid& operator=(const GlDepthPyramid&) = delete;

    void build() override;
    void testBounds(std::span<const Aabb> boxes, PyramidBound shape,
                    std::span<uint8_t> visible) override;
    uint32_t levelOf(const Aabb& box, PyramidBound shape) const override;

    // The pyramid's levels as the last build() left them, read back (tests): level `level`'s
    // texels, row 0 at the bottom, and its size.
    void readLevel(uint32_t level, std::vector<float>& texels, uint32_t* width,
                   uint32_t* height) const;
    uint32_t levelCount() const { return level_count_; }

    // One bound as the test shader reads it (std430): its footprint at `level`, its nearest depth
    // as stored, and whether it is visible without a test.
    struct Test {
        int32_t x0, y0, x1, y1;
        int32_t level;
        float depth;
        uint32_t untested;
        uint32_t pad;
    };
    // The record for one box under the renderer's current view and depth convention (public for
    // the tests of the rules as the GPU path applies them).
    Test testFor(const Aabb& box, PyramidBound shape) const;
    // Runs the test shader on `tests` against the last pyramid built, writing one uint flag per
    // test into `flag_buffer` (a GL buffer of at least first_flag + tests.size() uints) from
    // `first_flag` on, and reads nothing back: what GPU-driven draws (render/gl_gpu_driven_draws.h)
    // build their commands from.
    void dispatchTests(std::span<const Test> tests, uint32_t flag_buffer, uint32_t first_flag = 0);

  private:
    void ensureTextures();

    GlRenderer& renderer_;
    DeviceCounters& counters_;
    uint32_t reduce_program_ = 0, test_program_ = 0;
    int reduce_in_size_loc_ = -1, reduce_out_size_loc_ = -1, reduce_in_level_loc_ = -1,
        reduce_reverse_loc_ = -1, test_count_loc_ = -1, test_first_flag_loc_ = -1,
        test_reverse_loc_ = -1;
    uint32_t depth_copy_ = 0, pyramid_ = 0;  // textures
    uint32_t viewport_w_ = 0, viewport_h_ = 0, base_w_ = 0, base_h_ = 0, level_count_ = 0;
    uint32_t test_buffer_ = 0, flag_buffer_ = 0;
    size_t buffer_capacity_ = 0;  // tests the test buffer holds
    size_t flag_capacity_ = 0;    // flags the flag buffer holds
    bool built_ = false;
    std::vector<Test> tests_;
    std::vector<uint32_t> flags_;
};

}  // namespace occsim
