#include "sim/record/object_recorder.h"

#include <stdexcept>

#include "occsim/culling/contract/decision_log.h"
#include "sim/record/object_queries.h"
#include "sim/record/object_schema.h"
#include "sim/record/sqlite.h"

namespace occsim {
namespace {

// A row that says nothing: the frustum culled it and ground truth has no pixel of it.
bool saysNothing(const ObjectFrame& f) {
    return !f.drawn && f.why.kind == DecisionKind::FrustumCulled && f.pixels.truth == 0 &&
           f.pixels.error == 0 && f.pixels.tie == 0;
}

bool answered(DecisionKind kind) {
    return kind == DecisionKind::CulledOnQuery || kind == DecisionKind::DrawnOnQuery;
}

constexpr const char* kInsertDecision =
    "INSERT INTO decisions (frame, config, object, drawn, reason, query_frame, samples, flags, "
    "phase, level, interval, next_query, next_query_frame, visible_answers, history, "
    "truth_pixels, error_pixels, tie_pixels, node, node_kind) "
    "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)";

constexpr const char* kInsertRightEyeDecision =
    "INSERT INTO right_eye_decisions (frame, config, object, drawn, reason, query_frame, "
    "samples, flags, phase, level, interval, next_query, next_query_frame, visible_answers, "
    "history, truth_pixels, error_pixels, tie_pixels, node, node_kind) "
    "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)";

constexpr const char* kInsertLightDecision =
    "INSERT INTO light_decisions (frame, config, object, drawn, reason, query_frame, samples, "
    "flags, phase, level, interval, next_query, next_query_frame, visible_answers, history, "
    "shadow_pixels, missed_shadow_pixels, light, node, node_kind) "
    "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)";

// One object's row of any of the three tables: they share columns 1-15 and 19-20; 16-18 are an
// eye's truth, error and tie pixels, or the light's shadow pixels, missed shadow pixels and light.
void insertRow(sql::Statement& s, uint32_t frame, uint32_t config, uint32_t object,
               const ObjectFrame& f, uint32_t third) {
    const Decision& d = f.why;
    const bool statistics = d.kind == DecisionKind::DrawnOnStatistics;
    s.bind(1, frame).bind(2, config).bind(3, object).bind(4, f.drawn);
    s.bind(5, static_cast<uint32_t>(d.kind));
    if (d.query_frame != Decision::kNoFrame) s.bind(6, d.query_frame);
    if (answered(d.kind)) s.bind(7, d.samples);
    s.bind(8, d.flags);
    if (d.phase != 0) s.bind(9, d.phase);
    if (d.level != Decision::kNoLevel) s.bind(10, d.level);
    if (statistics) {
        s.bind(11, static_cast<double>(d.interval));
        s.bind(12, static_cast<double>(d.next_query));
        s.bind(14, d.count);
        s.bind(15, d.history);
    }
    if (d.next_query_frame != Decision::kNoFrame) s.bind(13, d.next_query_frame);
    s.bind(16, f.pixels.truth).bind(17, f.pixels.error).bind(18, third);
    if (f.node_kind != DecidingNode::None) {
        s.bind(19, f.node).bind(20, static_cast<uint32_t>(f.node_kind));
    }
    s.run();
    s.reset();  // clears the bindings: the columns left unbound above are NULL
}

// The frames whose rows stay: all of them, or those before the frame a stop dropped.
uint32_t framesKept(const BenchResult& result) {
    if (result.partial && result.partial->repetition == 0) return result.partial->frames_reached;
    return result.metadata.frames;
}

}  // namespace

ObjectRecorder::ObjectRecorder(const std::filesystem::path& folder)
    : file_(folder / kObjectsDatabaseFile) {
    std::error_code ec;
    std::filesystem::remove(file_, ec);
    db_ = std::make_unique<sql::Database>(file_, sql::Database::Mode::Create);
    // The file is published only once it is closed (the run folder is staged), so nothing is
    // synced to disk on the way; the rollback journal keeps it readable if the run dies mid-frame.
    db_->exec("PRAGMA synchronous = OFF; PRAGMA journal_mode = TRUNCATE;");
    db_->exec(kObjectsSchema);
    sql::Statement reason =
        db_->prepare("INSERT INTO reasons (reason, name, draws) VALUES (?,?,?)");
    for (uint32_t k = 0; k < kDecisionKinds; ++k) {
        const auto kind = static_cast<DecisionKind>(k);
        const int draws = decisionKindDraws(kind);
        reason.bind(1, k).bind(2, decisionKindName(kind));
        if (draws < 0) {
            reason.bindNull(3);
        } else {
            reason.bind(3, draws);
        }
        reason.run();
        reason.reset();
    }
    insert_ = std::make_unique<sql::Statement>(db_->prepare(kInsertDecision));
    insert_right_eye_ = std::make_unique<sql::Statement>(db_->prepare(kInsertRightEyeDecision));
    insert_light_ = std::make_unique<sql::Statement>(db_->prepare(kInsertLightDecision));
}

ObjectRecorder::~ObjectRecorder() = default;

// The run's row (partial until finish() says otherwise) and its objects, from the first frame.
void ObjectRecorder::start(const FrameEvent& e) {
    started_ = true;
    const Scenario& s = e.scenario;
    db_->prepare(
           "INSERT INTO run (format_version, occsim_version, command, command_line, scenario, "
           "scenario_file, frames, frames_recorded, partial, partial_reason, dt_s, seed, width, "
           "height, deterministic_latency) VALUES (?, ?, '', '', ?, ?, ?, 0, 1, "
           "'the run has not finished', ?, ?, ?, ?, NULL)")
        .bind(1, kObjectsFormatVersion)
        .bind(2, std::string_view(OCCSIM_VERSION))
        .bind(3, std::string_view(s.name))
        .bind(4, std::string_view(s.file.string()))
        .bind(5, s.frames)
        .bind(6, s.dt_s)
        .bind(7, s.seed)
        .bind(8, s.width)
        .bind(9, s.height)
        .run();
    const Scene& scene = e.simulation.world().scene();
    std::vector<uint8_t> moving(scene.objectCount(), 0);
    for (uint32_t o : e.simulation.state().moved) {
        if (o < moving.size()) moving[o] = 1;
    }
    db_->exec("BEGIN");
    sql::Statement object =
        db_->prepare("INSERT INTO objects (object, name, triangles, moving) VALUES (?,?,?,?)");
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        const std::string name =
            o < scene.object_names.size() ? scene.object_names[o] : "object " + std::to_string(o);
        object.bind(1, o)
            .bind(2, std::string_view(name))
            .bind(3, scene.meshes[scene.object_mesh[o]].triangleCount())
            .bind(4, moving[o]);
        object.run();
        object.reset();
    }
    db_->exec("COMMIT");
}

