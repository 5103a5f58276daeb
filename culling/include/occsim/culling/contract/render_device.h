// The only door from a culler to the renderer. Culling code draws objects and issues occlusion
// queries through this interface and never sees OpenGL; render/ implements it with real GL
// queries, occsim/culling/testing/scripted_query_device.h with a known visibility function for
// tests.
//
// Query semantics (GL_SAMPLES_PASSED on bounding boxes):
// - issueQuery() rasterises the given boxes with colour and depth writes off against the depth
//   buffer as it is now, without waiting, and returns an id. Several boxes make one multiquery
//   whose result is the sum over its boxes. The subjects say what the query decides (a node, the
//   objects stored in a node itself, one object; a multiquery over several nodes names each):
//   devices that draw ignore them, devices that record (TracingDevice) keep them, so a picture of
//   the frame knows what every query was for without guessing from its boxes.
// - isQueryReady() never blocks. Results become ready in issue order. Once it said yes for an id
//   it says yes without asking the driver again: a device remembers what its poll learned, so an
//   answer is polled at most until it is known to be ready, and never again by takeAnswer().
// - takeAnswer() returns the answer (QueryAnswer), blocking until it is available; the blocked
//   time is counted as wait time. The device decides `visible` (a decorator may apply a pixel
//   threshold), so no caller compares sample counts, and says whether the caller waited, so no
//   caller compares counters. The id is released by this call; an id is valid across frames
//   until then. Taking an id twice, or one never issued, is a programming error: debug builds
//   abort with a message naming the device and the id (query_id_check.h), and no build releases
//   an id twice.
// - counters() are the device's true figures: a decorator reports those of the device it wraps
//   (which does the work), so no caller ever needs to reach past a decorator.
#pragma once

#include <cstdint>
#include <span>

#include "occsim/culling/contract/gpu_driven_draws.h"
#include "occsim/culling/geometry/aabb.h"

namespace occsim {

using QueryId = uint32_t;

class ConditionalRendering;  // occsim/culling/contract/conditional_rendering.h
class DepthPyramid;          // occsim/culling/contract/depth_pyramid.h

// Optional capabilities of a device, as bits: a culler names those it needs
// (CullerRow::device_needs) and a run refuses it before any work on a device without them.
enum DeviceFeature : uint32_t {
    kConditionalRendering = 1u << 0,  // draws that the device skips on a query's result
    kDepthPyramid = 1u << 1,          // a hierarchical depth buffer that tests boxes
    kGpuDrivenDraws = 1u << 2,        // indirect draws written and decided on the device
    kBoxRaster = 1u << 3,             // GPU-driven draws that test boxes by rasterising them
};

// What one query decides. `index` is a node for Node and NodeObjects, an object for Object.
struct QueryTag {
    enum class Subject : uint8_t {
        Node,         // the node's subtree (its bounds, or a tighter cover of them)
        NodeObjects,  // only the objects stored in the node itself (a "virtual leaf")
        Object,       // one object
    };
    static constexpr uint32_t kUntagged = UINT32_MAX;

    Subject subject = Subject::Node;
    uint32_t index = kUntagged;

    static QueryTag node(uint32_t n) { return {Subject::Node, n}; }
    static QueryTag nodeObjects(uint32_t n) { return {Subject::NodeObjects, n}; }
    static QueryTag object(uint32_t o) { return {Subject::Object, o}; }
    bool operator==(const QueryTag&) const = default;
};

// The answer to one query, as takeAnswer() hands it over.
struct QueryAnswer {
    bool visible = true;  // the subject counts as visible (decided by the device, never the culler)
    uint64_t samples = 0;  // the samples the answer rests on (the query's, or a stale one's)
    bool waited = false;   // it was not ready when taken: the caller blocked for it
};

struct DeviceCounters {
    uint64_t objects_drawn = 0;
    uint64_t triangles_drawn = 0;
    // Of objects_drawn, those submitted under a query's condition (conditional_rendering.h): the
    // device may have skipped them, which only it knows.
    uint64_t conditional_draws = 0;
    uint64_t queries_issued = 0;  // query objects (a multiquery counts once)
    uint64_t query_boxes = 0;     // boxes rasterised for queries
    uint64_t results_fetched = 0;
    uint64_t results_waited = 0;  // results fetched before they were ready (the caller blocked)
    double wait_seconds = 0.0;    // wall-clock time blocked in takeAnswer()
    double submit_seconds = 0.0;  // wall-clock time spent in draw and query submission
    // Wall-clock time asking whether answers are ready and fetching answers that were: on
    // llvmpipe a poll can flush the command stream, so it is the driver's time, not the culler's.
    double poll_seconds = 0.0;
    // The depth-pyramid capability (depth_pyramid.h): pyramids built, bounds tested against them.
    uint64_t pyramid_builds = 0;
    uint64_t pyramid_bounds = 0;
    // Reads of data the device computed (query results, pyramid flags) made during the frame:
    // each makes the CPU wait for the device's work so far. GPU-driven draws make none.
    uint64_t read_backs = 0;
};

class RenderDevice {
  public:
    virtual ~RenderDevice() = default;

    virtual void drawObject(uint32_t object) = 0;
    virtual QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) = 0;
    virtual bool isQueryReady(QueryId id) = 0;
    virtual QueryAnswer takeAnswer(QueryId id) = 0;

    QueryId issueQuery(const Aabb& box, QueryTag subject = {}) {
        return issueQuery(std::span<const Aabb>(&box, 1), std::span<const QueryTag>(&subject, 1));
    }

    // The optional capabilities (DeviceFeature): nullptr when the device lacks one. A decorator
    // hands over those of the device it wraps.
    virtual ConditionalRendering* conditionalRendering() { return nullptr; }
    virtual DepthPyramid* depthPyramid() { return nullptr; }
    virtual GpuDrivenDraws* gpuDrivenDraws() { return nullptr; }
    // The DeviceFeature bits of the capabilities above that are present.
    uint32_t features() {
        GpuDrivenDraws* gpu = gpuDrivenDraws();
        return (conditionalRendering() ? kConditionalRendering : 0u) |
               (depthPyramid() ? kDepthPyramid : 0u) | (gpu ? kGpuDrivenDraws : 0u) |
               (gpu && gpu->offersBoxRaster() ? kBoxRaster : 0u);
    }

    virtual const DeviceCounters& counters() const { return counters_; }
    virtual void resetCounters() { counters_ = {}; }

  protected:
    DeviceCounters counters_;
};

// Deterministic latency: a query result counts as ready only once `latency` commands (draws or
// queries) have been submitted after it; a caller that needs it sooner blocks. With latency
// disabled the device reports what the hardware reports.
struct LatencyMode {
    bool deterministic = false;
    uint32_t latency_commands = 8;
};

}  // namespace occsim
