#include "sim/record/why.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "occsim/culling/contract/input_error.h"
#include "sim/output/atomic_file.h"
#include "sim/output/object_highlights.h"
#include "sim/record/object_database.h"
#include "sim/scenario/json_reader.h"

namespace occsim {
namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

// "at frame 176 (2 frames before)", "this frame".
std::string queryFrame(uint32_t query_frame, uint32_t frame) {
    if (query_frame == frame) return "this frame";
    std::string s = "at frame " + std::to_string(query_frame);
    if (query_frame < frame) {
        const uint32_t age = frame - query_frame;
        s += " (" + std::to_string(age) + (age == 1 ? " frame" : " frames") + " before)";
    }
    return s;
}

std::string samples(const Decision& d) {
    return " (" + std::to_string(d.samples) + (d.samples == 1 ? " sample" : " samples") +
           ((d.flags & kDecisionWaited) ? ", waited for" : "") + ")";
}

// The reason's words, after "drawn: " or "not drawn: ".
std::string reasonWords(const Decision& d, uint32_t frame, bool drawn) {
    const std::string q = queryFrame(d.query_frame, frame);
    std::string s;
    switch (d.kind) {
        case DecisionKind::NoReasonGiven:
            s = "its culler gave no reason";
            break;
        case DecisionKind::FrustumCulled:
            s = "its box is outside the view frustum";
            break;
        case DecisionKind::CulledOnQuery:
        case DecisionKind::DrawnOnQuery:
            s = std::string((d.flags & kDecisionMultiquery) ? "the multiquery" : "the query") +
                " issued " + q + " answered " +
                (d.kind == DecisionKind::CulledOnQuery ? "occluded" : "visible") + samples(d);
            if (d.next_query_frame != Decision::kNoFrame && d.next_query_frame > frame)
                s += "; next query at frame " + std::to_string(d.next_query_frame);
            break;
        case DecisionKind::DrawnOnStatistics: {
            const bool metres = (d.flags & kDecisionDistance) != 0;
            s = "no query: its last query, issued " + q + ", found it visible (" +
                std::to_string(d.count) + " of its last " + std::to_string(d.history) +
                " answers visible); the decay curve gives " + number(d.interval) +
                (metres ? " m of travel" : " s") + ", so it is queried again after " +
                number(d.next_query) + (metres ? " m" : " s");
            break;
        }
        case DecisionKind::DrawnOnCostModel:
            s = "the cost model put its query off (drawing it was estimated to cost less than "
                "querying it)";
            break;
        case DecisionKind::DrawnNearPlane:
            s = "the near plane may cut its box, so it is never tested";
            break;
        case DecisionKind::DrawnNoTest:
            s = (d.flags & kDecisionFallback)
                    ? "with no test (a fallback frame: frustum culling only)"
                    : "with no test";
            break;
        case DecisionKind::DrawnQueryInFlight:
            s = "while its query issued " + q + " is in flight";
            break;
        case DecisionKind::DrawnAssumedVisible:
            s = "assumed visible since its query issued " + q + " found it visible";
            if (d.next_query_frame != Decision::kNoFrame)
                s += "; tested again at frame " + std::to_string(d.next_query_frame);
            break;
        case DecisionKind::CulledOnPyramid:
            s = "the depth pyramid hides it (phase 2, level " + std::to_string(d.level) + ")";
            break;
        case DecisionKind::DrawnOnPyramid:
            if (d.phase == 1) {
                s = "in phase 1: it was visible last frame";
            } else if (d.flags & kDecisionNoPyramid) {
                s = "phase 1 drew nothing, so the pyramid hid nothing";
            } else if (d.level == Decision::kNoLevel) {
                s = "in phase 2: the pyramid could not test its bound";
            } else {
                s = "its bound passed the depth pyramid (phase 2, level " +
                    std::to_string(d.level) + ")";
            }
            break;
        case DecisionKind::CulledOnTiles:
            s = "its box failed the software depth buffer's tile test";
            break;
        case DecisionKind::DrawnOnTiles:
            s = "its box passed the software depth buffer's tile test";
            if (d.flags & kDecisionOccluder) s += ", and it was rasterised as an occluder";
            break;
        case DecisionKind::DrawnConditional:
            s = "submitted under the condition of its query issued " + q + ": the device " +
                (drawn ? "executed the draw" : "skipped it");
            break;
        case DecisionKind::DrawnByOracle:
            s = "ground truth saw it (the oracle draws exactly that)";
            break;
        case DecisionKind::CulledByOracle:
            s = "ground truth did not see it (the oracle draws only what it saw)";
            break;
        case DecisionKind::CulledOnBoxRaster:
            s = "no fragment of its box passed the depth test (phase 2)";
            break;
        case DecisionKind::DrawnOnBoxRaster:
            s = d.phase == 1 ? "in phase 1: it was visible last frame"
                             : "a fragment of its box passed the depth test (phase 2)";
            break;
    }
    if (d.flags & kDecisionNodeUnit) s += " (decided for its node)";
    return s;
}

std::string plural(uint64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

bool allDigits(const std::string& s) {
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string objectLabel(const RecordedObject& o) {
    return "object " + std::to_string(o.index) + " '" + o.name + "' (" +
           plural(o.triangles, "triangle", "triangles") + (o.moving ? ", moving" : "") + ")";
}

// --algo: a configuration's label, or every configuration of that algorithm.
std::vector<RecordedConfig> chosenConfigs(sql::Database& db, const std::string& algo) {
    const std::vector<RecordedConfig> all = recordedConfigs(db);
    if (algo.empty()) return all;
    std::vector<RecordedConfig> out;
    for (const RecordedConfig& c : all) {
        if (c.label == algo) return {c};
    }
    for (const RecordedConfig& c : all) {
        if (c.algorithm == algo) out.push_back(c);
    }
    if (out.empty()) {
        std::string names;
        for (const RecordedConfig& c : all) names += (names.empty() ? "" : ", ") + c.label;
        throw InputError("--algo " + algo + ": not in this run; expected one of: " +
                         (names.empty() ? "(none recorded)" : names));
    }
    return out;
}

// "5" or "5, 9, 12": the indices of objects, at most eight, then "...".
std::string someIndices(const std::vector<RecordedObject>& objects) {
    std::string some;
    for (size_t i = 0; i < objects.size() && i < 8; ++i)
        some += (i ? ", " : "") + std::to_string(objects[i].index);
    if (objects.size() > 8) some += ", ...";
    return some;
}

// --object: an index ("17", or "#17", which is never a name), else a name that one object has.
// Digits that are an index and also another object's name are refused, not guessed.
RecordedObject chosenObject(sql::Database& db, const std::string& text) {
    const bool marked = text.size() > 1 && text[0] == '#' && allDigits(text.substr(1));
    std::vector<RecordedObject> named;
    if (marked || allDigits(text)) {
        const std::string digits = marked ? text.substr(1) : text;
        const uint32_t count = recordedObjectCount(db);
        const unsigned long long index = digits.size() > 10 ? ~0ull : std::stoull(digits);
        std::optional<RecordedObject> indexed;
        if (index < count) indexed = recordedObject(db, static_cast<uint32_t>(index));
        if (!marked) named = recordedObjectsNamed(db, text);
        if (indexed && !named.empty() && !(named.size() == 1 && named[0].index == indexed->index)) {
            throw InputError("--object " + text + ": both object " + digits + " ('" +
                             indexed->name + "') and the name of " +
                             (named.size() == 1 ? "object " : "objects ") + someIndices(named) +
                             "; expected #" + digits + " for the index, or the named object's " +
                             "index");
        }
        if (indexed) return *indexed;
        if (named.empty()) {
            throw InputError("--object " + text + ": no such object; the run has " +
                             plural(count, "object", "objects") +
                             (count > 0 ? " (0-" + std::to_string(count - 1) + ")" : ""));
        }
    } else {
        named = recordedObjectsNamed(db, text);
    }
    if (named.size() == 1) return named.front();
    if (named.empty()) {
        std::vector<std::string> names;
        sql::Statement s = db.prepare("SELECT name FROM objects");
        while (s.step()) names.push_back(s.text(0));
        const auto near = closestMatch(text, names);
        throw InputError("--object '" + text + "': no object of that name" +
                         (near ? "; did you mean '" + *near + "'?"
                               : "; expected an object's index or its name"));
    }
    throw InputError("--object '" + text + "': names " + std::to_string(named.size()) +
                     " objects (" + someIndices(named) + "); expected one: give its index");
}

// The decision at `frame`: its row, or the row that was left out (frustum culled, unseen).
RecordedDecision decisionAt(sql::Database& db, uint32_t object, uint32_t config, uint32_t frame,
                            RecordedView view) {
    std::vector<RecordedDecision> rows = recordedDecisions(db, object, config, frame, view);
    if (!rows.empty()) return rows.front();
    RecordedDecision d;
    d.frame = frame;
    d.config = config;
    d.why.kind = DecisionKind::FrustumCulled;
    return d;
}

// Every line of `text` two more spaces in.
std::string indented(const std::string& text) {
    std::string out;
    size_t start = 0;
    while (start < text.size()) {
        const size_t end = text.find('\n', start);
        const size_t stop = end == std::string::npos ? text.size() : end + 1;
        out += "  " + text.substr(start, stop - start);
        start = stop;
    }
    return out;
}

// "leaf 57", "inner node 3", "inner node 3's own objects".
std::string nodeName(const RecordedDecision& d) {
    const std::string n = std::to_string(d.node);
    switch (d.node_kind) {
        case DecidingNode::Leaf:
            return "leaf " + n;
        case DecidingNode::Subtree:
            return "inner node " + n;
        default:
            return "inner node " + n + "'s own objects";
    }
}

std::string answerWords(const NodeAnswer& a, uint32_t frame) {
    std::string s = std::string(a.visible ? "visible" : "occluded") + " (" +
                    plural(a.samples, "sample", "samples") + ") at frame " +
                    std::to_string(a.frame);
    if (a.frame < frame) {
        const uint32_t age = frame - a.frame;
        s += " (" + plural(age, "frame", "frames") + " before)";
    } else if (a.frame > frame) {
        const uint32_t later = a.frame - frame;
        s += " (" + plural(later, "frame", "frames") + " later)";
    }
    if (a.query_frame != Decision::kNoFrame && a.query_frame != a.frame)
        s += ", to its query issued at frame " + std::to_string(a.query_frame);
    return s;
}

// Where a decision made with a node comes from: the node, the objects it held that frame (those
// ground truth saw marked), its last answer before the frame and its next one (when the decision
// was not itself an answer), and the bird's-eye picture of the frame. Empty for a decision made
// for the object itself.
std::string decisionCause(sql::Database& db, const WhyRequest& r, const RecordedConfig& c,
                          const RecordedDecision& d) {
    if (d.node_kind == DecidingNode::None) return "";
    std::ostringstream out;
    const std::vector<NodeMember> members = nodeMembers(db, c.id, d.frame, d.node, r.view);
    out << "  decided with " << nodeName(d) << ", which held "
        << plural(members.size(), "object", "objects") << " this frame:";
    constexpr size_t kListed = 6;
    uint32_t seen = 0;
    for (const NodeMember& m : members) seen += m.truth_pixels > 0;
    for (size_t i = 0; i < members.size() && i < kListed; ++i) {
        const NodeMember& m = members[i];
        out << (i ? ", " : " ") << "#" << m.object << " '" << m.name << "' ("
            << (m.truth_pixels > 0 ? "seen, " + std::to_string(m.truth_pixels) + " px"
                                   : std::string("unseen"))
            << ")";
    }
    if (members.size() > kListed) out << ", and " << members.size() - kListed << " more";
    out << "; ground truth saw " << seen << " of them\n";
    const bool answered =
        d.why.kind == DecisionKind::CulledOnQuery || d.why.kind == DecisionKind::DrawnOnQuery;
    bool visible_answer = d.why.kind == DecisionKind::DrawnOnQuery;
    if (!answered) {
        const std::optional<NodeAnswer> before = answerBefore(db, c.id, d.node, d.frame, r.view);
        const std::optional<NodeAnswer> next = answerFrom(db, c.id, d.node, d.frame, r.view);
        out << "  its last answer before: "
            << (before ? answerWords(*before, d.frame) : std::string("none recorded")) << "\n";
        if (next) out << "  its next answer: " << answerWords(*next, d.frame) << "\n";
        visible_answer = before && before->visible;
    }
    // The case the bird's-eye picture shows at a glance: the node's box passed where nothing it
    // holds is seen.
    if (visible_answer && seen == 0 && !members.empty()) {
        out << "  its box answered visible though ground truth saw none of its objects: the box "
               "reaches past what it holds\n";
    }
    // The bird's-eye picture is of the camera's culler (the left eye's, per eye).
    if (r.view != RecordedView::Camera) return out.str();
    char name[200];
    std::snprintf(name, sizeof name, "birds-eye-%s-frame-%05u.png", safeFileName(c.label).c_str(),
                  d.frame);
    out << "  from above: "
        << (std::filesystem::exists(r.run / name)
                ? (r.run / name).string()
                : "rerun the run with --birds-eye " + std::to_string(d.frame) +
                      " for the picture of this frame")
        << "\n";
    return out.str();
}

std::string oneObject(ObjectDatabase& base, const WhyRequest& r,
                      const std::vector<RecordedConfig>& configs, const RecordedObject& object) {
    sql::Database& db = base.db();
    std::ostringstream out;
    out << objectLabel(object) << "\n";
    if (r.frame) {
        for (const RecordedConfig& c : configs) {
            const RecordedDecision d = decisionAt(db, object.index, c.id, *r.frame, r.view);
            out << "frame " << *r.frame << ", " << c.label << ": " << describeDecision(d, r.view)
                << "\n"
                << decisionCause(db, r, c, d);
        }
        return out.str();
    }
    const uint32_t frames = base.run().frames_recorded;
    for (const RecordedConfig& c : configs) {
        const std::vector<RecordedDecision> rows =
            recordedDecisions(db, object.index, c.id, std::nullopt, r.view);
        std::vector<uint32_t> missed, hidden;
        uint32_t drawn = 0, seen = 0;
        uint64_t error = 0;
        for (const RecordedDecision& d : rows) {
            drawn += d.drawn;
            seen += d.truth_pixels > 0;
            if (!d.drawn && d.truth_pixels > 0) {
                missed.push_back(d.frame);
                error += d.error_pixels;
            }
            if (d.drawn && d.truth_pixels == 0) hidden.push_back(d.frame);
        }
        const bool light = r.view == RecordedView::Light;
        out << c.label << (light ? ": drawn into the shadow map on " : ": drawn on ") << drawn
            << " of " << frames
            << (light ? " frames; ground truth showed its shadow on "
                      : " frames; ground truth saw it on ")
            << seen << "; ";
        out << (missed.empty() ? "never missed"
                               : "missed on frames " + frameRanges(missed) + " (" +
                                     plural(error, light ? "shadow pixel" : "error pixel",
                                            light ? "shadow pixels" : "error pixels") +
                                     (light ? " left lit)" : ")"));
        out << "; "
            << (hidden.empty()
                    ? "never drawn while hidden"
                    : "drawn while hidden on " + plural(hidden.size(), "frame", "frames") + " (" +
                          frameRanges(hidden) + ")")
            << "\n";
        constexpr size_t kShown = 10;
        for (size_t i = 0; i < missed.size() && i < kShown; ++i) {
            const auto row = std::find_if(rows.begin(), rows.end(), [&](const RecordedDecision& d) {
                return d.frame == missed[i];
            });
            out << "  frame " << missed[i] << ", " << c.label << ": "
                << describeDecision(*row, r.view) << "\n";
            if (i == 0) out << indented(decisionCause(db, r, c, *row));
        }
        if (missed.size() > kShown)
            out << "  ... and " << missed.size() - kShown << " more missed frames (--frame N)\n";
        if (!hidden.empty()) {  // the first, with where it came from: over-draw has a cause too
            const auto row = std::find_if(rows.begin(), rows.end(), [&](const RecordedDecision& d) {
                return d.frame == hidden.front();
            });
            out << "  frame " << hidden.front() << ", " << c.label
                << " (first drawn while hidden): " << describeDecision(*row, r.view) << "\n"
                << indented(decisionCause(db, r, c, *row));
        }
    }
    return out.str();
}

std::string overdrawList(sql::Database& db, const std::vector<RecordedConfig>& configs,
                         uint32_t limit, RecordedView view) {
    std::ostringstream out;
    for (const RecordedConfig& c : configs) {
        const std::vector<OverdrawnObject> over = overdrawnObjects(db, c, view);
        out << c.label << ": " << plural(over.size(), "object", "objects")
            << (view == RecordedView::Light
                    ? " drawn into the shadow map while ground truth showed none of its shadow"
                    : " drawn while ground truth saw none of it");
        if (over.size() > limit) out << " (the " << limit << " with the most triangles drawn so)";
        out << "\n";
        for (size_t i = 0; i < over.size() && i < limit; ++i) {
            const OverdrawnObject& o = over[i];
            out << "  object " << o.object << " '" << o.name << "' ("
                << plural(o.triangles, "triangle", "triangles")
                << "): " << plural(o.frames, "frame", "frames") << ", longest streak "
                << o.longest_streak << " (frames " << o.streak_first << "-"
                << o.streak_first + o.longest_streak - 1 << "), "
                << uint64_t{o.triangles} * o.frames << " triangles in all\n";
        }
    }
    return out.str();
}

std::string missedList(sql::Database& db, const std::vector<RecordedConfig>& configs,
                       uint32_t repetitions, RecordedView view) {
    std::ostringstream out;
    for (const RecordedConfig& c : configs) {
        const std::vector<MissedObject> missed = missedObjects(db, c, view);
        out << c.label << ": " << plural(missed.size(), "object", "objects") << " missed";
        if (repetitions > 1) {
            out << " in repetition 1; "
                << laterRepetitionsNote(repetitions, c.missed_in_later_repetitions);
        }
        out << "\n";
        for (const MissedObject& m : missed) {
            out << "  object " << m.object << " '" << m.name << "': frames "
                << frameRanges(m.frames) << " ("
                << (view == RecordedView::Light
                        ? plural(m.error_pixels, "shadow pixel", "shadow pixels") + " left lit"
                        : plural(m.error_pixels, "error pixel", "error pixels"))
                << ")\n";
        }
    }
    return out.str();
}

}  // namespace

std::string describeDecision(const RecordedDecision& d, RecordedView view) {
    std::string s = d.drawn ? "drawn: " : "not drawn: ";
    s += reasonWords(d.why, d.frame, d.drawn);
    if (view == RecordedView::Light) {
        s += "; ground truth shadows " + std::to_string(d.truth_pixels) + " visible px through it";
        if (!d.drawn && d.truth_pixels > 0) {
            s += " (missed: " + plural(d.error_pixels, "shadow pixel", "shadow pixels") +
                 " left lit)";
        } else if (d.drawn && d.truth_pixels == 0) {
            s += " (drawn while its shadow falls on nothing visible)";
        }
        return s;
    }
    s += "; ground truth sees " + std::to_string(d.truth_pixels) + " px";
    if (!d.drawn && d.truth_pixels > 0) {
        s += " (missed: " + plural(d.error_pixels, "error pixel", "error pixels") + ")";
    } else if (d.drawn && d.truth_pixels == 0) {
        s += " (drawn while hidden)";
    }
    return s;
}

namespace {

// --view: that the run recorded the view asked for, and a line saying whose decisions follow
// where that is not plain (a stereo run culled per eye, a light's view).
std::string viewHead(sql::Database& db, const WhyRequest& r) {
    const bool per_eye = recordedViewHasRows(db, RecordedView::RightEye);
    switch (r.view) {
        case RecordedView::RightEye:
            if (!per_eye) {
                throw InputError(
                    "--view right: this run recorded no right eye's decisions (a stereo run "
                    "culled per eye records them); expected --view camera");
            }
            return "(the right eye's decisions, a stereo run culled per eye)\n";
        case RecordedView::Light:
            if (!recordedViewHasRows(db, RecordedView::Light)) {
                throw InputError(
                    "--view light: this run recorded no light view's decisions (--shadow-casters "
                    "culler or culler+receivers records them); expected --view camera");
            }
            return "(the light view's decisions: drawn into the shadow map or not; pixels are "
                   "the visible pixels ground truth shadows through the caster)\n";
        default:
            if (r.left_eye && !per_eye) {
                throw InputError(
                    "--view left: this run is not a stereo run culled per eye; expected --view "
                    "camera");
            }
            return per_eye ? "(the left eye's decisions, a stereo run culled per eye; --view "
                             "right for the right eye's)\n"
                           : "";
    }
}

}  // namespace

std::string answerWhy(const WhyRequest& r) {
    const int modes = (!r.object.empty()) + r.overdraw + r.missed;
    if (modes != 1) {
        throw InputError(
            "occsim why: expected one of --object ID|NAME, --overdraw or --missed, got " +
            std::to_string(modes));
    }
    if (r.frame && r.object.empty())
        throw InputError("--frame: goes with --object; expected --object ID|NAME beside it");
    ObjectDatabase base(r.run);
    sql::Database& db = base.db();
    try {
        const std::vector<RecordedConfig> configs = chosenConfigs(db, r.algo);
        std::string head;
        if (base.run().partial) {
            head = "(partial run: " +
                   (base.run().partial_reason.empty() ? std::string("it did not finish")
                                                      : base.run().partial_reason) +
                   "; " + plural(base.run().frames_recorded, "frame", "frames") + " recorded)\n";
        }
        head += viewHead(db, r);
        if (r.overdraw) return head + overdrawList(db, configs, r.limit, r.view);
        if (base.run().repetitions > 1) {
            head += "(repetition 1 of " + std::to_string(base.run().repetitions) +
                    " recorded: --record objects keeps the first repetition's decisions)\n";
        }
        if (r.missed) return head + missedList(db, configs, base.run().repetitions, r.view);
        const RecordedObject object = chosenObject(db, r.object);
        if (r.frame && *r.frame >= base.run().frames_recorded) {
            const uint32_t n = base.run().frames_recorded;
            throw InputError("--frame " + std::to_string(*r.frame) + ": outside the run; " +
                             (n == 0 ? std::string("no frame was recorded")
                                     : "frames 0-" + std::to_string(n - 1) + " were recorded") +
                             (base.run().partial ? " (the run stopped early)" : ""));
        }
        return head + oneObject(base, r, configs, object);
    } catch (const sql::Error& e) {
        throw ObjectsDatabaseError(base.file().string() + ": unreadable (" + e.what() +
                                   "); record the run again with --record objects");
    }
}

}  // namespace occsim
