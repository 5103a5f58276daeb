#include "sim/record/object_queries.h"

#include <algorithm>
#include <string>

namespace occsim {
namespace {

RecordedObject objectOf(const sql::Statement& s) {
    RecordedObject o;
    o.index = static_cast<uint32_t>(s.integer(0));
    o.name = s.text(1);
    o.triangles = static_cast<uint32_t>(s.integer(2));
    o.moving = s.integer(3) != 0;
    return o;
}

constexpr const char* kObjectColumns = "SELECT object, name, triangles, moving FROM objects ";

uint32_t optionalInteger(const sql::Statement& s, int column, uint32_t none) {
    return s.isNull(column) ? none : static_cast<uint32_t>(s.integer(column));
}

// A view's table, and its pixel columns as the camera's names (RecordedView).
std::string tableOf(RecordedView view) {
    switch (view) {
        case RecordedView::RightEye:
            return "right_eye_decisions";
        case RecordedView::Light:
            return "(SELECT *, shadow_pixels AS truth_pixels, missed_shadow_pixels AS "
                   "error_pixels, 0 AS tie_pixels FROM light_decisions)";
        default:
            return "decisions";
    }
}

}  // namespace

std::vector<RecordedConfig> recordedConfigs(sql::Database& db) {
    sql::Statement s = db.prepare(
        "SELECT config, label, algorithm, missed_in_later_repetitions FROM configurations "
        "ORDER BY config");
    std::vector<RecordedConfig> out;
    while (s.step()) {
        out.push_back({static_cast<uint32_t>(s.integer(0)), s.text(1), s.text(2),
                       static_cast<uint64_t>(s.integer(3))});
    }
    return out;
}

std::optional<RecordedObject> recordedObject(sql::Database& db, uint32_t index) {
    sql::Statement s = db.prepare(std::string(kObjectColumns) + "WHERE object = ?");
    s.bind(1, index);
    if (!s.step()) return std::nullopt;
    return objectOf(s);
}

std::vector<RecordedObject> recordedObjectsNamed(sql::Database& db, const std::string& name) {
    sql::Statement s = db.prepare(std::string(kObjectColumns) + "WHERE name = ? ORDER BY object");
    s.bind(1, std::string_view(name));
    std::vector<RecordedObject> out;
    while (s.step()) out.push_back(objectOf(s));
    return out;
}

uint32_t recordedObjectCount(sql::Database& db) {
    sql::Statement s = db.prepare("SELECT COUNT(*) FROM objects");
    s.step();
    return static_cast<uint32_t>(s.integer(0));
}

bool recordedViewHasRows(sql::Database& db, RecordedView view) {
    sql::Statement s = db.prepare("SELECT EXISTS (SELECT 1 FROM " + tableOf(view) + ")");
    s.step();
    return s.integer(0) != 0;
}

std::vector<RecordedDecision> recordedDecisions(sql::Database& db, uint32_t object, uint32_t config,
                                                std::optional<uint32_t> frame, RecordedView view) {
    sql::Statement s = db.prepare(
        "SELECT frame, drawn, reason, query_frame, samples, flags, phase, level, interval, "
        "next_query, next_query_frame, visible_answers, history, truth_pixels, error_pixels, "
        "tie_pixels, node, node_kind FROM " +
        tableOf(view) +
        " WHERE object = ?1 AND config = ?2 AND (?3 IS NULL OR frame = ?3) ORDER BY frame");
    s.bind(1, object).bind(2, config).bind(3, frame);
    std::vector<RecordedDecision> out;
    while (s.step()) {
        RecordedDecision r;
        r.frame = static_cast<uint32_t>(s.integer(0));
        r.config = config;
        r.drawn = s.integer(1) != 0;
        Decision& d = r.why;
        d.kind = static_cast<DecisionKind>(s.integer(2));
        d.query_frame = optionalInteger(s, 3, Decision::kNoFrame);
        d.samples = optionalInteger(s, 4, 0);
        d.flags = static_cast<uint8_t>(s.integer(5));
        d.phase = static_cast<uint8_t>(optionalInteger(s, 6, 0));
        d.level = static_cast<uint8_t>(optionalInteger(s, 7, Decision::kNoLevel));
        d.interval = static_cast<float>(s.real(8));
        d.next_query = static_cast<float>(s.real(9));
        d.next_query_frame = optionalInteger(s, 10, Decision::kNoFrame);
        d.count = static_cast<uint8_t>(optionalInteger(s, 11, 0));
        d.history = static_cast<uint8_t>(optionalInteger(s, 12, 0));
        r.truth_pixels = static_cast<uint32_t>(s.integer(13));
        r.error_pixels = static_cast<uint32_t>(s.integer(14));
        r.tie_pixels = static_cast<uint32_t>(s.integer(15));
        r.node = optionalInteger(s, 16, 0);
        r.node_kind = static_cast<DecidingNode>(optionalInteger(s, 17, 0));
        out.push_back(r);
    }
    return out;
}

std::vector<NodeMember> nodeMembers(sql::Database& db, uint32_t config, uint32_t frame,
                                    uint32_t node, RecordedView view) {
    sql::Statement s =
        db.prepare("SELECT d.object, o.name, d.drawn, d.truth_pixels FROM " + tableOf(view) +
                   " d JOIN objects o ON o.object = d.object "
                   "WHERE d.config = ?1 AND d.node = ?2 AND d.frame = ?3 "
                   "ORDER BY d.object");
    s.bind(1, config).bind(2, node).bind(3, frame);
    std::vector<NodeMember> out;
    while (s.step()) {
        out.push_back({static_cast<uint32_t>(s.integer(0)), s.text(1), s.integer(2) != 0,
                       static_cast<uint32_t>(s.integer(3))});
    }
    return out;
}

namespace {

// The answers are the rows `culled on query` (2) and `drawn on query` (3).
std::optional<NodeAnswer> nodeAnswer(sql::Database& db, const char* where_and_order,
                                     uint32_t config, uint32_t node, uint32_t frame,
                                     RecordedView view) {
    sql::Statement s =
        db.prepare("SELECT frame, reason, query_frame, samples FROM " + tableOf(view) +
                   " WHERE config = ?1 AND node = ?2 AND reason IN (2, 3) AND " + where_and_order +
                   " LIMIT 1");
    s.bind(1, config).bind(2, node).bind(3, frame);
    if (!s.step()) return std::nullopt;
    NodeAnswer a;
    a.frame = static_cast<uint32_t>(s.integer(0));
    a.visible = static_cast<DecisionKind>(s.integer(1)) == DecisionKind::DrawnOnQuery;
    a.query_frame = optionalInteger(s, 2, Decision::kNoFrame);
    a.samples = optionalInteger(s, 3, 0);
    return a;
}

}  // namespace

std::optional<NodeAnswer> answerBefore(sql::Database& db, uint32_t config, uint32_t node,
                                       uint32_t frame, RecordedView view) {
    return nodeAnswer(db, "frame < ?3 ORDER BY frame DESC", config, node, frame, view);
}

std::optional<NodeAnswer> answerFrom(sql::Database& db, uint32_t config, uint32_t node,
                                     uint32_t frame, RecordedView view) {
    return nodeAnswer(db, "frame >= ?3 ORDER BY frame", config, node, frame, view);
}

std::vector<OverdrawnObject> overdrawnObjects(sql::Database& db, const RecordedConfig& config,
                                              RecordedView view) {
    sql::Statement s =
        db.prepare("SELECT d.object, o.name, o.triangles, d.frame FROM " + tableOf(view) +
                   " d JOIN objects o ON o.object = d.object WHERE d.config = ? AND d.drawn = 1 "
                   "AND d.truth_pixels = 0 ORDER BY d.object, d.frame");
    s.bind(1, config.id);
    std::vector<OverdrawnObject> out;
    uint32_t streak = 0, streak_first = 0, last_frame = 0;
    while (s.step()) {
        const auto object = static_cast<uint32_t>(s.integer(0));
        const auto frame = static_cast<uint32_t>(s.integer(3));
        if (out.empty() || out.back().object != object) {
            OverdrawnObject o;
            o.config = config.label;
            o.object = object;
            o.name = s.text(1);
            o.triangles = static_cast<uint32_t>(s.integer(2));
            out.push_back(o);
            streak = 0;
        }
        OverdrawnObject& o = out.back();
        ++o.frames;
        if (streak > 0 && frame == last_frame + 1) {
            ++streak;
        } else {
            streak = 1;
            streak_first = frame;
        }
        last_frame = frame;
        if (streak > o.longest_streak) {
            o.longest_streak = streak;
            o.streak_first = streak_first;
        }
    }
    std::sort(out.begin(), out.end(), [](const OverdrawnObject& a, const OverdrawnObject& b) {
        const uint64_t ta = uint64_t{a.triangles} * a.frames, tb = uint64_t{b.triangles} * b.frames;
        return ta != tb ? ta > tb : a.object < b.object;
    });
    return out;
}

std::vector<MissedObject> missedObjects(sql::Database& db, const RecordedConfig& config,
                                        RecordedView view) {
    sql::Statement s =
        db.prepare("SELECT d.object, o.name, d.frame, d.error_pixels FROM " + tableOf(view) +
                   " d JOIN objects o ON o.object = d.object WHERE d.config = ? AND d.drawn = 0 "
                   "AND d.truth_pixels > 0 ORDER BY d.object, d.frame");
    s.bind(1, config.id);
    std::vector<MissedObject> out;
    while (s.step()) {
        const auto object = static_cast<uint32_t>(s.integer(0));
        if (out.empty() || out.back().object != object) {
            MissedObject m;
            m.config = config.label;
            m.object = object;
            m.name = s.text(1);
            out.push_back(m);
        }
        out.back().frames.push_back(static_cast<uint32_t>(s.integer(2)));
        out.back().error_pixels += static_cast<uint64_t>(s.integer(3));
    }
    return out;
}

}  // namespace occsim
