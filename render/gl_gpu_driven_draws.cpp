#include "render/gl_gpu_driven_draws.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <stdexcept>

#include "render/gl_api.h"
#include "render/gl_shader.h"
#include "render/steady_seconds.h"

namespace occsim {
namespace {

// Storage-buffer bindings shared by the three programs.
constexpr GLuint kUnitsBinding = 0, kTemplatesBinding = 1, kEntryUnitsBinding = 2,
                 kSlotsBinding = 3, kStatesBinding = 4, kCommandsBinding = 5, kFlagsBinding = 6;

// One command per entry, from its template: one instance when its unit is drawn in this phase.
// Phase 1: the unit is forced or its slot passed last frame (stamped with the previous frame).
// Phase 2: the unit passed and phase 1 did not draw it (its state, written by kStoreShader).
const char* kCommandsShader = R"(#version 430 core
layout(local_size_x = 64) in;
struct Command {
    uint count;
    uint instance_count;
    uint first_index;
    uint base_vertex;
    uint base_instance;
};
layout(std430, binding = 0) readonly buffer Units { uvec2 units[]; };
layout(std430, binding = 1) readonly buffer Templates { Command templates[]; };
layout(std430, binding = 2) readonly buffer EntryUnits { uint entry_units[]; };
layout(std430, binding = 3) readonly buffer Slots { uint slots[]; };
layout(std430, binding = 4) readonly buffer States { uint states[]; };
layout(std430, binding = 5) writeonly buffer Commands { Command commands[]; };
uniform uint u_first;
uniform uint u_end;
uniform uint u_phase;
uniform uint u_frame;
void main() {
    uint e = u_first + gl_GlobalInvocationID.x;
    if (e >= u_end) return;
    uint u = entry_units[e];
    bool draw;
    if (u_phase == 1u) {
        uvec2 unit = units[u];
        draw = unit.y != 0u || slots[unit.x] + 1u == u_frame;
    } else {
        uint state = states[u];
        draw = (state & 2u) != 0u && (state & 1u) == 0u;
    }
    Command c = templates[e];
    c.instance_count = draw ? 1u : 0u;
    commands[e] = c;
}
)";

// Per unit, after the test: whether phase 1 drew it and whether it passed (forced or flagged),
// and the frame stamp of its slot when it passed, for the next frame's phase 1.
const char* kStoreShader = R"(#version 430 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Units { uvec2 units[]; };
layout(std430, binding = 3) buffer Slots { uint slots[]; };
layout(std430, binding = 4) writeonly buffer States { uint states[]; };
layout(std430, binding = 6) readonly buffer Flags { uint flags[]; };
uniform uint u_first;
uniform uint u_end;
uniform uint u_frame;
void main() {
    uint u = u_first + gl_GlobalInvocationID.x;
    if (u >= u_end) return;
    uvec2 unit = units[u];
    bool first = unit.y != 0u || slots[unit.x] + 1u == u_frame;
    bool passed = unit.y != 0u || flags[u] != 0u;
    if (passed) slots[unit.x] = u_frame;
    states[u] = (first ? 1u : 0u) | (passed ? 2u : 0u);
}
)";

// Every unit's box of a batch, one instance each (the base instance the batch's first unit), the
// unit cube scaled and moved (eye-relative) and turned into view space as GlRenderer::drawQueryBox
// turns a query box.
const char* kBoxVertexShader = R"(#version 430 core
layout(location = 0) in vec3 a_corner;
layout(location = 1) in vec3 a_offset;
layout(location = 2) in vec3 a_size;
uniform mat4 u_projection;
uniform mat4 u_view_rotation;
uniform uint u_first_unit;
flat out uint v_unit;
void main() {
    vec3 p = a_offset + a_corner * a_size;
    gl_Position = u_projection * (u_view_rotation * vec4(p, 1.0));
    v_unit = u_first_unit + uint(gl_InstanceID);
}
)";

// Early fragment tests: the shader runs only for fragments that passed the depth test, so a flag
// is written exactly where an occlusion query would count a sample.
const char* kBoxFragmentShader = R"(#version 430 core
layout(early_fragment_tests) in;
layout(std430, binding = 6) writeonly buffer Flags { uint flags[]; };
flat in uint v_unit;
void main() { flags[v_unit] = 1u; }
)";

GLuint workGroups(uint32_t n) { return (n + 63) / 64; }

