// A frame's decision records resolved per object (occsim/culling/tree/decision_resolution.h), and
// the reasons every built-in culler gives through them in known situations (a field hidden by a
// wall, an object that comes out from behind it), on the CPU test devices.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>
#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"
#include "occsim/culling/tree/decision_resolution.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {
namespace {

using testing::buildTree;
using testing::Camera;
using testing::makeCamera;
using testing::makeFrame;

// --- The resolution rule ------------------------------------------------------------------------

// Four objects in a row, one per leaf.
struct Row {
    std::vector<Aabb> boxes = testing::gridBoxes(4, 1);
    BspTree tree = buildTree(boxes, 1);
    std::vector<Decision> out;
    std::vector<uint32_t> stack;

    std::vector<DecisionKind> resolve(const DecisionLog& log) {
        resolveDecisions(tree, log.records(), out, stack);
        std::vector<DecisionKind> kinds;
        for (const Decision& d : out) kinds.push_back(d.kind);
        return kinds;
    }
};

TEST(DecisionResolution, TheLastRecordCoveringAnObjectIsItsReason) {
    Row row;
    DecisionLog log;
    log.add(QueryTag::node(row.tree.root()), decisionOf(DecisionKind::CulledOnQuery));
    log.add(QueryTag::object(2), decisionOf(DecisionKind::DrawnOnQuery));
    const std::vector<DecisionKind> kinds = row.resolve(log);
    EXPECT_EQ(kinds,
              (std::vector<DecisionKind>{DecisionKind::CulledOnQuery, DecisionKind::CulledOnQuery,
                                         DecisionKind::DrawnOnQuery, DecisionKind::CulledOnQuery}));
    log.add(QueryTag::node(row.tree.root()), decisionOf(DecisionKind::DrawnNoTest));
    EXPECT_EQ(row.resolve(log)[2], DecisionKind::DrawnNoTest);
}

TEST(DecisionResolution, ANodesRecordNeverOverridesAnObjectTheFrustumCulled) {
    Row row;
    DecisionLog log;
    log.add(QueryTag::object(1), decisionOf(DecisionKind::FrustumCulled));
    log.add(QueryTag::nodeObjects(row.tree.nodeOf(1)), decisionOf(DecisionKind::DrawnOnQuery));
    log.add(QueryTag::node(row.tree.root()), decisionOf(DecisionKind::DrawnNoTest));
    EXPECT_EQ(row.resolve(log)[1], DecisionKind::FrustumCulled);
    // An object's own record still does.
    log.add(QueryTag::object(1), decisionOf(DecisionKind::DrawnNearPlane));
    EXPECT_EQ(row.resolve(log)[1], DecisionKind::DrawnNearPlane);
}

TEST(DecisionResolution, ObjectsNoRecordCoversGetNoReasonAndUnknownSubjectsAreIgnored) {
    Row row;
    DecisionLog log;
    log.add(QueryTag::object(0), decisionOf(DecisionKind::DrawnNoTest));
    log.add(QueryTag::object(99), decisionOf(DecisionKind::DrawnNoTest));
    log.add(QueryTag::node(9999), decisionOf(DecisionKind::CulledOnQuery));
    log.add(QueryTag::nodeObjects(9999), decisionOf(DecisionKind::CulledOnQuery));
    const std::vector<DecisionKind> kinds = row.resolve(log);
    ASSERT_EQ(kinds.size(), 4u);
    EXPECT_EQ(kinds[0], DecisionKind::DrawnNoTest);
    for (size_t o = 1; o < 4; ++o) EXPECT_EQ(kinds[o], DecisionKind::NoReasonGiven) << o;
}

// What `occsim why` follows: each object's subject is that of the record that decided it (the
// node whose subtree or own objects it was decided with, or the object itself), untagged where no
// record covers it, and a frustum-culled object keeps its own.
TEST(DecisionResolution, EachObjectKeepsTheSubjectOfTheRecordThatDecidedIt) {
    Row row;
    DecisionLog log;
    const uint32_t leaf2 = row.tree.nodeOf(2);
    log.add(QueryTag::object(1), decisionOf(DecisionKind::FrustumCulled));
    log.add(QueryTag::node(row.tree.root()), decisionOf(DecisionKind::DrawnQueryInFlight));
    log.add(QueryTag::nodeObjects(leaf2), decisionOf(DecisionKind::CulledOnQuery));
    log.add(QueryTag::object(3), decisionOf(DecisionKind::DrawnOnQuery));
    std::vector<QueryTag> subjects;
    resolveDecisions(row.tree, log.records(), row.out, row.stack, &subjects);
    ASSERT_EQ(subjects.size(), 4u);
    EXPECT_EQ(subjects[0], QueryTag::node(row.tree.root()));
    EXPECT_EQ(subjects[1], QueryTag::object(1));
    EXPECT_EQ(subjects[2], QueryTag::nodeObjects(leaf2));
    EXPECT_EQ(subjects[3], QueryTag::object(3));
    EXPECT_EQ(row.out[2].kind, DecisionKind::CulledOnQuery);

    DecisionLog none;
    resolveDecisions(row.tree, none.records(), row.out, row.stack, &subjects);
    for (const QueryTag& s : subjects) EXPECT_EQ(s.index, QueryTag::kUntagged);
}

// --- The reasons each culler gives
// ----------------------------------------------------------------

// A wall of boxes across the view near the camera and a field behind it that the wall hides.
struct WallAndField {
    std::vector<Aabb> boxes;
    uint32_t wall_count = 0;
    WallAndField() {
        for (int i = 0; i < 16; ++i) {
            const float x = -24.0f + 3.0f * static_cast<float>(i);
            boxes.push_back({glm::vec3(x, 0, -1), glm::vec3(x + 2.9f, 12, 0)});
        }
        wall_count = static_cast<uint32_t>(boxes.size());
        for (int z = 0; z < 8; ++z) {
            for (int x = 0; x < 16; ++x) {
                const glm::vec3 lo(-24.0f + 3.0f * static_cast<float>(x), 0.0f,
                                   -8.0f - 4.0f * static_cast<float>(z));
                boxes.push_back({lo, lo + glm::vec3(1.0f, 1.5f, 1.0f)});
            }
        }
    }
    bool isField(uint32_t o) const { return o >= wall_count; }
};

// A camera behind the wall whose view has the viewport and projection a software raster needs.
Camera wallCamera(float x = 0.0f) {
    Camera cam = makeCamera({x, 3, 12}, {0, 2, -40});
    cam.view.view_projection = cam.view_projection;
    cam.view.viewport_width = 64;
    cam.view.viewport_height = 48;
    return cam;
}

// What a culler said and did over one frame.
struct Said {
    std::vector<Decision> why;
    std::vector<uint8_t> drawn;
    std::vector<uint8_t> truth;  // DepthRasterDevice only

