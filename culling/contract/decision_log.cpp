#include "occsim/culling/contract/decision_log.h"

#include <array>

namespace occsim {
namespace {

struct KindRow {
    std::string_view name;
    int draws;
};

// Indexed by DecisionKind; the names are what objects.sqlite's reasons table and `occsim why`
// show (docs/objects.md). One kind a line, in DecisionKind's order:
// clang-format off
constexpr std::array<KindRow, kDecisionKinds> kKinds = {{
    {"no reason given", -1},
    {"frustum culled", 0},
    {"culled on query", 0},
    {"drawn on query", 1},
    {"drawn on statistics", 1},
    {"drawn on cost model", 1},
    {"drawn at near plane", 1},
    {"drawn with no test", 1},
    {"drawn with query in flight", 1},
    {"drawn assumed visible", 1},
    {"culled on pyramid", 0},
    {"drawn on pyramid", 1},
    {"culled on tiles", 0},
    {"drawn on tiles", 1},
    {"drawn conditionally", -1},
    {"drawn by oracle", 1},
    {"culled by oracle", 0},
    {"culled on box raster", 0},
    {"drawn on box raster", 1},
}};
// clang-format on

}  // namespace

std::string_view decisionKindName(DecisionKind kind) {
    const auto i = static_cast<size_t>(kind);
    return i < kKinds.size() ? kKinds[i].name : "unknown reason";
}

int decisionKindDraws(DecisionKind kind) {
    const auto i = static_cast<size_t>(kind);
    return i < kKinds.size() ? kKinds[i].draws : -1;
}

}  // namespace occsim
