// The registry rows of "statistical" (the paper as published) and "statistical+" (every
// improvement on): their options table, one row per member of StatisticalOptions, and the hooks
// the registry calls. The algorithm is statistical_culler.cpp's.
#include <algorithm>
#include <limits>

#include "culling/cullers/statistical_culler.h"
#include "occsim/culling/declaration/culler_row.h"

namespace occsim {
namespace {

using SO = StatisticalOptions;

// The keys of culling.statistical and culling["statistical+"], in the order `occsim cullers`
// lists them: the paper's, then the improvements'. The two cullers share every row but what the
// tuner may tune. The paper's tunable bounds: the paper's BASE_TIME is 2/3 s; the box reaches from
// re-querying every few frames to past the statistics' "too old" age (2 s by default), where a
// longer wait changes nothing. The decay curve a - b^occ_num stays >= 0 (a >= 1, b in [0, 1]); a
// up to 4 lets a long unoccluded history wait four BASE_TIMEs.
// statistical+ tunes what decided its frame times in the quiet table of 2026-12-02 and the sweeps
// after it (docs/tuning.md, "The search space of statistical+"): how soon a node is re-queried
// (the parallax factor), how far the traversal runs ahead of its answers (queries_before_restart)
// and how often a frame may block (waits_per_frame). Not the decay curve: once a node has three
// visible results its interval is within 1/8 of parallax * a, so a only rescales the parallax
// factor (a ridge the quadratic response cannot place), and b was kept at its default in 20 of
// those 22 sessions.
OptionTable<SO> statisticalTable(bool plus) {
    const double inf = std::numeric_limits<double>::infinity();
    OptionRow<SO> base_time =
        numberOption(OptionMember{&SO::base_time_s, "base_time"}, "s", 0.0, inf,
                     "BASE_TIME: a node found visible is re-queried after "
                     "BASE_TIME * (a - b^occ_num) seconds");
    OptionRow<SO> parallax = alternativeTo(
        switchable(numberOption(OCCSIM_OPTION_MEMBER(SO, requery_parallax), "", 0.0, inf,
                                "re-query once the travel divided by the node's distance from the "
                                "eye exceeds this * (a - b^occ_num); 0 = BASE_TIME seconds"),
                   0.0),
        "requery_distance");
    OptionRow<SO> in_flight = integerOption(
        OCCSIM_OPTION_MEMBER(SO, queries_before_restart), "queries", 1, 4294967295.0,
        "the traversal returns to the queue start after this many queries (with ready_answers: "
        "the most queries in flight; with waits_per_frame, the least bound)");
    OptionRow<SO> decay_a =
        numberOption(OCCSIM_OPTION_MEMBER(SO, decay_a), "", 1.0, inf,
                     "a in BASE_TIME * (a - b^occ_num): the longest wait, in BASE_TIMEs");
    OptionRow<SO> decay_b = numberOption(OCCSIM_OPTION_MEMBER(SO, decay_b), "", 0.0, 1.0,
                                         "b in BASE_TIME * (a - b^occ_num): how fast a visible "
                                         "history lengthens the wait");
    OptionRow<SO> waits = switchable(
        integerOption(OCCSIM_OPTION_MEMBER(SO, waits_per_frame), "waits", 0, 1000000,
                      "with ready_answers, the bound on queries in flight is at least the last "
                      "frame's waited queries over this many waits; 0 = off"),
        0.0);
    if (plus) {
        // BASE_TIME is unused while the parallax factor is > 0. The sessions of 2026-12-02 ended
        // on the old lower bound 0.005 in 11 of 22; the default 0.025 sits inside the new box.
        parallax = tunable(parallax, 0.002, 0.05);
        // The best bound on queries in flight depends on the scene (docs/statistical.md, (1)); 2,
        // the old lower bound, was chosen in 6 of 22 sessions.
        in_flight = tunable(in_flight, 1, 32);
        // 0 (off) is another mode, far slower where frames wait (plant 1.06x against 1.41x at 2).
        waits = tunable(waits, 1, 16);
    } else {
        base_time = tunable(base_time, 0.05, 2.0);
        decay_a = tunable(decay_a, 1.0, 4.0);
        decay_b = tunable(decay_b, 0.0, 1.0);
    }
    return {
        base_time,
        decay_a,
        decay_b,
        integerOption(OCCSIM_OPTION_MEMBER(SO, history_length), "results", 1, 32,
                      "query results remembered per node"),
        numberOption(OptionMember{&SO::max_statistics_age_s, "max_statistics_age"}, "s", 1e-6, inf,
                     "statistics older than this are ignored: the node is queried"),
        in_flight,
        // The improvements (statistical_options.h numbers them).
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, ready_answers),
                                 "take each answer as soon as it is ready and keep traversing"),
                   0.0),
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, virtual_leaves),
                                 "the objects stored in an inner node get statistics and a query "
                                 "of their own"),
                   0.0),
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, object_queries),
                                 "the objects of a rendered leaf are decided one by one, each with "
                                 "statistics of its own"),
                   0.0),
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, cost_model),
                                 "weigh each query against culling.cost_model: draw without a "
                                 "query what is cheaper to draw than to query"),
                   0.0),
        alternativeTo(
            switchable(numberOption(OptionMember{&SO::requery_distance_m, "requery_distance"}, "m",
                                    0.0, inf,
                                    "re-query after this distance travelled (camera and movers) "
                                    "* (a - b^occ_num); 0 = BASE_TIME seconds"),
                       0.0),
            "requery_parallax"),
        parallax,
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, fallback),
                                 "when recent answers show little occlusion, cull by the frustum "
                                 "only for a while"),
                   0.0),
        numberOption(OCCSIM_OPTION_MEMBER(SO, fallback_visible_share), "", 0.0, 1.0,
                     "fall back when at least this share of the window's answers came back "
                     "visible"),
        integerOption(OCCSIM_OPTION_MEMBER(SO, fallback_window_frames), "frames", 1, 1000,
                      "the window the share is taken over"),
        numberOption(OptionMember{&SO::fallback_recheck_s, "fallback_recheck"}, "s", 0.0, inf,
                     "simulation time culled by the frustum only before the algorithm runs again"),
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, draw_while_requerying),
                                 "a subject last found visible whose re-query is due is drawn at "
                                 "once; its answer, taken when ready, only updates statistics"),
                   0.0),
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, descend_visible_inner_nodes),
                                 "an inner node last found visible whose re-query is due is not "
                                 "queried: its children decide"),
                   0.0),
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, weigh_in_flight),
                                 "with ready_answers, each query in flight counts by its chance of "
                                 "coming back visible against queries_before_restart"),
                   0.0),
        waits,
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, requery_horizon),
                                 "with cost_model, a re-query of a subject last found visible is "
                                 "weighed over the frames until it would come due again"),
                   0.0),
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(SO, distance_order),
                                 "the main queue takes its entries nearest first by the distance "
                                 "from the eye to their bounds, not in the tree's order"),
                   0.0),
    };
}