    const Decision& operator[](uint32_t o) const { return why[o]; }
};

// Every object has a reason, and what the reason says about drawing is what the device did.
void expectReasonsAgreeWithDraws(const Said& s, const std::string& where) {
    for (uint32_t o = 0; o < s.why.size(); ++o) {
        const DecisionKind k = s.why[o].kind;
        EXPECT_NE(k, DecisionKind::NoReasonGiven) << where << ": object " << o;
        const int draws = decisionKindDraws(k);
        if (draws >= 0) {
            EXPECT_EQ(draws, s.drawn[o])
                << where << ": object " << o << " is " << decisionKindName(k)
                << (s.drawn[o] ? " but drawn" : " but not drawn");
        }
    }
}

// Frames of one culler on the depth raster, with the decision log on.
class RasterRun {
  public:
    RasterRun(std::unique_ptr<Culler> culler, const std::vector<Aabb>& boxes, uint32_t latency = 0,
              uint32_t leaf = 4)
        : culler_(std::move(culler)),
          boxes_(boxes),
          tree_(buildTree(boxes, leaf, BspSplitRule::Sah)),
          device_(64, 48, latency) {
        culler_->reset(tree_);
    }

    Said frame(uint64_t index, const Camera& cam, const CullMeshes& meshes = {}) {
        device_.beginFrame(cam.view_projection, cam.view.eye, boxes_);
        Said s;
        s.truth = device_.groundTruth();
        CullFrame frame = makeFrame(cam.view, index, static_cast<double>(index) / 30.0);
        frame.ground_truth_visible = s.truth;
        frame.meshes = meshes;
        log_.clear();
        frame.decisions = &log_;
        culler_->cullAndRender(tree_, frame, device_);
        culler_->afterFrame(device_);  // as the simulation does, once the frame is over
        resolveDecisions(tree_, log_.records(), s.why, stack_);
        s.drawn.assign(boxes_.size(), 0);
        for (uint32_t o : device_.drawnObjects()) s.drawn[o] = 1;
        return s;
    }
    const BspTree& tree() const { return tree_; }