// (Re)allocates `buffer` for `bytes` with no contents.
void allocate(GLuint buffer, size_t bytes, GLenum usage) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, usage);
}

void upload(GLuint buffer, const void* data, size_t bytes) {
    if (bytes == 0) return;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
}

// Fills the first `count` uints of `buffer` with `value`.
void fillUints(GLuint buffer, uint32_t count, uint32_t value) {
    if (count == 0) return;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glClearBufferSubData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, 0,
                         static_cast<GLsizeiptr>(count * sizeof(uint32_t)), GL_RED_INTEGER,
                         GL_UNSIGNED_INT, &value);
}

}  // namespace

GlGpuDrivenDraws::GlGpuDrivenDraws(GlRenderer& renderer, GlDepthPyramid* pyramid,
                                   DeviceCounters& counters)
    : renderer_(renderer), pyramid_(pyramid), counters_(counters) {
    commands_program_ = linkProgram({{GL_COMPUTE_SHADER, kCommandsShader}}, "GPU-driven commands");
    try {
        store_program_ = linkProgram({{GL_COMPUTE_SHADER, kStoreShader}}, "GPU-driven visibility");
        box_program_ = linkProgram(
            {{GL_VERTEX_SHADER, kBoxVertexShader}, {GL_FRAGMENT_SHADER, kBoxFragmentShader}},
            "GPU-driven box rasterisation");
    } catch (...) {
        glDeleteProgram(commands_program_);
        if (store_program_ != 0) glDeleteProgram(store_program_);
        throw;
    }
    commands_first_loc_ = glGetUniformLocation(commands_program_, "u_first");
    commands_end_loc_ = glGetUniformLocation(commands_program_, "u_end");
    commands_phase_loc_ = glGetUniformLocation(commands_program_, "u_phase");
    commands_frame_loc_ = glGetUniformLocation(commands_program_, "u_frame");
    store_first_loc_ = glGetUniformLocation(store_program_, "u_first");
    store_end_loc_ = glGetUniformLocation(store_program_, "u_end");
    store_frame_loc_ = glGetUniformLocation(store_program_, "u_frame");
    box_projection_loc_ = glGetUniformLocation(box_program_, "u_projection");
    box_rotation_loc_ = glGetUniformLocation(box_program_, "u_view_rotation");
    box_first_unit_loc_ = glGetUniformLocation(box_program_, "u_first_unit");

    GLuint* buffers[] = {&units_buffer_,   &templates_buffer_, &entry_units_buffer_,
                         &slots_buffer_,   &flags_buffer_,     &states_buffer_,
                         &first_commands_, &second_commands_,  &boxes_buffer_};
    for (GLuint* b : buffers) glGenBuffers(1, b);
    // The boxes: the renderer's unit cube per vertex, offset and size per instance.
    glGenVertexArrays(1, &box_vao_);
    glBindVertexArray(box_vao_);
    glBindBuffer(GL_ARRAY_BUFFER, renderer_.boxVertexBuffer());
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, renderer_.boxIndexBuffer());
    glBindBuffer(GL_ARRAY_BUFFER, boxes_buffer_);
    for (GLuint attribute = 1; attribute <= 2; ++attribute) {
        glEnableVertexAttribArray(attribute);
        glVertexAttribPointer(attribute, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float),
                              reinterpret_cast<const void*>((attribute - 1) * 4 * sizeof(float)));
        glVertexAttribDivisor(attribute, 1);
    }
    glBindVertexArray(0);
    renderer_.forgetBoundState();
    checkGl("GPU-driven draws set-up");
}

GlGpuDrivenDraws::~GlGpuDrivenDraws() {
    glDeleteProgram(commands_program_);
    glDeleteProgram(store_program_);
    glDeleteProgram(box_program_);
    const GLuint buffers[] = {units_buffer_,   templates_buffer_, entry_units_buffer_,
                              slots_buffer_,   flags_buffer_,     states_buffer_,
                              first_commands_, second_commands_,  boxes_buffer_};
    glDeleteBuffers(9, buffers);
    glDeleteVertexArrays(1, &box_vao_);
    if (!timestamps_.empty()) {
        glDeleteQueries(static_cast<GLsizei>(timestamps_.size()), timestamps_.data());
    }
}

