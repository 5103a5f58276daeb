#include "render/gl_query_device.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <stdexcept>

#include "occsim/culling/contract/query_id_check.h"
#include "render/gl_api.h"
#include "render/gl_checked_call.h"
#include "render/steady_seconds.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

GlQueryDevice::GlQueryDevice(GlRenderer& renderer, LatencyMode latency)
    : renderer_(renderer), latency_(latency) {}

GlQueryDevice::~GlQueryDevice() {
    if (!gl_queries_.empty()) {
        OCCSIM_GL_CHECKED(
            glDeleteQueries(static_cast<GLsizei>(gl_queries_.size()), gl_queries_.data()));
    }
    if (!primitive_queries_.empty()) {
        OCCSIM_GL_CHECKED(glDeleteQueries(static_cast<GLsizei>(primitive_queries_.size()),
                                          primitive_queries_.data()));
    }
}

DepthPyramid* GlQueryDevice::depthPyramid() {
    if (!pyramid_tried_) {
        pyramid_tried_ = true;
        try {
            pyramid_ = std::make_unique<GlDepthPyramid>(renderer_, counters_);
        } catch (const std::runtime_error&) {
            pyramid_.reset();  // no compute shaders here: the capability is absent
        }
    }
    return pyramid_.get();
}

GpuDrivenDraws* GlQueryDevice::gpuDrivenDraws() {
    if (!gpu_draws_tried_) {
        gpu_draws_tried_ = true;
        // The pyramid test needs the depth pyramid; box rasterisation does not.
        auto* pyramid = static_cast<GlDepthPyramid*>(depthPyramid());
        try {
            gpu_draws_ = std::make_unique<GlGpuDrivenDraws>(renderer_, pyramid, counters_);
        } catch (const std::runtime_error&) {
            gpu_draws_.reset();  // no compute shaders or storage buffers: the capability is absent
        }
    }
    return gpu_draws_.get();
}

void GlQueryDevice::resolveGpuDrivenDraws() {
    gpu_frame_resolved_ = false;
    gpu_drawn_objects_.clear();
    if (!gpu_draws_) return;
    gpu_frame_resolved_ = gpu_draws_->takeDrawnEntries(gpu_drawn_);
    for (const GlRenderer::DrawCommand& c : gpu_drawn_) {
        const uint32_t object = c.base_instance;
        gpu_drawn_objects_.push_back(object);
        if (object < drawn_mark_.size()) drawn_mark_[object] = drawn_set_;
        ++counters_.objects_drawn;
        counters_.triangles_drawn += c.count / 3;
    }
}

uint32_t GlQueryDevice::queriesInFlight() const {
    return static_cast<uint32_t>(gl_queries_.size() - free_ids_.size() - held_ids_.size());
}

void GlQueryDevice::drawObject(uint32_t object) {
    if (leftOut(object)) return;
    const auto start = Clock::now();
    renderer_.drawObject(object);
    if (object < drawn_mark_.size()) drawn_mark_[object] = drawn_set_;
    ++commands_;
    ++counters_.objects_drawn;
    counters_.triangles_drawn += renderer_.triangleCount(object);
    counters_.submit_seconds += steadySecondsSince(start);
}

void GlQueryDevice::markSubmitted(std::vector<uint8_t>& submitted) const {
    submitted.assign(drawn_mark_.size(), 0);
    for (size_t o = 0; o < drawn_mark_.size(); ++o) submitted[o] = drawn_mark_[o] == drawn_set_;
    for (const ConditionalDraw& d : conditional_draws_) {
        if (d.object < submitted.size()) submitted[d.object] = 1;
    }
}

void GlQueryDevice::beginDrawnSet(uint32_t objects) {
    if (++drawn_set_ == 0) {  // wrapped after 2^32 sets: old marks could match again
        drawn_mark_.assign(drawn_mark_.size(), 0);
        drawn_set_ = 1;
    }
    drawn_mark_.resize(objects, 0);
    // The last set's conditional draws are forgotten: the queries they held may serve again.
    conditional_draws_.clear();
    blocks_.clear();
    for (QueryId id : held_ids_) conditioned_[id] = 0;
    free_ids_.insert(free_ids_.end(), held_ids_.begin(), held_ids_.end());
    held_ids_.clear();
}