  private:
    std::unique_ptr<Culler> culler_;
    std::vector<Aabb> boxes_;
    BspTree tree_;
    DepthRasterDevice device_;
    DecisionLog log_;
    std::vector<uint32_t> stack_;
};

std::unique_ptr<Culler> named(const char* name) {
    return testing::cullerNamed(name, CullerOptions{});
}

// The field objects in the frustum that ground truth does not see and the culler did not draw.
std::vector<uint32_t> hiddenFieldLeftOut(const WallAndField& scene, const Camera& cam,
                                         const Said& s) {
    std::vector<uint32_t> out;
    for (uint32_t o = scene.wall_count; o < scene.boxes.size(); ++o) {
        if (classify(cam.view.frustum, scene.boxes[o]) == FrustumTest::Outside) continue;
        if (!s.truth[o] && !s.drawn[o]) out.push_back(o);
    }
    return out;
}

TEST(CullerReasons, VfcDrawsWhatIsInTheFrustumWithNoTestAndSaysTheFrustumCulledTheRest) {
    const WallAndField scene;
    RasterRun run(named("vfc"), scene.boxes);
    const Camera cam = wallCamera();
    const Said s = run.frame(0, cam);
    expectReasonsAgreeWithDraws(s, "vfc");
    uint32_t outside = 0;
    for (uint32_t o = 0; o < scene.boxes.size(); ++o) {
        const bool in = classify(cam.view.frustum, scene.boxes[o]) != FrustumTest::Outside;
        EXPECT_EQ(s[o].kind, in ? DecisionKind::DrawnNoTest : DecisionKind::FrustumCulled) << o;
        outside += !in;
    }
    EXPECT_GT(outside, 0u) << "the field reaches out of the view";
}

TEST(CullerReasons, StopAndWaitCullsTheFieldBehindTheWallOnThisFramesQueries) {
    const WallAndField scene;
    RasterRun run(named("stop-and-wait"), scene.boxes, /*latency=*/5);
    const Camera cam = wallCamera();
    const Said s = run.frame(7, cam);
    expectReasonsAgreeWithDraws(s, "stop-and-wait");
    const std::vector<uint32_t> hidden = hiddenFieldLeftOut(scene, cam, s);
    ASSERT_GT(hidden.size(), 50u);
    for (uint32_t o : hidden) {
        EXPECT_EQ(s[o].kind, DecisionKind::CulledOnQuery) << o;
        EXPECT_EQ(s[o].query_frame, 7u) << o;
        EXPECT_EQ(s[o].samples, 0u) << o;
        EXPECT_TRUE(s[o].flags & kDecisionWaited) << "stop-and-wait waits for every answer";
    }
    for (uint32_t o = 0; o < scene.wall_count; ++o) {
        if (!s.drawn[o]) continue;
        EXPECT_TRUE(s[o].kind == DecisionKind::DrawnOnQuery ||
                    s[o].kind == DecisionKind::DrawnNearPlane)
            << o << ": " << decisionKindName(s[o].kind);
        if (s[o].kind == DecisionKind::DrawnOnQuery) {
            EXPECT_GT(s[o].samples, 0u) << o;
        }
    }
}

TEST(CullerReasons, StatisticalDrawsWhatItFoundVisibleOnItsStatisticsUntilTheIntervalRunsOut) {
    const WallAndField scene;
    RasterRun run(named("statistical"), scene.boxes);
    const Camera cam = wallCamera();
    const Said first = run.frame(0, cam);
    expectReasonsAgreeWithDraws(first, "statistical frame 0");
    for (uint32_t o : hiddenFieldLeftOut(scene, cam, first)) {
        EXPECT_EQ(first[o].kind, DecisionKind::CulledOnQuery) << o;
        EXPECT_EQ(first[o].query_frame, 0u) << o;
    }
    const Said second = run.frame(1, cam);
    expectReasonsAgreeWithDraws(second, "statistical frame 1");
    uint32_t on_statistics = 0;
    for (uint32_t o = 0; o < scene.wall_count; ++o) {
        if (second[o].kind != DecisionKind::DrawnOnStatistics) continue;
        ++on_statistics;
        // One visible answer (frame 0): BASE_TIME (2/3 s) * (2 - 0.5^1) = 1 s from time 0.
        EXPECT_EQ(second[o].query_frame, 0u) << o;
        EXPECT_EQ(second[o].count, 1u) << o;
        EXPECT_EQ(second[o].history, 1u) << o;
        EXPECT_FLOAT_EQ(second[o].interval, 1.0f) << o;
        EXPECT_FLOAT_EQ(second[o].next_query, 1.0f) << o;
    }
    EXPECT_GT(on_statistics, 0u) << "the wall was found visible at frame 0";
    // The field's last answer said occluded: it is queried again, every frame.
    for (uint32_t o : hiddenFieldLeftOut(scene, cam, second)) {
        EXPECT_EQ(second[o].kind, DecisionKind::CulledOnQuery) << o;
        EXPECT_EQ(second[o].query_frame, 1u) << o;
    }
}

TEST(CullerReasons, ChcCullsPreviouslyInvisibleNodesOnThisFramesAnswersAndDrawsTheVisibleOnes) {
    const WallAndField scene;
    RasterRun run(named("chc"), scene.boxes);
    const Camera cam = wallCamera();
    run.frame(0, cam);
    const Said s = run.frame(1, cam);
    expectReasonsAgreeWithDraws(s, "chc");
    const std::vector<uint32_t> hidden = hiddenFieldLeftOut(scene, cam, s);
    ASSERT_GT(hidden.size(), 50u);
    for (uint32_t o : hidden) {
        EXPECT_EQ(s[o].kind, DecisionKind::CulledOnQuery) << o;
        EXPECT_EQ(s[o].query_frame, 1u) << o;
    }
    // The wall was visible at frame 0: drawn at once, its query (for frame 2) in flight.
    for (uint32_t o = 0; o < scene.wall_count; ++o) {
        if (!s.drawn[o] || s[o].kind == DecisionKind::DrawnNearPlane) continue;
        EXPECT_EQ(s[o].kind, DecisionKind::DrawnQueryInFlight) << o;
        EXPECT_EQ(s[o].query_frame, 1u) << o;
    }
}

TEST(CullerReasons, ChcppCullsTheFieldOnQueriesAndAssumesTheWallVisibleBetweenTests) {
    const WallAndField scene;
    RasterRun run(named("chc++"), scene.boxes);
    const Camera cam = wallCamera();
    uint32_t assumed = 0, multiquery = 0;
    for (uint64_t f = 0; f < 4; ++f) {
        const Said s = run.frame(f, cam);
        expectReasonsAgreeWithDraws(s, "chc++ frame " + std::to_string(f));
        const std::vector<uint32_t> hidden = hiddenFieldLeftOut(scene, cam, s);
        ASSERT_GT(hidden.size(), 50u);
        for (uint32_t o : hidden) {
            EXPECT_EQ(s[o].kind, DecisionKind::CulledOnQuery) << o;
            EXPECT_EQ(s[o].query_frame, f) << o;
            multiquery += (s[o].flags & kDecisionMultiquery) != 0;
        }
        for (uint32_t o = 0; o < scene.wall_count; ++o) {
            if (s[o].kind != DecisionKind::DrawnAssumedVisible) continue;
            ++assumed;
            EXPECT_LT(s[o].query_frame, f) << o;
            EXPECT_GT(s[o].next_query_frame, f) << o;
        }
    }
    EXPECT_GT(assumed, 0u) << "n_av = 2 spares some re-tests";
    EXPECT_GT(multiquery, 0u) << "the field's nodes are grouped into multiqueries";
}

TEST(CullerReasons, HzbDrawsLastFramesVisibleSetInPhaseOneAndCullsTheFieldOnThePyramid) {
    const WallAndField scene;
    RasterRun run(named("hzb"), scene.boxes);
    const Camera cam = wallCamera();
    const Said first = run.frame(0, cam);
    expectReasonsAgreeWithDraws(first, "hzb frame 0");
    for (uint32_t o = 0; o < scene.boxes.size(); ++o) {
        if (first[o].kind == DecisionKind::FrustumCulled) continue;
        // Nothing was visible before frame 0: phase 1 drew nothing, so nothing was tested.
        EXPECT_EQ(first[o].kind, DecisionKind::DrawnOnPyramid) << o;
        EXPECT_EQ(first[o].phase, 2u) << o;
        EXPECT_TRUE(first[o].flags & kDecisionNoPyramid) << o;
    }
    run.frame(1, cam);  // the field drawn in phase 1 (visible at frame 0), then found hidden
    const Said s = run.frame(2, cam);
    expectReasonsAgreeWithDraws(s, "hzb frame 2");
    const std::vector<uint32_t> hidden = hiddenFieldLeftOut(scene, cam, s);
    ASSERT_GT(hidden.size(), 50u);
    for (uint32_t o : hidden) {
        EXPECT_EQ(s[o].kind, DecisionKind::CulledOnPyramid) << o;
        EXPECT_EQ(s[o].phase, 2u) << o;
        EXPECT_NE(s[o].level, Decision::kNoLevel) << o;
    }
    for (uint32_t o = 0; o < scene.wall_count; ++o) {
        if (s[o].kind != DecisionKind::DrawnOnPyramid) continue;
        EXPECT_EQ(s[o].phase, 1u) << o << ": the wall was visible last frame";
    }
}

// A unit cube mesh for every object, placed over its box: what the masked culler rasterises.
struct BoxMeshes {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                     2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    std::vector<MeshRange> meshes{{0, 36, 0, 8}};
    std::vector<uint32_t> object_mesh;
    std::vector<glm::mat4> transforms;