void GlGpuDrivenDraws::ensureCapacity(uint32_t units, uint32_t entries, uint32_t slots) {
    if (units > unit_capacity_) {
        unit_capacity_ = std::max(units, 2 * unit_capacity_);
        allocate(units_buffer_, unit_capacity_ * 2 * sizeof(uint32_t), GL_STREAM_DRAW);
        allocate(flags_buffer_, unit_capacity_ * sizeof(uint32_t), GL_DYNAMIC_COPY);
        allocate(states_buffer_, unit_capacity_ * sizeof(uint32_t), GL_DYNAMIC_READ);
        glBindBuffer(GL_ARRAY_BUFFER, boxes_buffer_);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(unit_capacity_ * 8 * sizeof(float)),
                     nullptr, GL_STREAM_DRAW);
    }
    if (entries > entry_capacity_) {
        entry_capacity_ = std::max(entries, 2 * entry_capacity_);
        const size_t command_bytes = entry_capacity_ * sizeof(GlRenderer::DrawCommand);
        allocate(templates_buffer_, command_bytes, GL_STREAM_DRAW);
        allocate(entry_units_buffer_, entry_capacity_ * sizeof(uint32_t), GL_STREAM_DRAW);
        allocate(first_commands_, command_bytes, GL_DYNAMIC_COPY);
        allocate(second_commands_, command_bytes, GL_DYNAMIC_COPY);
    }
    if (slots > slot_capacity_) {
        // The tree has more nodes than before: a larger slot buffer, its new slots unseen, the
        // old ones copied on the GPU (forgetting them would make phase 1 draw nothing and phase 2
        // everything for a frame).
        const uint32_t old_capacity = slot_capacity_;
        slot_capacity_ = std::max(slots, 2 * slot_capacity_);
        GLuint grown = 0;
        glGenBuffers(1, &grown);
        allocate(grown, slot_capacity_ * sizeof(uint32_t), GL_DYNAMIC_COPY);
        fillUints(grown, slot_capacity_, 0);
        if (old_capacity > 0) {
            glBindBuffer(GL_COPY_READ_BUFFER, slots_buffer_);
            glBindBuffer(GL_COPY_WRITE_BUFFER, grown);
            glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0,
                                static_cast<GLsizeiptr>(old_capacity * sizeof(uint32_t)));
        }
        glDeleteBuffers(1, &slots_buffer_);
        slots_buffer_ = grown;
    }
}

void GlGpuDrivenDraws::resetVisibility() { fillUints(slots_buffer_, slot_capacity_, 0); }

