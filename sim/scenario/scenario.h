// A scenario: everything one headless run needs, parsed strictly from a JSON file (see
// docs/scenario-format.md). Units: seconds, metres, degrees, pixels. Every field has the default
// documented there; parseScenario() rejects unknown keys, wrong types, out-of-range values,
// NaN/infinite numbers and missing files with a ScenarioError naming the file and JSON pointer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "occsim/culling/geometry/aabb.h"
#include "occsim/culling/registry/culler_options.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "sim/scenario/errors.h"
#include "sim/scenario/scene_specs.h"
#include "sim/scenario/segments.h"
#include "sim/scenario/view_specs.h"

namespace occsim {

struct CameraKeyframe {
    double time_s = 0.0;
    glm::dvec3 position{0.0};
    glm::dvec3 target{0.0, 0.0, -1.0};
};

struct CameraSpec {
    double fov_y_deg = 60.0;  // vertical field of view, (0, 180)
    double near_m = 0.1;
    double far_m = 1000.0;
    // At least one, times strictly increasing. Given directly, or made by the parser from the
    // "orbit" and "fly" helpers (docs/scenario-format.md).
    std::vector<CameraKeyframe> keyframes;
    bool loop = false;  // wrap around after the last keyframe (whose pose should equal the first)
};

enum class MotionType : uint8_t { Bounce, Orbit, Path, RandomWalk, Spin };

// Which objects a mover spec moves: a share of a source's objects, listed objects of a source, or
// new objects it spawns.
enum class MoverSelection : uint8_t { Fraction, Objects, Spawn };

enum class SpawnShape : uint8_t { Teapot, Box, Sphere };

struct SpawnSpec {
    uint32_t count = 0;
    SpawnShape shape = SpawnShape::Teapot;
    double size_min_m = 1.0;  // height of each spawned object; a model's scale factor
    double size_max_m = 2.0;
    // "model": spawn copies of this glTF source's model instead of a shape (each copy moves as
    // one rigid body about its origin, and plays the source's animations).
    int32_t model_source = -1;
};

struct MoverSpec {
    uint32_t source = 0;  // index into scene.sources: whose objects, region and lanes
    MoverSelection selection = MoverSelection::Fraction;
    double fraction = 0.0;          // Fraction: share of the source's objects, [0, 1]
    std::vector<uint32_t> objects;  // Objects: indices within the source
    SpawnSpec spawn;                // Spawn
    // A glTF source's copies, each moved as one rigid body about its origin: the fraction is a
    // share of its copies, the objects are copy indices.
    bool whole_copies = false;
    MotionType motion = MotionType::Bounce;
    double speed_min_mps = 1.0;
    double speed_max_mps = 4.0;
    // Bounce and random walk: the box movers stay in (default: the source's region).
    bool has_region = false;
    WorldBox region;
    double radius_min_m = 2.0;  // orbit
    double radius_max_m = 8.0;
    std::vector<glm::dvec3> waypoints;  // path: a closed loop; empty = the source's lanes
    double turn_rate_deg_s = 90.0;      // random walk: largest heading change per second
    double spin_min_deg_s = 30.0;       // spin: angular speed about the vertical axis
    double spin_max_deg_s = 180.0;
};

// What a regression run checks (docs/regression.md): the scenario's "expect" block.
struct RatioExpectation {
    std::string algorithm;  // numerator: its mean frame time
    std::string reference;  // denominator
    double max = 1.0;       // the ratio must be <= max * (1 + tolerance)
    double tolerance = 0.0;
    std::string segment;  // the means over this segment's frames; empty: the whole run
};

// A check of error scoped to one segment of the scenario: zero error pixels and no missed object
// on its frames (max_pixels unset), or at most max_pixels error pixels on any of its frames.
struct SegmentErrorExpectation {
    std::string algorithm;
    std::string segment;
    std::optional<int64_t> max_pixels;
};

struct Expectations {
    std::vector<std::string> algorithms;  // run these (default: vfc and the scenario's algorithm)
    uint32_t deterministic_latency = 8;   // draw calls before a query result counts as ready
    std::optional<uint32_t> frames;       // default: the scenario's
    std::vector<std::string> zero_error;  // must show 0 error pixels on every frame
    std::map<std::string, int64_t> max_error_pixels;  // per-frame bound for approximate ones
    std::vector<RatioExpectation> ratios;
    // zero_error and max_error_pixels entries that name a segment, in the order written.
    std::vector<SegmentErrorExpectation> segment_errors;
    std::filesystem::path baseline;  // default: <scenario stem>.baseline.json beside it
};

struct Scenario {
    std::filesystem::path file;  // where it was read from (paths inside resolve against it)
    std::string name;            // default: the file name without extension
    uint64_t seed = 1;
    uint32_t frames = 300;
    double dt_s = 1.0 / 30.0;  // simulation time step
    // The simulation clock at frame 0. Camera keyframes and movers count from the start of the
    // run; only the clock that culling decisions see is offset (a long-running simulation).
    double start_time_s = 0.0;
    uint32_t warmup_frames = 10;  // excluded from timing summaries (not from error counts)
    uint32_t width = 640;
    uint32_t height = 480;
    // Depth as most engines once stored it (near to -1, 24-bit fixed point) instead of reverse-Z
    // in float: only to show the depth-precision trap (docs/stability.md).
    bool conventional_depth = false;
    CameraSpec camera;
    // The views besides the camera's ("lights", "stereo"): read and checked; docs/views.md says
    // what a run does with them.
    std::vector<LightSpec> lights;
    std::optional<StereoSpec> stereo;
    std::vector<SceneSourceSpec> sources;
    std::vector<MoverSpec> movers;
    // Plugins the scenario loads ("plugins"), resolved against its folder; loaded by the parser.
    std::vector<std::filesystem::path> plugins;
    std::string algorithm =
        "statistical";  // a registered culler (occsim/culling/registry/registry.h)
    CullerOptions culler;
    BspBuildOptions bsp;
    // Named stretches of the run ("segments"), every figure also given over each.
    std::vector<SegmentSpec> segments;
    std::optional<Expectations> expect;  // present when the file has an "expect" block
};

// The number of objects a source builds when its spec alone tells (a teapot field); nullopt when
// only building it tells (generators, glTF files).
std::optional<uint32_t> knownObjectCount(const SceneSourceSpec& source);

// Mover object indices are checked where the source's object count is known: by the parser for
// sources whose spec tells it, by the scene builder for the others, both through this one check.
// Throws ScenarioError at /movers/<mover>/objects/<item>.
void checkMoverObjectIndex(const Scenario& scenario, size_t mover, size_t item,
                           uint32_t source_object_count);

// Throws ScenarioError.
Scenario parseScenarioFile(const std::filesystem::path& file);
Scenario parseScenarioText(const std::string& text, const std::filesystem::path& file);

}  // namespace occsim
