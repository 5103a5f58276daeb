// RenderDevice over real OpenGL occlusion queries (GL_SAMPLES_PASSED). Query objects come from a
// pool that grows as needed and is reused; an id stays valid across frames until its result is
// fetched. Draw and query submission time and blocked time are measured here, so cullers need not.
#pragma once

#include "occsim/culling/contract/render_device.h"
#include "render/gl_renderer.h"

#include <cstdint>
#include <vector>

namespace occsim {

class GlQueryDevice final : public RenderDevice {
public:
    GlQueryDevice(GlRenderer& renderer, LatencyMode latency);
    ~GlQueryDevice() override;
    GlQueryDevice(const GlQueryDevice&) = delete;
    GlQueryDevice& operator=(const GlQueryDevice&) = delete;

    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override;
    bool isQueryReady(QueryId id) override;
    uint64_t queryResult(QueryId id) override;

    uint32_t queriesInFlight() const;

private:
    GlRenderer& renderer_;
    LatencyMode latency_;
    uint64_t commands_ = 0;               // draws and queries submitted so far
    std::vector<uint32_t> gl_queries_;    // QueryId -> GL query object
    std::vector<uint64_t> issued_at_;     // QueryId -> commands_ when issued
    std::vector<QueryId> free_ids_;
};

}  // namespace occsim