void GlQueryDevice::retire(QueryId id) {
    live_[id] = 0;
    (conditioned_[id] ? held_ids_ : free_ids_).push_back(id);
}

void GlQueryDevice::drawIf(QueryId id, std::span<const uint32_t> objects, ConditionWait wait) {
    const auto start = Clock::now();
    // Release builds: a dead id draws unconditionally (the safe side). A box that reaches the near
    // plane as drawn gives samples that mean nothing: drawn unconditionally, as takeAnswer()
    // would have answered it visible.
    bool conditional = isLive(id, "drawIf") && near_eye_[id] == 0;
    GLenum mode = wait == ConditionWait::Wait ? GL_QUERY_WAIT : GL_QUERY_NO_WAIT;
    if (conditional && latency_.deterministic) {
        // The device's model of readiness, not the driver's: the same draws execute every run.
        const bool ready = commands_ - issued_at_[id] > latency_.latency_commands;
        if (wait == ConditionWait::NoWait && !ready) conditional = false;
        mode = GL_QUERY_WAIT;
    }
    if (conditional) {
        conditioned_[id] = 1;
        const auto block = static_cast<uint32_t>(blocks_.size());
        if (block == primitive_queries_.size()) {
            GLuint q = 0;
            OCCSIM_GL_CHECKED(glGenQueries(1, &q));
            primitive_queries_.push_back(q);
        }
        blocks_.push_back({static_cast<uint32_t>(conditional_draws_.size()), 0, block});
        OCCSIM_GL_CHECKED(glBeginQuery(GL_PRIMITIVES_GENERATED, primitive_queries_[block]));
        OCCSIM_GL_CHECKED(glBeginConditionalRender(gl_queries_[id], mode));
    }
    for (uint32_t object : objects) {
        if (leftOut(object)) continue;
        renderer_.drawObject(object);
        if (!conditional) {
            if (object < drawn_mark_.size()) drawn_mark_[object] = drawn_set_;
        } else {
            conditional_draws_.push_back({object, id});
            ++blocks_.back().draws;
        }
        ++commands_;
        ++counters_.objects_drawn;
        ++counters_.conditional_draws;
        counters_.triangles_drawn += renderer_.triangleCount(object);
    }
    if (conditional) {
        OCCSIM_GL_CHECKED(glEndConditionalRender());
        OCCSIM_GL_CHECKED(glEndQuery(GL_PRIMITIVES_GENERATED));
    }
    counters_.submit_seconds += steadySecondsSince(start);
}

void GlQueryDevice::release(QueryId id) {
    if (isLive(id, "release")) retire(id);  // release builds: a dead id is released nothing
}

void GlQueryDevice::resolveConditionalDraws() {
    for (const ConditionalDraw& d : conditional_draws_) {
        if (d.object >= drawn_mark_.size() || drawn_mark_[d.object] == drawn_set_) continue;
        GLuint64 samples = 0;
        OCCSIM_GL_CHECKED(glGetQueryObjectui64v(gl_queries_[d.query], GL_QUERY_RESULT, &samples));
        if (samples > 0) drawn_mark_[d.object] = drawn_set_;
    }
}

GlQueryDevice::SkippedDraws GlQueryDevice::skippedConditionalDraws() {
    SkippedDraws skipped;
    for (const ConditionalBlock& b : blocks_) {
        GLuint64 primitives = 0;
        OCCSIM_GL_CHECKED(glGetQueryObjectui64v(primitive_queries_[b.primitive_query],
                                                GL_QUERY_RESULT, &primitives));
        for (uint32_t k = b.first_draw; k < b.first_draw + b.draws; ++k) {
            const uint64_t triangles = renderer_.triangleCount(conditional_draws_[k].object);
            if (primitives >= triangles) {
                primitives -= triangles;  // executed
            } else {
                ++skipped.objects;
                skipped.triangles += triangles;
            }
        }
    }
    return skipped;
}