uint32_t ObjectRecorder::configId(const RunConfig& config) {
    const auto found = configs_.find(config.label);
    if (found != configs_.end()) return found->second;
    const auto id = static_cast<uint32_t>(configs_.size());
    db_->prepare("INSERT INTO configurations (config, label, algorithm) VALUES (?, ?, ?)")
        .bind(1, id)
        .bind(2, std::string_view(config.label))
        .bind(3, std::string_view(config.algorithm ? config.algorithm->name : ""))
        .run();
    configs_.emplace(config.label, id);
    return id;
}

void ObjectRecorder::commitFrame() {
    db_->prepare("UPDATE run SET frames_recorded = ?").bind(1, frame_ + 1).run();
    db_->exec("COMMIT");
    in_frame_ = false;
}

void ObjectRecorder::onFrame(const FrameEvent& e) {
    const std::vector<ObjectFrame>& objects = e.simulation.objectFrames();
    if (!db_ || e.repetition != 0 || objects.empty()) return;
    if (!started_) start(e);
    if (in_frame_ && e.frame != frame_) commitFrame();
    if (!in_frame_) {
        db_->exec("BEGIN");
        in_frame_ = true;
        frame_ = e.frame;
    }
    const uint32_t config = configId(e.config);
    for (uint32_t o = 0; o < objects.size(); ++o) {
        if (!saysNothing(objects[o]))
            insertRow(*insert_, e.frame, config, o, objects[o], objects[o].pixels.tie);
    }
    const std::vector<ObjectFrame>& right = e.simulation.rightEyeObjectFrames();
    for (uint32_t o = 0; o < right.size(); ++o) {
        if (!saysNothing(right[o]))
            insertRow(*insert_right_eye_, e.frame, config, o, right[o], right[o].pixels.tie);
    }
    const std::vector<ObjectFrame>& casters = e.simulation.lightObjectFrames();
    const uint32_t light = e.simulation.recordedLight();
    for (uint32_t o = 0; o < casters.size(); ++o) {
        if (!saysNothing(casters[o]))
            insertRow(*insert_light_, e.frame, config, o, casters[o], light);
    }
}

