// GPU-driven draws (occsim/culling/contract/gpu_driven_draws.h) on OpenGL 4.5: both phases'
// draw commands written by compute shaders and drawn with one glMultiDrawElementsIndirect each,
// each slot's visibility kept in a storage buffer from frame to frame, nothing read back during
// the frame. GlQueryDevice offers it (GlQueryDevice::gpuDrivenDraws()).
//
// - drawFirstPhase(): uploads the units (slot, forced) and one command template per draw-list
//   entry (the object's mesh range, its index as the base instance: GlRenderer::drawCommandFor);
//   a compute pass writes phase 1's commands, one instance where the entry's unit is forced or its
//   slot passed last frame (a frame stamp, so a unit out of view for a frame is not "visible last
//   frame"), zero otherwise; one multi-draw draws them.
// - drawSecondPhase(): the test writes one flag per unit into a storage buffer. Pyramid: the
//   depth pyramid is built from phase 1's depth and each unit's bound is projected on the CPU
//   (GlDepthPyramid::testFor, the rules of hzb_rules.h) and tested by its compute shader
//   (dispatchTests). BoxRaster: every unit's box, grown by the query-box pad as
//   GlRenderer::drawQueryBox grows it, is drawn as one instanced draw against the depth buffer
//   with the query boxes' depth test (GL_GEQUAL with reverse-Z), no colour or depth writes and
//   early fragment tests, so only a fragment that passes the depth test writes its unit's flag.
//   A unit the near plane reaches (GlRenderer::queryBoxNearEye) is forced here as well. Then a
//   compute pass over the units stores each one's answer (forced or flagged) in its slot and a
//   last one over the entries writes phase 2's commands (passed, not drawn in phase 1); one
//   multi-draw draws them. In batches (GpuUnits::batch_ends) all of it is done batch by batch:
//   each batch's boxes are one instanced draw (its first unit the base instance), or a pyramid
//   rebuilt from the depth so far, and its entries (contiguous, as its units are) one multi-draw
//   from an offset into the command list.
// - After the frame: readResults() and takeDrawnEntries() read the units' states back, once
//   (what the command passes wrote their commands from), and derive what each phase drew
//   (GlQueryDevice::resolveGpuDrivenDraws).
// Time spent here counts as the device's submission time (DeviceCounters::submit_seconds), and
// is measured per phase (phase 1, the test, phase 2; the batches' tests and draws summed) on the
// CPU and, with timestamp queries between the phases, on the GPU (phaseTimes(); on a software
// rasteriser the GPU times are the rasteriser's threads' time, which is CPU time).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "occsim/culling/contract/gpu_driven_draws.h"
#include "occsim/culling/contract/render_device.h"
#include "render/gl_depth_pyramid.h"
#include "render/gl_renderer.h"

namespace occsim {

class GlGpuDrivenDraws final : public GpuDrivenDraws {
  public:
    // Compiles the shaders (std::runtime_error when the context cannot). `pyramid` may be null
    // (GpuTest::Pyramid then passes every unit). Everything passed in must outlive this object.
    GlGpuDrivenDraws(GlRenderer& renderer, GlDepthPyramid* pyramid, DeviceCounters& counters);
    ~GlGpuDrivenDraws() override;
    GlGpuDrivenDraws(const GlGpuDrivenDraws&) = delete;
    GlGpuDrivenDraws& operator=(const GlGpuDrivenDraws&) = delete;

    void resetVisibility() override;
    void drawFirstPhase(const GpuUnits& units) override;
    void drawSecondPhase(GpuTest test, PyramidBound shape) override;
    void readResults(std::span<uint8_t> first_phase, std::span<uint8_t> passed) override;
    bool offersBoxRaster() const override { return true; }

    // After the frame, outside any timing: the entries the two phases drew this frame (from the
    // units' states read back, as the command passes read them), as the command each drew, and the
    // frame's phase times; false (and `drawn` empty) when no frame ran since the last call. The
    // frame is forgotten after.
    bool takeDrawnEntries(std::vector<GlRenderer::DrawCommand>& drawn);

    // Milliseconds of phase 1 (uploads, commands, its multi-draw), the test (pyramid build and
    // tests, or the box raster, and the pass that stores the answers) and phase 2 (commands, its
    // multi-draw), of the last frame takeDrawnEntries() took: submission on the CPU, and between
    // timestamps on the GPU.
    struct PhaseTimes {
        double cpu_ms[3] = {0, 0, 0};
        double gpu_ms[3] = {0, 0, 0};
    };
    const PhaseTimes& phaseTimes() const { return phase_times_; }

  private:
    void ensureCapacity(uint32_t units, uint32_t entries, uint32_t slots);
    void clearSlot(uint32_t slot);
    void stampTime();
    void drawPhase(uint32_t phase, uint32_t commands, uint32_t first, uint32_t end);
    void uploadBoxes();
    void rasteriseBoxes(uint32_t first, uint32_t end);
    void testBatch(GpuTest test, PyramidBound shape, uint32_t first, uint32_t end);
    void readStates();

    GlRenderer& renderer_;
    GlDepthPyramid* pyramid_;
    DeviceCounters& counters_;
    uint32_t commands_program_ = 0, store_program_ = 0, box_program_ = 0;
    int commands_first_loc_ = -1, commands_end_loc_ = -1, commands_phase_loc_ = -1,
        commands_frame_loc_ = -1;
    int store_first_loc_ = -1, store_end_loc_ = -1, store_frame_loc_ = -1;
    int box_projection_loc_ = -1, box_rotation_loc_ = -1, box_first_unit_loc_ = -1;
    uint32_t box_vao_ = 0;
    // Storage buffers: units (slot, forced), entry templates and their units, each slot's frame
    // stamp, each unit's flag and state (bit 0 first phase, bit 1 passed), the two command lists,
    // and the boxes to rasterise.
    uint32_t units_buffer_ = 0, templates_buffer_ = 0, entry_units_buffer_ = 0;
    uint32_t slots_buffer_ = 0, flags_buffer_ = 0, states_buffer_ = 0;
    uint32_t first_commands_ = 0, second_commands_ = 0, boxes_buffer_ = 0;
    uint32_t unit_capacity_ = 0, entry_capacity_ = 0, slot_capacity_ = 0;
    uint32_t frame_ = 1;  // the stamp of the current frame (slots hold 0 when never passed)
    // Timestamp queries: before phase 1, after it, then after each batch's test and its draws.
    std::vector<uint32_t> timestamps_;
    uint32_t timestamps_used_ = 0;
    std::vector<uint64_t> ns_;
    PhaseTimes phase_times_;
    bool frame_pending_ = false;
    // This frame, on the CPU.
    std::vector<uint32_t> units_;  // slot, forced: two uints a unit
    std::vector<Aabb> bounds_;
    std::vector<GlRenderer::DrawCommand> templates_;
    std::vector<uint32_t> entry_units_;
    std::vector<uint32_t> batch_ends_;  // phase 2's batches (GpuUnits::batch_ends), at least one
    std::vector<GlDepthPyramid::Test> tests_;
    std::vector<float> boxes_;      // per unit: offset (xyz, pad) and size (xyz, pad), eye-relative
    std::vector<uint32_t> states_;  // per unit, read back once a frame after it (readStates)
    bool states_read_ = false;
};

}  // namespace occsim