QueryId GlQueryDevice::issueQuery(std::span<const Aabb> boxes,
                                  std::span<const QueryTag> /*subjects*/) {
    const auto start = Clock::now();
    QueryId id;
    if (!free_ids_.empty()) {
        id = free_ids_.back();
        free_ids_.pop_back();
    } else {
        id = static_cast<QueryId>(gl_queries_.size());
        GLuint q = 0;
        OCCSIM_GL_CHECKED(glGenQueries(1, &q));
        gl_queries_.push_back(q);
        issued_at_.push_back(0);
        answered_.push_back(0);
        live_.push_back(0);
        near_eye_.push_back(0);
        conditioned_.push_back(0);
    }
    near_eye_[id] = 0;
    size_t drawn_boxes = 0;
    OCCSIM_GL_CHECKED(glBeginQuery(GL_SAMPLES_PASSED, gl_queries_[id]));
    for (const Aabb& box : boxes) {
        if (may_matter_ && !may_matter_(box)) {  // setQueryFilter: it counts no sample
            ++filtered_query_boxes_;
            continue;
        }
        near_eye_[id] |= renderer_.queryBoxNearEye(box) ? 1 : 0;
        renderer_.drawQueryBox(box);
        ++drawn_boxes;
    }
    OCCSIM_GL_CHECKED(glEndQuery(GL_SAMPLES_PASSED));
    issued_at_[id] = commands_++;
    answered_[id] = 0;
    live_[id] = 1;
    ++counters_.queries_issued;
    counters_.query_boxes += drawn_boxes;
    counters_.submit_seconds += steadySecondsSince(start);
    return id;
}

void GlQueryDevice::noteAnswered(QueryId id) {
    if (answered_[id]) return;
    answered_[id] = 1;
    const uint64_t after = commands_ - issued_at_[id] - 1;
    latencies_.push_back(static_cast<uint32_t>(std::min<uint64_t>(after, UINT32_MAX)));
}

void GlQueryDevice::takeAnswerLatencies(std::vector<uint32_t>& out) {
    out.clear();
    out.swap(latencies_);
}

bool GlQueryDevice::isLive(QueryId id, const char* call) const {
    const bool issued = id < live_.size();
    if (issued && live_[id]) return true;
    if (kCheckQueryIds) {
        failQueryId("GlQueryDevice", call, id,
                    issued ? "is not in flight (already taken)" : "was never issued");
    }
    return false;
}

bool GlQueryDevice::pollReady(QueryId id) {
    bool ready = false;
    if (latency_.deterministic) {
        ready = commands_ - issued_at_[id] > latency_.latency_commands;
    } else {
        const auto start = Clock::now();
        GLuint available = GL_FALSE;
        OCCSIM_GL_CHECKED(
            glGetQueryObjectuiv(gl_queries_[id], GL_QUERY_RESULT_AVAILABLE, &available));
        counters_.poll_seconds += steadySecondsSince(start);
        ready = available == GL_TRUE;
    }
    if (ready) noteAnswered(id);
    return ready;
}

bool GlQueryDevice::isQueryReady(QueryId id) {
    if (!isLive(id, "isQueryReady")) return true;  // release builds: nothing to wait for
    return answered_[id] || pollReady(id);         // once ready, never polled again
}

QueryAnswer GlQueryDevice::takeAnswer(QueryId id) {
    // Release builds: a dead id is answered "visible" (the safe answer) and released nothing.
    if (!isLive(id, "takeAnswer")) return {};
    const bool ready = answered_[id] || pollReady(id);
    const auto start = Clock::now();
    GLuint64 samples = 0;
    OCCSIM_GL_CHECKED(glGetQueryObjectui64v(gl_queries_[id], GL_QUERY_RESULT, &samples));
    if (!ready) {
        // Waited for: the answer arrived with as many commands after the query as there are now.
        noteAnswered(id);
        ++counters_.results_waited;
        counters_.wait_seconds += steadySecondsSince(start);
    } else {
        counters_.poll_seconds += steadySecondsSince(start);
    }
    ++counters_.results_fetched;
    ++counters_.read_backs;
    retire(id);
    return {samples > 0 || near_eye_[id] != 0, samples, !ready};
}

}  // namespace occsim