    explicit BoxMeshes(const std::vector<Aabb>& boxes) {
        for (int i = 0; i < 8; ++i)
            positions.emplace_back(i & 1 ? 1.0f : 0.0f, i & 2 ? 1.0f : 0.0f, i & 4 ? 1.0f : 0.0f);
        for (const Aabb& b : boxes) {
            object_mesh.push_back(0);
            // A hair inside its box, so that the mesh never pokes out of it.
            const glm::vec3 size = (b.max - b.min) * 0.999f;
            transforms.push_back(
                glm::scale(glm::translate(glm::mat4(1.0f), b.min + size * 5e-4f), size));
        }
    }
    CullMeshes view() const {
        return {positions, indices, meshes, object_mesh, transforms, {}, {}};
    }
};

TEST(CullerReasons, MaskedCullsTheFieldOnItsTilesOnceTheWallIsRasterised) {
    const WallAndField scene;
    const BoxMeshes meshes(scene.boxes);
    RasterRun run(named("masked"), scene.boxes);
    const Camera cam = wallCamera();
    run.frame(0, cam, meshes.view());
    const Said s = run.frame(1, cam, meshes.view());
    expectReasonsAgreeWithDraws(s, "masked");
    const std::vector<uint32_t> hidden = hiddenFieldLeftOut(scene, cam, s);
    ASSERT_GT(hidden.size(), 50u);
    for (uint32_t o : hidden) EXPECT_EQ(s[o].kind, DecisionKind::CulledOnTiles) << o;
    uint32_t occluders = 0;
    for (uint32_t o = 0; o < scene.wall_count; ++o) {
        if (!s.drawn[o]) continue;
        EXPECT_TRUE(s[o].kind == DecisionKind::DrawnOnTiles ||
                    s[o].kind == DecisionKind::DrawnNearPlane)
            << o;
        occluders += (s[o].flags & kDecisionOccluder) != 0;
    }
    EXPECT_GT(occluders, 0u) << "the wall is rasterised as it is drawn";
}

TEST(CullerReasons, ConditionalSubmitsTheFieldUnderThisFramesQueriesAndTheDeviceSkipsIt) {
    const WallAndField scene;
    RasterRun run(named("conditional"), scene.boxes);
    const Camera cam = wallCamera();
    const Said s = run.frame(5, cam);
    expectReasonsAgreeWithDraws(s, "conditional");
    const std::vector<uint32_t> hidden = hiddenFieldLeftOut(scene, cam, s);
    ASSERT_GT(hidden.size(), 50u);
    for (uint32_t o : hidden) {
        EXPECT_EQ(s[o].kind, DecisionKind::DrawnConditional) << o;
        EXPECT_EQ(s[o].query_frame, 5u) << o;
    }
}

TEST(CullerReasons, IdealDrawsWhatGroundTruthSawAndNothingElse) {
    const WallAndField scene;
    RasterRun run(named("ideal"), scene.boxes);
    const Camera cam = wallCamera();
    const Said s = run.frame(0, cam);
    expectReasonsAgreeWithDraws(s, "ideal");
    for (uint32_t o = 0; o < scene.boxes.size(); ++o) {
        if (s[o].kind == DecisionKind::FrustumCulled) continue;
        EXPECT_EQ(s[o].kind,
                  s.truth[o] ? DecisionKind::DrawnByOracle : DecisionKind::CulledByOracle)
            << o;
    }
}

// A culler that gives no reasons: a plugin that prepares its view without the frame's log.
class Silent final : public Culler {
  public:
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override {
        const PreparedView view = prepareView(frame.view);
        traverseFrontToBack(tree, view, stack_, [&](const NodeVisit& v) {
            drawNodeObjects(tree, v.node, view.frustum, v.inside_frustum, device);
            return true;
        });
    }