void GlGpuDrivenDraws::clearSlot(uint32_t slot) {
    const uint32_t zero = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, slots_buffer_);
    glClearBufferSubData(GL_SHADER_STORAGE_BUFFER, GL_R32UI,
                         static_cast<GLintptr>(slot * sizeof(uint32_t)), sizeof(uint32_t),
                         GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

void GlGpuDrivenDraws::drawFirstPhase(const GpuUnits& units) {
    assert(units.slots.size() == units.bounds.size() && units.forced.size() == units.bounds.size());
    assert(units.object_units.size() == units.objects.size());
    const auto start = std::chrono::steady_clock::now();
    timestamps_used_ = 0;
    stampTime();
    ++frame_;
    frame_pending_ = true;
    states_read_ = false;
    const auto unit_count = static_cast<uint32_t>(units.bounds.size());
    const auto entry_count = static_cast<uint32_t>(units.objects.size());
    bounds_.assign(units.bounds.begin(), units.bounds.end());
    units_.resize(size_t{unit_count} * 2);
    for (uint32_t u = 0; u < unit_count; ++u) {
        assert(units.slots[u] < units.slot_count);
        units_[2 * u] = units.slots[u];
        // The renderer's own near-plane rule on the box as drawn: visible without a test.
        units_[2 * u + 1] = units.forced[u] || renderer_.queryBoxNearEye(units.bounds[u]) ? 1 : 0;
    }
    templates_.resize(entry_count);
    for (uint32_t e = 0; e < entry_count; ++e) {
        templates_[e] = renderer_.drawCommandFor(units.objects[e]);
    }
    entry_units_.assign(units.object_units.begin(), units.object_units.end());
    assert(std::is_sorted(entry_units_.begin(), entry_units_.end()));
    batch_ends_.assign(units.batch_ends.begin(), units.batch_ends.end());
    if (batch_ends_.empty()) batch_ends_.push_back(unit_count);
    assert(std::is_sorted(batch_ends_.begin(), batch_ends_.end()) &&
           batch_ends_.back() == unit_count);
    ensureCapacity(unit_count, entry_count, units.slot_count);
    upload(units_buffer_, units_.data(), units_.size() * sizeof(uint32_t));
    // Forgotten slots: a few a frame at most (BSP nodes the tree reused), each cleared alone.
    for (const uint32_t slot : units.forgotten_slots) {
        assert(slot < units.slot_count);
        clearSlot(slot);
    }
    upload(templates_buffer_, templates_.data(), entry_count * sizeof(GlRenderer::DrawCommand));
    upload(entry_units_buffer_, entry_units_.data(), entry_count * sizeof(uint32_t));

    drawPhase(1, first_commands_, 0, entry_count);
    stampTime();
    const double seconds = steadySecondsSince(start);
    phase_times_.cpu_ms[0] = seconds * 1e3;
    counters_.submit_seconds += seconds;
}

void GlGpuDrivenDraws::stampTime() {
    if (timestamps_used_ == timestamps_.size()) {
        timestamps_.push_back(0);
        glGenQueries(1, &timestamps_.back());
    }
    glQueryCounter(timestamps_[timestamps_used_++], GL_TIMESTAMP);
}

// Writes one phase's commands for entries [first, end) from their templates (kCommandsShader)
// into `commands` and draws them with one multi-draw; the command barrier makes the draw read
// what the pass wrote.
void GlGpuDrivenDraws::drawPhase(uint32_t phase, uint32_t commands, uint32_t first, uint32_t end) {
    if (end <= first) return;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kUnitsBinding, units_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTemplatesBinding, templates_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kEntryUnitsBinding, entry_units_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSlotsBinding, slots_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kStatesBinding, states_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCommandsBinding, commands);
    glUseProgram(commands_program_);
    glUniform1ui(commands_first_loc_, first);
    glUniform1ui(commands_end_loc_, end);
    glUniform1ui(commands_phase_loc_, phase);
    glUniform1ui(commands_frame_loc_, frame_);
    glDispatchCompute(workGroups(end - first), 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    renderer_.forgetBoundState();
    renderer_.drawIndirect(commands, end - first, first);
}

// Uploads every unit's box (once a frame, before the first batch) and clears the flags.
void GlGpuDrivenDraws::uploadBoxes() {
    boxes_.resize(bounds_.size() * 8);
    for (size_t u = 0; u < bounds_.size(); ++u) {
        const GlRenderer::EyeRelativeBox box = renderer_.queryBoxAsDrawn(bounds_[u]);
        float* b = &boxes_[u * 8];
        b[0] = box.offset.x, b[1] = box.offset.y, b[2] = box.offset.z, b[3] = 0.0f;
        b[4] = box.size.x, b[5] = box.size.y, b[6] = box.size.z, b[7] = 0.0f;
    }
    glBindBuffer(GL_ARRAY_BUFFER, boxes_buffer_);
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(boxes_.size() * sizeof(float)),
                    boxes_.data());
    fillUints(flags_buffer_, static_cast<uint32_t>(bounds_.size()), 0);
}

// The boxes of units [first, end) as one instanced draw.
void GlGpuDrivenDraws::rasteriseBoxes(uint32_t first, uint32_t end) {
    const ViewSetup& view = renderer_.view();
    // The query boxes' state (no writes, the passing-on-equal depth test), then this program.
    renderer_.useBoxState();
    glUseProgram(box_program_);
    glUniformMatrix4fv(box_projection_loc_, 1, GL_FALSE, &view.projection[0][0]);
    glUniformMatrix4fv(box_rotation_loc_, 1, GL_FALSE, &view.view_rotation[0][0]);
    glUniform1ui(box_first_unit_loc_, first);
    glBindVertexArray(box_vao_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFlagsBinding, flags_buffer_);
    glDrawElementsInstancedBaseVertexBaseInstance(GL_TRIANGLES, 36, GL_UNSIGNED_BYTE, nullptr,
                                                  static_cast<GLsizei>(end - first), 0, first);
    glBindVertexArray(0);
    renderer_.forgetBoundState();
}

