// Reading objects.sqlite back: the configurations and objects of a run, one object's decisions,
// and the over-drawn and missed objects of a configuration. Shared by the recorder (report.md's
// highlights, read from the file it just wrote) and `occsim why`.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "occsim/culling/contract/decision_log.h"
#include "sim/output/object_highlights.h"
#include "sim/record/sqlite.h"
#include "sim/run/deciding_node.h"

namespace occsim {

// The table a view's decisions are in (docs/objects.md): the camera's `decisions` (in a stereo
// run culled per eye, the left eye's), `right_eye_decisions` (the right eye's, per eye) or
// `light_decisions` (a light's view culled by the culler). The light's rows read as the camera's:
// truth_pixels its shadow_pixels, error_pixels its missed_shadow_pixels, tie_pixels 0.
enum class RecordedView : uint8_t { Camera, RightEye, Light };

struct RecordedConfig {
    uint32_t id = 0;
    std::string label;
    std::string algorithm;
    // Objects ground truth saw and this configuration did not draw, summed over the frames of
    // the repetitions after the first (which have no rows).
    uint64_t missed_in_later_repetitions = 0;
};

struct RecordedObject {
    uint32_t index = 0;
    std::string name;
    uint32_t triangles = 0;
    bool moving = false;
};

// One row of `decisions`: a configuration's decision on an object in a frame.
struct RecordedDecision {
    uint32_t frame = 0;
    uint32_t config = 0;
    bool drawn = false;
    Decision why;
    uint32_t truth_pixels = 0, error_pixels = 0, tie_pixels = 0;
    // The node whose record decided it (decisions.node and node_kind); None when it was decided
    // for itself.
    uint32_t node = 0;
    DecidingNode node_kind = DecidingNode::None;
};

// An object decided with a node in a frame, and what ground truth saw of it.
struct NodeMember {
    uint32_t object = 0;
    std::string name;
    bool drawn = false;
    uint32_t truth_pixels = 0;
};

// An answer recorded for a node: the frame it decided, and its row's reason and query.
struct NodeAnswer {
    uint32_t frame = 0;
    bool visible = false;
    uint32_t query_frame = Decision::kNoFrame;
    uint32_t samples = 0;
};

std::vector<RecordedConfig> recordedConfigs(sql::Database& db);
std::optional<RecordedObject> recordedObject(sql::Database& db, uint32_t index);
// The objects of that name, by index.
std::vector<RecordedObject> recordedObjectsNamed(sql::Database& db, const std::string& name);
uint32_t recordedObjectCount(sql::Database& db);
// Whether the view's table has a row (a run that recorded that view).
bool recordedViewHasRows(sql::Database& db, RecordedView view);

// The object's rows for one configuration, by frame; `frame` limits them to that frame.
std::vector<RecordedDecision> recordedDecisions(sql::Database& db, uint32_t object, uint32_t config,
                                                std::optional<uint32_t> frame = {},
                                                RecordedView view = RecordedView::Camera);

// The objects the configuration decided with `node` in `frame`, by index (rows only: an object
// frustum culled and unseen has none).
std::vector<NodeMember> nodeMembers(sql::Database& db, uint32_t config, uint32_t frame,
                                    uint32_t node, RecordedView view = RecordedView::Camera);
// The last answer recorded for `node` before `frame`, and the first at or after it.
std::optional<NodeAnswer> answerBefore(sql::Database& db, uint32_t config, uint32_t node,
                                       uint32_t frame, RecordedView view = RecordedView::Camera);
std::optional<NodeAnswer> answerFrom(sql::Database& db, uint32_t config, uint32_t node,
                                     uint32_t frame, RecordedView view = RecordedView::Camera);

// Every object the configuration drew while ground truth saw none of it, the most triangles drawn
// that way (triangles x frames) first.
std::vector<OverdrawnObject> overdrawnObjects(sql::Database& db, const RecordedConfig& config,
                                              RecordedView view = RecordedView::Camera);
// Every object ground truth saw that the configuration did not draw, by index.
std::vector<MissedObject> missedObjects(sql::Database& db, const RecordedConfig& config,
                                        RecordedView view = RecordedView::Camera);

}  // namespace occsim