  private:
    std::vector<NodeVisit> stack_;
};

TEST(CullerReasons, ACullerThatGivesNoneLeavesNoReasonGivenOnEveryObject) {
    const WallAndField scene;
    RasterRun run(std::make_unique<Silent>(), scene.boxes);
    const Said s = run.frame(0, wallCamera());
    for (uint32_t o = 0; o < scene.boxes.size(); ++o)
        EXPECT_EQ(s[o].kind, DecisionKind::NoReasonGiven) << o;
}

// An object behind the wall for frames 0-5 that is visible from frame 6 on (as a mover stepping
// out from behind it): async's last answer, from a frame before, still says occluded, so it
// misses the object, and its reason names the frame of the query that hid it.
TEST(CullerReasons, AsyncMissesAnObjectThatStepsOutOnTheAnswerOfAnEarlierFramesQuery) {
    const std::vector<Aabb> boxes = testing::gridBoxes(4, 1);
    const BspTree tree = buildTree(boxes, 1);
    const auto culler = named("async");
    culler->reset(tree);
    ScriptedQueryDevice device(6);  // answers arrive six commands later: in a later frame
    DecisionLog log;
    std::vector<Decision> why;
    std::vector<uint32_t> stack;
    const CullView view = testing::overview(boxes);
    const uint32_t mover = 2;
    bool missed = false;
    for (uint64_t f = 0; f < 12; ++f) {
        std::vector<uint8_t> visible(boxes.size(), 1);
        visible[mover] = f >= 6 ? 1 : 0;
        device.setVisibility(visible, boxes);
        device.clearLog();
        log.clear();
        CullFrame frame = makeFrame(view, f, static_cast<double>(f) / 30.0);
        frame.decisions = &log;
        culler->cullAndRender(tree, frame, device);
        resolveDecisions(tree, log.records(), why, stack);
        const auto& d = device.drawnObjects();
        const bool drawn = std::find(d.begin(), d.end(), mover) != d.end();
        EXPECT_EQ(decisionKindDraws(why[mover].kind), drawn ? 1 : 0) << "frame " << f;
        if (f == 6) {
            ASSERT_FALSE(drawn) << "async draws it only once an answer says visible";
            EXPECT_EQ(why[mover].kind, DecisionKind::CulledOnQuery);
            EXPECT_LT(why[mover].query_frame, 6u);
            missed = true;
        }
        if (drawn && f >= 6) {
            EXPECT_EQ(why[mover].kind, DecisionKind::DrawnOnQuery) << "frame " << f;
            EXPECT_GE(why[mover].query_frame, 6u) << "frame " << f;
        }
    }
    EXPECT_TRUE(missed);
}

// The property: over random scenes and a moving camera, every built-in culler gives every object
// a reason, and the reason agrees with what the device drew.
TEST(CullerReasons, EveryBuiltInGivesEveryObjectAReasonThatAgreesWithItsDraws) {
    for (uint32_t scene_seed = 1; scene_seed <= 3; ++scene_seed) {
        const std::vector<Aabb> boxes = testing::randomBoxes(300, scene_seed, 40.0f);
        const BoxMeshes meshes(boxes);
        for (const CullerRow* a : cullerRows()) {
            RasterRun run(makeCuller(*a, CullerOptions{}), boxes, 5, 3);
            for (uint64_t f = 0; f < 6; ++f) {
                const float t = static_cast<float>(f);
                Camera cam = makeCamera({-50.0f + 4.0f * t, 6.0f, 30.0f - 2.0f * t}, {0, 0, 0});
                cam.view.view_projection = cam.view_projection;
                cam.view.viewport_width = 64;
                cam.view.viewport_height = 48;
                const Said s = run.frame(f, cam, a->needs_meshes ? meshes.view() : CullMeshes{});
                expectReasonsAgreeWithDraws(s, std::string(a->name) + " scene " +
                                                   std::to_string(scene_seed) + " frame " +
                                                   std::to_string(f));
            }
        }
    }
}

}  // namespace
}  // namespace occsim