// Tests units [first, end) against the depth drawn so far and stores each one's answer (its
// state, and its slot's stamp when it passed).
void GlGpuDrivenDraws::testBatch(GpuTest test, PyramidBound shape, uint32_t first, uint32_t end) {
    if (test == GpuTest::BoxRaster) {
        if (first == 0) uploadBoxes();
        rasteriseBoxes(first, end);
    } else if (pyramid_) {
        pyramid_->build();
        tests_.resize(end - first);
        for (uint32_t u = first; u < end; ++u)
            tests_[u - first] = pyramid_->testFor(bounds_[u], shape);
        counters_.pyramid_bounds += end - first;
        pyramid_->dispatchTests(tests_, flags_buffer_, first);
    } else if (first == 0) {
        fillUints(flags_buffer_, static_cast<uint32_t>(bounds_.size()), 1);  // nothing is hidden
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kUnitsBinding, units_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSlotsBinding, slots_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kStatesBinding, states_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFlagsBinding, flags_buffer_);
    glUseProgram(store_program_);
    glUniform1ui(store_first_loc_, first);
    glUniform1ui(store_end_loc_, end);
    glUniform1ui(store_frame_loc_, frame_);
    glDispatchCompute(workGroups(end - first), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void GlGpuDrivenDraws::drawSecondPhase(GpuTest test, PyramidBound shape) {
    using Clock = std::chrono::steady_clock;
    double test_seconds = 0, draw_seconds = 0;
    uint32_t first = 0, first_entry = 0;
    const auto entry_count = static_cast<uint32_t>(entry_units_.size());
    for (const uint32_t end : batch_ends_) {
        const auto start = Clock::now();
        if (end > first) testBatch(test, shape, first, end);
        stampTime();
        test_seconds += steadySecondsSince(start);
        const auto draw_start = Clock::now();
        // The batch's entries: those of its units, contiguous as the units are.
        uint32_t end_entry = first_entry;
        while (end_entry < entry_count && entry_units_[end_entry] < end) ++end_entry;
        drawPhase(2, second_commands_, first_entry, end_entry);
        stampTime();
        draw_seconds += steadySecondsSince(draw_start);
        first = end;
        first_entry = end_entry;
    }
    renderer_.forgetBoundState();
    phase_times_.cpu_ms[1] = test_seconds * 1e3;
    phase_times_.cpu_ms[2] = draw_seconds * 1e3;
    counters_.submit_seconds += test_seconds + draw_seconds;
}

void GlGpuDrivenDraws::readStates() {
    if (states_read_) return;
    states_read_ = true;
    states_.resize(bounds_.size());
    if (states_.empty()) return;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, states_buffer_);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                       static_cast<GLsizeiptr>(states_.size() * sizeof(uint32_t)), states_.data());
}

void GlGpuDrivenDraws::readResults(std::span<uint8_t> first_phase, std::span<uint8_t> passed) {
    assert(first_phase.size() == bounds_.size() && passed.size() == bounds_.size());
    readStates();
    for (size_t u = 0; u < states_.size(); ++u) {
        first_phase[u] = (states_[u] & 1u) != 0 ? 1 : 0;
        passed[u] = (states_[u] & 2u) != 0 ? 1 : 0;
    }
}

bool GlGpuDrivenDraws::takeDrawnEntries(std::vector<GlRenderer::DrawCommand>& drawn) {
    drawn.clear();
    if (!frame_pending_) return false;
    frame_pending_ = false;
    // Timestamps: before phase 1, after it, then after each batch's test and after its draws.
    ns_.resize(timestamps_used_);
    for (uint32_t i = 0; i < timestamps_used_; ++i) {
        glGetQueryObjectui64v(timestamps_[i], GL_QUERY_RESULT, &ns_[i]);
    }
    // Timestamps are monotonic; a driver that returns zeros gives zero, never a negative.
    const auto between = [&](uint32_t i) {
        return ns_[i + 1] > ns_[i] ? static_cast<double>(ns_[i + 1] - ns_[i]) * 1e-6 : 0.0;
    };
    for (double& ms : phase_times_.gpu_ms) ms = 0;
    for (uint32_t i = 0; i + 1 < timestamps_used_; ++i) {
        phase_times_.gpu_ms[i == 0 ? 0 : (i % 2 == 1 ? 1 : 2)] += between(i);
    }
    // An entry was drawn in phase 1 when its unit was, in phase 2 when its unit passed (and
    // phase 1 had not drawn it): the units' states, which the command passes read, say which.
    readStates();
    for (size_t e = 0; e < templates_.size(); ++e) {
        if ((states_[entry_units_[e]] & 3u) != 0) drawn.push_back(templates_[e]);
    }
    return true;
}

}  // namespace occsim