std::string validateStatistical(const OptionValues& values) {
    std::string why;
    statisticalOptionTable().read(values).isValid(&why);
    return why;
}

CostModelUse statisticalCostModelUse(const OptionValues& values) {
    // The most queries the culler keeps in flight: the paper's passes and a fixed bound keep
    // queries_before_restart (each weighed at least 1 / kMaxRunAhead with weigh_in_flight), a
    // bound that grows with the frame (waits_per_frame) keeps no fixed number (0: measured with
    // every query issued before the first answer is fetched).
    const SO o = statisticalOptionTable().read(values);
    uint32_t in_flight = o.queries_before_restart;
    if (o.ready_answers && o.waits_per_frame > 0) {
        in_flight = 0;
    } else if (o.ready_answers && o.weigh_in_flight) {
        in_flight = static_cast<uint32_t>(
            std::min(4294967295.0, o.queries_before_restart * SO::kMaxRunAhead));
    }
    return {o.cost_model, in_flight};
}

std::unique_ptr<Culler> makeStatistical(const CullerContext& c) {
    return std::make_unique<StatisticalCuller>(statisticalOptionTable().read(c.options),
                                               c.cost_model);
}

CullerRow statisticalRow(std::string name, std::string summary, bool plus) {
    CullerRow t;
    t.name = std::move(name);
    t.summary = std::move(summary);
    t.conservative = true;
    t.issues_queries = true;
    t.options = statisticalTable(plus).descriptor(plus ? SO::plus() : SO::paper());
    t.factory = makeStatistical;
    t.validate = validateStatistical;
    t.cost_model_use = statisticalCostModelUse;
    return t;
}

}  // namespace

const OptionTable<StatisticalOptions>& statisticalOptionTable() {
    // Either variant's table reads values: they differ only in what the tuner may tune.
    static const OptionTable<StatisticalOptions> table = statisticalTable(false);
    return table;
}

CullerRow statisticalRegistration() {
    return statisticalRow("statistical", "Kovalcik & Sochor 2005, as published", false);
}

CullerRow statisticalPlusRegistration() {
    return statisticalRow("statistical+",
                          "Kovalcik & Sochor with ready answers, virtual leaves, a cost model, "
                          "re-query by distance, a frustum fallback, CHC's treatment of what was "
                          "visible, and a nearest-first queue",
                          true);
}

}  // namespace occsim
