// objects.sqlite through the executable, with real OpenGL (`--record objects`): on a small
// scenario and on a glTF level built here, the database's missed objects per frame are
// frames.csv's for every configuration and its visible-but-not-drawn objects account for every
// error pixel; `why` names the object async missed and the frame of the query that hid it; a
// stopped run keeps a readable database of its whole frames, marked partial; regress records too.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "objects_fixtures.h"
#include "occsim/culling/contract/decision_log.h"
#include "occsim/culling/registry/registry.h"
#include "signalled_run.h"
#include "sim/output/console_table.h"
#include "sim/record/object_schema.h"

namespace occsim::testing {
namespace {

namespace fs = std::filesystem;

const std::string kExe = OCCSIM_EXE;
const std::string kSmall = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";

Outcome occsim(const std::string& args) { return shell(kExe + " " + args); }

// Per configuration and frame, the database against frames.csv: its missed objects (ground truth
// saw them, not drawn), its visible objects, the error pixels its missed objects account for,
// the error and tie pixels of all its rows, and its drawn objects (but for conditional draws,
// which frames.csv counts as submitted). Every row's reason agrees with the drawing, and no row
// says nothing (frustum culled, no pixel).
void expectDatabaseMatchesFramesCsv(const fs::path& out) {
    const FramesCsv csv(out / "frames.csv");
    ASSERT_FALSE(csv.rows.empty());
    sql::Database db(out / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
    const auto count = [&](const std::string& where, const std::string& label, int64_t frame) {
        return queryInteger(db,
                            "SELECT COUNT(*) FROM decisions d JOIN configurations c ON "
                            "c.config = d.config WHERE c.label = ? AND d.frame = ? AND " +
                                where,
                            {label}, {frame});
    };
    const auto sum = [&](const std::string& what, const std::string& where,
                         const std::string& label, int64_t frame) {
        return queryInteger(db,
                            "SELECT COALESCE(SUM(" + what +
                                "), 0) FROM decisions d JOIN configurations c ON c.config = "
                                "d.config WHERE c.label = ? AND d.frame = ? AND " +
                                where,
                            {label}, {frame});
    };
    for (const auto& row : csv.rows) {
        const std::string label = row.at("configuration");
        const int64_t frame = std::stoll(row.at("frame"));
        const std::string where = label + " frame " + std::to_string(frame);
        EXPECT_EQ(count("d.drawn = 0 AND d.truth_pixels > 0", label, frame),
                  std::stoll(row.at("missed_objects")))
            << where;
        EXPECT_EQ(count("d.truth_pixels > 0", label, frame), std::stoll(row.at("visible_objects")))
            << where;
        EXPECT_EQ(sum("d.error_pixels", "d.drawn = 0 AND d.truth_pixels > 0", label, frame),
                  std::stoll(row.at("error_pixels")))
            << where << ": the missed objects account for every error pixel";
        EXPECT_EQ(sum("d.error_pixels", "1", label, frame), std::stoll(row.at("error_pixels")))
            << where;
        EXPECT_EQ(sum("d.tie_pixels", "1", label, frame), std::stoll(row.at("tie_pixels")))
            << where;
        if (label != "conditional") {
            EXPECT_EQ(count("d.drawn = 1", label, frame), std::stoll(row.at("objects_drawn")))
                << where;
        }
    }
    EXPECT_EQ(queryInteger(db, "SELECT COUNT(*) FROM decisions WHERE reason = 0"), 0)
        << "every built-in culler gives a reason";
    EXPECT_EQ(queryInteger(db,
                           "SELECT COUNT(*) FROM decisions d JOIN reasons r ON r.reason = d.reason "
                           "WHERE r.draws IS NOT NULL AND r.draws != d.drawn"),
              0)
        << "a reason that says drawn is a drawn object, and one that says culled is not";
    EXPECT_EQ(queryInteger(db,
                           "SELECT COUNT(*) FROM decisions WHERE reason = 1 AND drawn = 0 AND "
                           "truth_pixels = 0 AND error_pixels = 0 AND tie_pixels = 0"),
              0)
        << "rows that say nothing are left out";
    EXPECT_EQ(queryInteger(db, "SELECT frames_recorded FROM run"),
              queryInteger(db, "SELECT frames FROM run"));
    EXPECT_EQ(queryInteger(db, "SELECT partial FROM run"), 0);
}

TEST(ObjectsDatabase, OnTheSmallScenarioItsMissesAndErrorPixelsAreFramesCsvsForEveryCuller) {
    TempDir dir;
    const fs::path out = dir.path() / "out";
    const Outcome o = occsim("bench " + kSmall + " --frames 12 --deterministic-latency 8 " +
                             "--record objects --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("objects: " + (out / "objects.sqlite").string()), std::string::npos)
        << o.output;
    expectDatabaseMatchesFramesCsv(out);
    sql::Database db(out / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
    const int64_t configurations = static_cast<int64_t>(cullerRows().size());  // every culler
    EXPECT_EQ(queryInteger(db, "SELECT COUNT(*) FROM configurations"), configurations);
    EXPECT_EQ(queryInteger(db, "SELECT COUNT(*) FROM objects"), 300);
    EXPECT_EQ(queryInteger(db, "SELECT COUNT(*) FROM objects WHERE name = 'teapot 17'"), 1);
    EXPECT_GT(queryInteger(db, "SELECT COUNT(*) FROM objects WHERE moving = 1"), 0);
    EXPECT_EQ(queryInteger(db, "SELECT deterministic_latency FROM run"), 8);
    // The frustum culls something every frame, and those rows are left out: fewer rows than
    // frames x configurations x objects.
    EXPECT_LT(queryInteger(db, "SELECT COUNT(*) FROM decisions"), 12 * configurations * 300);
    const std::string report = fileText(out / "report.md");
    EXPECT_NE(report.find("## Objects"), std::string::npos) << report;
    EXPECT_NE(report.find("**Drawn while hidden**"), std::string::npos) << report;
}

// A light's view culled by each culler (--shadow-casters culler): light_decisions holds its
// decisions beside the camera's. Per configuration and frame its drawn casters are frames.csv's
// shadow_casters, the casters with shadow pixels are its shadow_seen_casters, none of them
// missed (as frames.csv's missed_casters: zero), every reason agrees with the drawing; the
// camera's rows still match frames.csv.
TEST(ObjectsDatabase, ALightsViewCulledByEachCullerHasItsOwnRowsThatMatchFramesCsv) {
    TempDir dir;
    const fs::path out = dir.path() / "out";
    const std::string city =
        std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/city-sun-small.json";
    const Outcome o = occsim("bench " + city + " --algos vfc,statistical,chc --frames 10 " +
                             "--deterministic-latency 8 --shadow-casters culler --record objects " +
                             "--out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    expectDatabaseMatchesFramesCsv(out);
    const FramesCsv csv(out / "frames.csv");
    sql::Database db(out / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
    EXPECT_EQ(queryInteger(db, "SELECT format_version FROM run"), kObjectsFormatVersion);
    const auto count = [&](const std::string& where, const std::string& label, int64_t frame) {
        return queryInteger(db,
                            "SELECT COUNT(*) FROM light_decisions d JOIN configurations c ON "
                            "c.config = d.config WHERE c.label = ? AND d.frame = ? AND " +
                                where,
                            {label}, {frame});
    };
    int64_t seen = 0;
    for (const auto& row : csv.rows) {
        const std::string label = row.at("configuration");
        const int64_t frame = std::stoll(row.at("frame"));
        const std::string where = label + " frame " + std::to_string(frame);
        EXPECT_EQ(count("d.drawn = 1", label, frame), std::stoll(row.at("shadow_casters")))
            << where;
        EXPECT_EQ(count("d.shadow_pixels > 0", label, frame),
                  std::stoll(row.at("shadow_seen_casters")))
            << where;
        EXPECT_EQ(count("d.missed_shadow_pixels > 0", label, frame),
                  std::stoll(row.at("missed_casters")))
            << where;
        seen += std::stoll(row.at("shadow_seen_casters"));
    }
    EXPECT_GT(seen, 0) << "ground truth shows no shadow: the checks above prove little";
    EXPECT_EQ(queryInteger(db, "SELECT COUNT(*) FROM light_decisions WHERE light != 0"), 0);
    EXPECT_EQ(queryInteger(db,
                           "SELECT COUNT(*) FROM light_decisions d JOIN reasons r ON "
                           "r.reason = d.reason WHERE r.draws IS NOT NULL AND r.draws != d.drawn"),
              0)
        << "a reason that says drawn is a drawn caster, and one that says culled is not";
    EXPECT_GT(queryInteger(db,
                           "SELECT COUNT(*) FROM light_decisions WHERE reason IN "
                           "(SELECT reason FROM reasons WHERE name = 'culled on query')"),
              0)
        << "some caster is hidden from the light";
    // `why --view light` on a caster the light's chc hid: its query, and the shadow it casts.
    sql::Statement hidden = db.prepare(
        "SELECT d.object, d.frame FROM light_decisions d JOIN configurations c USING (config) "
        "WHERE c.label = 'chc' AND d.reason = 2 ORDER BY d.frame, d.object LIMIT 1");
    ASSERT_TRUE(hidden.step());
    const Outcome why =
        occsim("why " + out.string() + " --view light --algo chc --object " +
               std::to_string(hidden.integer(0)) + " --frame " + std::to_string(hidden.integer(1)));
    ASSERT_EQ(why.exit_code, 0) << why.output;
    EXPECT_NE(why.output.find("the light view's decisions"), std::string::npos) << why.output;
    EXPECT_NE(why.output.find("chc: not drawn: the query issued"), std::string::npos) << why.output;
    EXPECT_NE(why.output.find("visible px through it"), std::string::npos) << why.output;
    const Outcome right = occsim("why " + out.string() + " --missed --view right");
    EXPECT_EQ(right.exit_code, 2) << right.output;
    EXPECT_NE(right.output.find("--view right: this run recorded no right eye's"),
              std::string::npos)
        << right.output;
}

// A stereo run culled per eye (eyes 4 m apart, async answering 100 commands late, so both eyes
// miss): `decisions` holds the left eye's decisions with its half's pixels, right_eye_decisions
// the right eye's. Per configuration and frame each table's error pixels are that eye's figure in
// frames.csv, the objects either table has missed are its missed_objects, and the two tables'
// drawn rows its objects_drawn; `why --view left|right` reads each eye's, a view the run did
// not record is one line.
TEST(ObjectsDatabase, AStereoRunCulledPerEyeRecordsEachEyesDecisionsThatMatchFramesCsv) {
    TempDir dir;
    const fs::path out = dir.path() / "out";
    const std::string city = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/city-small.json";
    const Outcome o = occsim("bench " + city + " --stereo 4,per_eye --algos chc,async " +
                             "--deterministic-latency 100 --record objects --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const FramesCsv csv(out / "frames.csv");
    ASSERT_FALSE(csv.rows.empty());
    sql::Database db(out / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
    const auto sum = [&](const std::string& what, const std::string& table,
                         const std::string& label, int64_t frame) {
        return queryInteger(db,
                            "SELECT COALESCE(" + what + ", 0) FROM " + table +
                                " d JOIN configurations c ON c.config = d.config WHERE "
                                "c.label = ? AND d.frame = ?",
                            {label}, {frame});
    };
    int64_t left_error = 0, right_error = 0;
    for (const auto& row : csv.rows) {
        const std::string label = row.at("configuration");
        const int64_t frame = std::stoll(row.at("frame"));
        const std::string where = label + " frame " + std::to_string(frame);
        EXPECT_EQ(sum("SUM(d.error_pixels)", "decisions", label, frame),
                  std::stoll(row.at("left_error_pixels")))
            << where;
        EXPECT_EQ(sum("SUM(d.error_pixels)", "right_eye_decisions", label, frame),
                  std::stoll(row.at("right_error_pixels")))
            << where;
        EXPECT_EQ(sum("SUM(d.drawn)", "decisions", label, frame) +
                      sum("SUM(d.drawn)", "right_eye_decisions", label, frame),
                  std::stoll(row.at("objects_drawn")))
            << where;
        EXPECT_EQ(queryInteger(db,
                               "SELECT COUNT(DISTINCT object) FROM (SELECT * FROM decisions UNION "
                               "ALL SELECT * FROM right_eye_decisions) d JOIN configurations c "
                               "ON c.config = d.config WHERE c.label = ? AND d.frame = ? AND "
                               "d.drawn = 0 AND d.truth_pixels > 0",
                               {label}, {frame}),
                  std::stoll(row.at("missed_objects")))
            << where;
        left_error += std::stoll(row.at("left_error_pixels"));
        right_error += std::stoll(row.at("right_error_pixels"));
    }
    EXPECT_GT(left_error, 0) << "async missed nothing in the left eye: the checks prove little";
    EXPECT_GT(right_error, 0) << "async missed nothing in the right eye: the checks prove little";
    EXPECT_GT(queryInteger(db,
                           "SELECT COUNT(*) FROM decisions l JOIN right_eye_decisions r "
                           "USING (config, frame, object) WHERE l.drawn != r.drawn"),
              0)
        << "eyes 4 m apart decide apart";
    EXPECT_EQ(queryInteger(db,
                           "SELECT COUNT(*) FROM right_eye_decisions d JOIN reasons r ON "
                           "r.reason = d.reason WHERE r.draws IS NOT NULL AND r.draws != d.drawn"),
              0);
    const std::string report = fileText(out / "report.md");
    EXPECT_NE(report.find("async (right eye)"), std::string::npos) << report;

    const Outcome right = occsim("why " + out.string() + " --missed --algo async --view right");
    ASSERT_EQ(right.exit_code, 0) << right.output;
    EXPECT_NE(right.output.find("the right eye's decisions"), std::string::npos) << right.output;
    const Outcome left = occsim("why " + out.string() + " --missed --algo async --view left");
    ASSERT_EQ(left.exit_code, 0) << left.output;
    EXPECT_NE(left.output.find("the left eye's decisions"), std::string::npos) << left.output;
    EXPECT_NE(left.output, right.output);
    const Outcome light = occsim("why " + out.string() + " --missed --view light");
    EXPECT_EQ(light.exit_code, 2) << light.output;
    EXPECT_EQ(std::count(light.output.begin(), light.output.end(), '\n'), 1) << light.output;
    EXPECT_NE(light.output.find("--view light"), std::string::npos) << light.output;
    const Outcome bad = occsim("why " + out.string() + " --missed --view top");
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("--view: expected camera, left, right or light, got 'top'"),
              std::string::npos)
        << bad.output;
}

TEST(ObjectsDatabase, OnAGltfLevelAsyncMissesTheTruckAndWhyNamesTheQueryThatHidIt) {
    TempDir dir;
    const fs::path scenario = writeWalledYard(dir);
    const fs::path out = dir.path() / "out";
    // Answers 20 commands later: a few frames, in a scene of eight objects.
    const Outcome o = occsim("bench " + scenario.string() +
                             " --deterministic-latency 20 --record objects --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    expectDatabaseMatchesFramesCsv(out);

    sql::Database db(out / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
    EXPECT_EQ(queryInteger(db, "SELECT COUNT(*) FROM objects"), 7);
    EXPECT_EQ(queryInteger(db, "SELECT moving FROM objects WHERE name = 'truck'"), 1);
    EXPECT_EQ(queryInteger(db, "SELECT moving FROM objects WHERE name = 'wall'"), 0);
    EXPECT_EQ(queryInteger(db, "SELECT triangles FROM objects WHERE name = 'crate.1'"), 12);
    // Only async misses anything, and it misses the truck as it comes out from behind the wall.
    EXPECT_EQ(queryInteger(db,
                           "SELECT COUNT(*) FROM decisions d JOIN configurations c ON c.config = "
                           "d.config WHERE c.label != 'async' AND d.drawn = 0 AND "
                           "d.truth_pixels > 0"),
              0);
    sql::Statement miss = db.prepare(
        "SELECT d.frame, d.query_frame, d.reason, d.truth_pixels FROM decisions d "
        "JOIN configurations c ON c.config = d.config JOIN objects o ON o.object = d.object "
        "WHERE c.label = 'async' AND o.name = 'truck' AND d.drawn = 0 AND d.truth_pixels > 0 "
        "ORDER BY d.frame LIMIT 1");
    ASSERT_TRUE(miss.step()) << "async must miss the truck once at least";
    const int64_t frame = miss.integer(0), query_frame = miss.integer(1);
    EXPECT_EQ(miss.integer(2), static_cast<int64_t>(DecisionKind::CulledOnQuery));
    EXPECT_LT(query_frame, frame) << "the answer that hid it came from an earlier frame's query";
    const int64_t pixels = miss.integer(3);

    const Outcome why = occsim("why " + out.string() + " --object truck --frame " +
                               std::to_string(frame) + " --algo async");
    ASSERT_EQ(why.exit_code, 0) << why.output;
    EXPECT_NE(why.output.find("'truck'"), std::string::npos) << why.output;
    const std::string line = "frame " + std::to_string(frame) +
                             ", async: not drawn: the query issued at frame " +
                             std::to_string(query_frame) + " (";
    EXPECT_NE(why.output.find(line), std::string::npos) << why.output;
    EXPECT_NE(why.output.find("answered occluded"), std::string::npos) << why.output;
    EXPECT_NE(why.output.find("ground truth sees " + std::to_string(pixels) + " px"),
              std::string::npos)
        << why.output;

    const Outcome missed = occsim("why " + out.string() + " --missed");
    ASSERT_EQ(missed.exit_code, 0) << missed.output;
    EXPECT_NE(missed.output.find("async: 1 object missed\n  object 6 'truck': frames " +
                                 std::to_string(frame)),
              std::string::npos)
        << missed.output;
    EXPECT_NE(missed.output.find("chc: 0 objects missed"), std::string::npos) << missed.output;
    // Over the run: how often it was drawn, seen and missed, and each missed frame in words.
    const Outcome history = occsim("why " + out.string() + " --object 6 --algo async");
    ASSERT_EQ(history.exit_code, 0) << history.output;
    EXPECT_NE(history.output.find("async: drawn on "), std::string::npos) << history.output;
    EXPECT_NE(history.output.find("missed on frames " + std::to_string(frame)), std::string::npos)
        << history.output;

    const std::string report = fileText(out / "report.md");
    EXPECT_NE(report.find("| async | 6 truck | " + std::to_string(frame)), std::string::npos)
        << report;
}

// Issue 56: CHC drew a crate hidden behind the wall "while its query is in flight", and why
// stopped there. With one leaf for the whole yard (the wall and the crates share it), `why`
// follows the decision to that leaf: the objects it held (the wall seen, the crates not), its
// last answer and the next one, and the frame's bird's-eye picture; over the run, the first frame
// drawn while hidden gets the same.
TEST(ObjectsDatabase, WhyFollowsADecisionMadeForALeafToTheLeafItsAnswersAndThePicture) {
    TempDir dir;
    nlohmann::json scenario = nlohmann::json::parse(fileText(writeWalledYard(dir, 12)));
    scenario["bsp"]["max_objects_per_leaf"] = 16;  // one leaf: the root
    const fs::path file = dir.write("one-leaf.json", scenario.dump());
    const fs::path out = dir.path() / "out";
    const Outcome o = occsim("bench " + file.string() +
                             " --algos chc --deterministic-latency 20 --record objects "
                             "--birds-eye 6 --out " +
                             out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;

    sql::Database db(out / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
    const std::string crate = "(SELECT object FROM objects WHERE name = 'crate.1')";
    const int64_t node =
        queryInteger(db, "SELECT node FROM decisions WHERE frame = 6 AND object = " + crate);
    EXPECT_EQ(
        queryInteger(db, "SELECT node_kind FROM decisions WHERE frame = 6 AND object = " + crate),
        1)
        << "decided with a leaf";
    EXPECT_EQ(queryInteger(
                  db, "SELECT truth_pixels FROM decisions WHERE frame = 6 AND object = " + crate),
              0)
        << "the crate is hidden behind the wall";
    ASSERT_GE(node, 0);
    const int64_t reason =
        queryInteger(db, "SELECT reason FROM decisions WHERE frame = 6 AND object = " + crate);

    const Outcome why = occsim("why " + out.string() + " --object crate.1 --frame 6");
    ASSERT_EQ(why.exit_code, 0) << why.output;
    const std::string leaf = "decided with leaf " + std::to_string(node) + ", which held 7 objects";
    EXPECT_NE(why.output.find(leaf), std::string::npos) << why.output;
    EXPECT_NE(why.output.find("'wall' (seen, "), std::string::npos) << why.output;
    EXPECT_NE(why.output.find("'crate.1' (unseen)"), std::string::npos) << why.output;
    if (reason != static_cast<int64_t>(DecisionKind::DrawnOnQuery) &&
        reason != static_cast<int64_t>(DecisionKind::CulledOnQuery)) {
        EXPECT_NE(why.output.find("its last answer before: visible ("), std::string::npos)
            << why.output;
    }
    EXPECT_NE(why.output.find("from above: " + (out / "birds-eye-chc-frame-00006.png").string()),
              std::string::npos)
        << why.output;
    std::istringstream lines(why.output);
    for (std::string line; std::getline(lines, line);) EXPECT_LE(displayWidth(line), 100u) << line;

    // Over the run: the first frame drawn while hidden, with its cause.
    const Outcome history = occsim("why " + out.string() + " --object crate.1");
    ASSERT_EQ(history.exit_code, 0) << history.output;
    EXPECT_NE(history.output.find("(first drawn while hidden): drawn: "), std::string::npos)
        << history.output;
    EXPECT_NE(history.output.find("    " + leaf), std::string::npos) << history.output;
    EXPECT_NE(history.output.find("    from above: "), std::string::npos) << history.output;
}

// The case: with --repetitions 3 summary.json counted the later repetitions' misses and
// `why --missed` and report.md's Missed section, reading the first repetition's rows, said none.
// Here every repetition makes the same decisions (deterministic latency): the file, why and the
// report must add up to summary.json, and say which repetition the rows are.
TEST(ObjectsDatabase, WithRepetitionsTheFileWhyAndTheReportAddUpToTheSummarysMisses) {
    TempDir dir;
    const fs::path scenario = writeWalledYard(dir);
    const fs::path out = dir.path() / "out";
    const Outcome o = occsim("bench " + scenario.string() +
                             " --algos vfc,async --deterministic-latency 20 --repetitions 3 "
                             "--record objects --out " +
                             out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    sql::Database db(out / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
    EXPECT_EQ(queryInteger(db, "SELECT repetitions FROM run"), 3);
    const nlohmann::json summary = nlohmann::json::parse(fileText(out / "summary.json"));
    for (const std::string label : {"vfc", "async"}) {
        int64_t total = -1;
        for (const nlohmann::json& a : summary["algorithms"]) {
            if (a["configuration"] == label) total = a["error"]["missed_objects_total"];
        }
        const int64_t recorded = queryInteger(db,
                                              "SELECT COUNT(*) FROM decisions d JOIN "
                                              "configurations c ON c.config = d.config WHERE "
                                              "c.label = ? AND d.drawn = 0 AND d.truth_pixels > 0",
                                              {label});
        const int64_t later = queryInteger(
            db, "SELECT missed_in_later_repetitions FROM configurations WHERE label = ?", {label});
        EXPECT_EQ(recorded + later, total) << label;
        EXPECT_EQ(later, 2 * recorded) << label << ": the same decisions in every repetition";
    }
    const int64_t async_later = queryInteger(
        db, "SELECT missed_in_later_repetitions FROM configurations WHERE label = 'async'");
    ASSERT_GT(async_later, 0) << "async must miss the truck in every repetition";

    const Outcome missed = occsim("why " + out.string() + " --missed");
    ASSERT_EQ(missed.exit_code, 0) << missed.output;
    EXPECT_NE(missed.output.find("(repetition 1 of 3 recorded: "), std::string::npos)
        << missed.output;
    // As the console prints it: broken into lines of at most 100 columns.
    EXPECT_NE(
        missed.output.find(wrappedText("async: 1 object missed in repetition 1; repetitions "
                                       "2-3, not recorded, missed " +
                                       std::to_string(async_later) + " more (objects × frames)")),
        std::string::npos)
        << missed.output;
    EXPECT_NE(missed.output.find("vfc: 0 objects missed in repetition 1; repetitions 2-3, not "
                                 "recorded, missed none\n"),
              std::string::npos)
        << missed.output;
    const std::string report = fileText(out / "report.md");
    EXPECT_NE(report.find("every one in the first of the 3 repetitions"), std::string::npos)
        << report;
    EXPECT_NE(report.find("- async: repetitions 2-3, not recorded, missed " +
                          std::to_string(async_later) + " more"),
              std::string::npos)
        << report;
}

TEST(ObjectsDatabase, AStoppedRunKeepsAReadableDatabaseOfItsWholeFramesMarkedPartial) {
    TempDir dir;
    const fs::path out = dir.path() / "out";
    const SignalledRun r = runAndSignal({kExe, "bench", kSmall, "--frames", "20000", "--algos",
                                         "vfc,async", "--record", "objects", "--out", out.string()},
                                        "frame ", SIGINT, (dir.path() / "stdout.txt").string());
    ASSERT_TRUE(r.signal_sent) << r.terminal;
    ASSERT_TRUE(r.exited) << r.terminal;
    EXPECT_EQ(r.exit_code, 128 + SIGINT) << r.terminal;
    const nlohmann::json summary = nlohmann::json::parse(fileText(out / "summary.json"));
    const int64_t reached = summary["partial"]["frames_reached"].get<int64_t>();
    ASSERT_GE(reached, 1);
    sql::Database db(out / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
    EXPECT_EQ(queryInteger(db, "SELECT partial FROM run"), 1);
    EXPECT_EQ(queryInteger(db, "SELECT frames_recorded FROM run"), reached);
    EXPECT_EQ(queryInteger(db, "SELECT MAX(frame) FROM decisions"), reached - 1);
    const Outcome why = occsim("why " + out.string() + " --missed");
    EXPECT_EQ(why.exit_code, 0) << why.output;
    EXPECT_NE(why.output.find("(partial run: partial: interrupted by SIGINT"), std::string::npos)
        << why.output;
    EXPECT_FALSE(fs::exists(out / "objects.sqlite-journal"));
}

TEST(ObjectsDatabase, RegressRecordsItInEachScenarioFolderAndARunWithoutRecordWritesNone) {
    TempDir dir;
    const fs::path scenario = writeWalledYard(dir, 10);
    // The level with an expect block: regress runs it (its baseline is written by --update).
    nlohmann::json s = nlohmann::json::parse(fileText(scenario));
    s["expect"] = {{"algorithms", {"vfc", "chc"}}, {"deterministic_latency", 8}};
    const fs::path file = dir.write("yard-regress.json", s.dump());
    const fs::path out = dir.path() / "regress";
    Outcome o =
        occsim("regress " + file.string() + " --update --record objects --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const fs::path folder = out / "yard-regress";
    ASSERT_TRUE(fs::exists(folder / kObjectsDatabaseFile)) << o.output;
    {
        sql::Database db(folder / kObjectsDatabaseFile, sql::Database::Mode::ReadOnly);
        sql::Statement command = db.prepare("SELECT command FROM run");
        ASSERT_TRUE(command.step());
        EXPECT_EQ(command.text(0), "regress");
        EXPECT_EQ(queryInteger(db, "SELECT COUNT(*) FROM configurations"), 2);
        EXPECT_EQ(queryInteger(db, "SELECT frames_recorded FROM run"), 10);
    }
    expectDatabaseMatchesFramesCsv(folder);
    EXPECT_NE(fileText(folder / "summary.json").find("--record objects"), std::string::npos)
        << "the command to rerun the scenario records too";

    o = occsim("bench " + file.string() + " --algos vfc --out " + (dir.path() / "plain").string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_FALSE(fs::exists(dir.path() / "plain" / kObjectsDatabaseFile));
    EXPECT_EQ(fileText(dir.path() / "plain/report.md").find("## Objects"), std::string::npos);
    EXPECT_EQ(o.output.find("objects: "), std::string::npos) << o.output;
}

}  // namespace
}  // namespace occsim::testing
