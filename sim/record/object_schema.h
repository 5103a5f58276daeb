// objects.sqlite, the objects database of a run (`--record objects`): its file name, format
// version and schema. docs/objects.md documents every table and column, with example queries;
// a test checks that page against the schema here.
#pragma once

#include <cstdint>

namespace occsim {

inline constexpr const char* kObjectsDatabaseFile = "objects.sqlite";
// 1: run, configurations, objects, reasons, decisions.
// 2: run.repetitions and configurations.missed_in_later_repetitions (only the first repetition
//    has rows; what the later ones missed is counted, so the file agrees with summary.json).
// 3: decisions.node and decisions.node_kind (the node a decision rests on), and an index by node.
// 4: light_decisions, the decisions of a light's view culled by the configuration's culler.
// 5: right_eye_decisions, the right eye's of a stereo run culled per eye (decisions: the left's).
inline constexpr int kObjectsFormatVersion = 5;

// The columns `decisions` and `light_decisions` share: a decision, its reason and what the culler
// said of it (a macro, so that both tables' statements stay string literals).
#define OCCSIM_DECISION_COLUMNS                                                \
    "  drawn INTEGER NOT NULL,\n"                                              \
    "  reason INTEGER NOT NULL REFERENCES reasons(reason),\n"                  \
    "  query_frame INTEGER,\n"                                                 \
    "  query_age INTEGER GENERATED ALWAYS AS (frame - query_frame) VIRTUAL,\n" \
    "  samples INTEGER,\n"                                                     \
    "  flags INTEGER NOT NULL,\n"                                              \
    "  phase INTEGER,\n"                                                       \
    "  level INTEGER,\n"                                                       \
    "  interval REAL,\n"                                                       \
    "  next_query REAL,\n"                                                     \
    "  next_query_frame INTEGER,\n"                                            \
    "  visible_answers INTEGER,\n"                                             \
    "  history INTEGER,\n"                                                     \
    "  node INTEGER,\n"                                                        \
    "  node_kind INTEGER,\n"

// A table of one camera view's decisions: `decisions` and `right_eye_decisions` (a macro, as
// above).
#define OCCSIM_VIEW_DECISIONS_TABLE(name)                                             \
    "CREATE TABLE " name                                                              \
    " (\n"                                                                            \
    "  frame INTEGER NOT NULL,\n"                                                     \
    "  config INTEGER NOT NULL REFERENCES configurations(config),\n"                  \
    "  object INTEGER NOT NULL REFERENCES objects(object),\n" OCCSIM_DECISION_COLUMNS \
    "  truth_pixels INTEGER NOT NULL,\n"                                              \
    "  error_pixels INTEGER NOT NULL,\n"                                              \
    "  tie_pixels INTEGER NOT NULL,\n"                                                \
    "  PRIMARY KEY (config, frame, object)\n"                                         \
    ") WITHOUT ROWID;\n"

// The tables. `decisions` holds a row per frame, configuration and object except the rows that
// say nothing: an object the frustum culled that ground truth does not see (no pixel, no error,
// no tie). Every drawn object, every visible one and every missed one has its row. In a stereo
// run culled per eye, `decisions` holds the left eye's (its pixels those of the left eye's half)
// and `right_eye_decisions`, with the same columns, the right eye's.
// `light_decisions` holds the same for a light's view, when the configuration's culler culls it
// (`--shadow-casters culler`, `culler+receivers`): a caster's pixels are the visible pixels ground
// truth shadows through it.
inline constexpr const char* kObjectsSchema = R"sql(
CREATE TABLE run (
  format_version INTEGER NOT NULL,
  occsim_version TEXT NOT NULL,
  command TEXT NOT NULL,
  command_line TEXT NOT NULL,
  scenario TEXT NOT NULL,
  scenario_file TEXT NOT NULL,
  frames INTEGER NOT NULL,
  frames_recorded INTEGER NOT NULL,
  partial INTEGER NOT NULL,
  partial_reason TEXT NOT NULL,
  dt_s REAL NOT NULL,
  seed INTEGER NOT NULL,
  width INTEGER NOT NULL,
  height INTEGER NOT NULL,
  deterministic_latency INTEGER,
  repetitions INTEGER NOT NULL DEFAULT 1
);
CREATE TABLE configurations (
  config INTEGER PRIMARY KEY,
  label TEXT NOT NULL UNIQUE,
  algorithm TEXT NOT NULL,
  missed_in_later_repetitions INTEGER NOT NULL DEFAULT 0
);
CREATE TABLE objects (
  object INTEGER PRIMARY KEY,
  name TEXT NOT NULL,
  triangles INTEGER NOT NULL,
  moving INTEGER NOT NULL
);
CREATE TABLE reasons (
  reason INTEGER PRIMARY KEY,
  name TEXT NOT NULL UNIQUE,
  draws INTEGER
);
)sql" OCCSIM_VIEW_DECISIONS_TABLE("decisions") OCCSIM_VIEW_DECISIONS_TABLE("right_eye_decisions")
    R"sql(
CREATE TABLE light_decisions (
  frame INTEGER NOT NULL,
  config INTEGER NOT NULL REFERENCES configurations(config),
  light INTEGER NOT NULL,
  object INTEGER NOT NULL REFERENCES objects(object),
)sql" OCCSIM_DECISION_COLUMNS R"sql(
  shadow_pixels INTEGER NOT NULL,
  missed_shadow_pixels INTEGER NOT NULL,
  PRIMARY KEY (config, frame, light, object)
) WITHOUT ROWID;
)sql";

// Made once the rows are in (faster than keeping them up to date row by row): one object's
// history, a culler's misses and its over-draw, and the objects decided with one node.
inline constexpr const char* kObjectsIndexes = R"sql(
CREATE INDEX decisions_by_object ON decisions(object, config, frame);
CREATE INDEX decisions_missed ON decisions(config, object, frame)
  WHERE drawn = 0 AND truth_pixels > 0;
CREATE INDEX decisions_overdrawn ON decisions(config, object, frame)
  WHERE drawn = 1 AND truth_pixels = 0;
CREATE INDEX decisions_by_node ON decisions(config, node, frame) WHERE node IS NOT NULL;
)sql";

}  // namespace occsim