ObjectHighlights ObjectRecorder::finish(const BenchResult& result, uint32_t overdrawn_per_config) {
    if (!db_) throw std::logic_error("ObjectRecorder::finish: called twice");
    const RunMetadata& m = result.metadata;
    if (!started_) {  // no frame was recorded: the run's row all the same
        db_->prepare(
               "INSERT INTO run (format_version, occsim_version, command, command_line, "
               "scenario, scenario_file, frames, frames_recorded, partial, partial_reason, dt_s, "
               "seed, width, height) VALUES (?, ?, '', '', ?, ?, ?, 0, 1, '', ?, ?, ?, ?)")
            .bind(1, kObjectsFormatVersion)
            .bind(2, std::string_view(OCCSIM_VERSION))
            .bind(3, std::string_view(m.scenario_name))
            .bind(4, std::string_view(m.scenario_file))
            .bind(5, m.frames)
            .bind(6, m.dt_s)
            .bind(7, m.seed)
            .bind(8, m.width)
            .bind(9, m.height)
            .run();
    }
    if (in_frame_) commitFrame();
    const uint32_t kept = started_ ? framesKept(result) : 0;
    db_->exec("BEGIN");
    db_->prepare("DELETE FROM decisions WHERE frame >= ?").bind(1, kept).run();
    db_->prepare("DELETE FROM right_eye_decisions WHERE frame >= ?").bind(1, kept).run();
    db_->prepare("DELETE FROM light_decisions WHERE frame >= ?").bind(1, kept).run();
    db_->prepare(
           "UPDATE run SET command = ?, command_line = ?, frames = ?, frames_recorded = ?, "
           "partial = ?, partial_reason = ?, deterministic_latency = ?")
        .bind(1, std::string_view(m.command))
        .bind(2, std::string_view(m.command_line))
        .bind(3, m.frames)
        .bind(4, kept)
        .bind(5, result.partial.has_value())
        .bind(6, std::string_view(result.partial ? partialLine(result) : std::string()))
        .bind(7, m.deterministic_latency)
        .run();
    db_->prepare("UPDATE run SET repetitions = ?").bind(1, m.repetitions).run();
    {  // finalised before the file is closed
        sql::Statement later = db_->prepare(
            "UPDATE configurations SET missed_in_later_repetitions = ? WHERE label = ?");
        for (const RunRecord& r : result.runs) {
            int64_t missed = 0;  // each later repetition's summary, as summary.json sums them
            for (size_t k = 1; k < r.repetitions.size(); ++k) {
                missed += r.repetitions[k].missed_objects_total;
            }
            later.bind(1, missed).bind(2, std::string_view(r.summary.label));
            later.run();
            later.reset();
        }
    }
    db_->exec(kObjectsIndexes);
    db_->exec("COMMIT");

    ObjectHighlights h;
    h.overdrawn_per_config = overdrawn_per_config;
    h.repetitions = m.repetitions;
    // A stereo run culled per eye: the right eye's beside the left eye's (`decisions`), each
    // named for its eye.
    const bool per_eye = recordedViewHasRows(*db_, RecordedView::RightEye);
    for (const RecordedConfig& c : recordedConfigs(*db_)) {
        if (m.repetitions > 1) h.later_misses.push_back({c.label, c.missed_in_later_repetitions});
        for (const RecordedView view : {RecordedView::Camera, RecordedView::RightEye}) {
            if (view == RecordedView::RightEye && !per_eye) continue;
            const std::string eye = !per_eye                       ? ""
                                    : view == RecordedView::Camera ? " (left eye)"
                                                                   : " (right eye)";
            std::vector<OverdrawnObject> over = overdrawnObjects(*db_, c, view);
            if (over.size() > overdrawn_per_config) over.resize(overdrawn_per_config);
            for (OverdrawnObject& o : over) o.config += eye;
            h.overdrawn.insert(h.overdrawn.end(), over.begin(), over.end());
            std::vector<MissedObject> missed = missedObjects(*db_, c, view);
            for (MissedObject& o : missed) o.config += eye;
            h.missed.insert(h.missed.end(), missed.begin(), missed.end());
        }
    }
    insert_.reset();
    insert_right_eye_.reset();
    insert_light_.reset();
    db_->exec("PRAGMA journal_mode = DELETE");  // removes the journal file beside it
    db_->close();
    db_.reset();
    return h;
}

}  // namespace occsim
