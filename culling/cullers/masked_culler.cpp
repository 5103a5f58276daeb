// Hasselgren, Andersson & Akenine-Möller, "Masked Software Occlusion Culling", HPG 2016, as a
// culler over the BSP tree: see masked_culler.h and docs/masked.md.
#include "culling/cullers/masked_culler.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "occsim/culling/declaration/culler_row.h"
#include "occsim/culling/declaration/option_table.h"
#include "occsim/culling/geometry/query_box.h"

namespace occsim {

namespace {

// Every point of `box` strictly on the inner side of `plane` (Frustum's convention), with room for
// the plane's rounding.
bool whollyInside(const Aabb& box, const glm::vec4& plane) {
    const glm::vec3 n(plane);
    const glm::vec3 nearest(n.x >= 0.0f ? box.min.x : box.max.x,
                            n.y >= 0.0f ? box.min.y : box.max.y,
                            n.z >= 0.0f ? box.min.z : box.max.z);
    const float reach = std::max(
        {std::abs(nearest.x), std::abs(nearest.y), std::abs(nearest.z), std::abs(plane.w)});
    return glm::dot(n, nearest) + plane.w > 1e-5f * (reach + 1.0f);
}

MaskedLayout layoutOf(const MaskedOptions& o) {
    MaskedLayout layout;
    layout.cell_width = o.cell_width;
    layout.cell_height = o.cell_height;
    layout.merge = o.accurate_merge ? MaskedMerge::Accurate : MaskedMerge::Quick;
    layout.test_working_layer = o.working_layer_test;
    return layout;
}

}  // namespace

MaskedCuller::MaskedCuller(const MaskedOptions& options)
    : options_(options),
      buffer_(options.simd ? MaskedKernel::Avx2 : MaskedKernel::Plain, layoutOf(options)) {}

void MaskedCuller::reset(const BspTree& tree) {
    drawn_last_.clear();
    drawn_now_.clear();
    rasterised_in_.assign(tree.objectCount(), 0);
    occluder_in_.assign(tree.objectCount(), 0);
    stamp_ = 0;
    welded_.clear();
    neighbours_.clear();
    has_neighbours_.clear();
}

bool MaskedCuller::mayBeVisible(const Aabb& box, const CullView& view) {
    return nearPlaneTouchesBox(box, view.eye, view.near_radius) || buffer_.testBox(box);
}

void MaskedCuller::tryOccluder(const BspTree& tree, const CullMeshes& meshes, uint32_t object) {
    if (rasterised_in_[object] == stamp_) return;
    rasterised_in_[object] = stamp_;
    if (object >= meshes.object_mesh.size() || object >= meshes.object_to_culling.size()) return;
    const uint8_t role =
        object < meshes.object_occluder.size() ? meshes.object_occluder[object] : kOccluderBySize;
    if (role == kOccluderNever) return;
    const Aabb& box = tree.objectBox(object);
    uint32_t mesh = meshes.object_mesh[object];
    // Its inscribed occluder mesh where it has one, unless the eye may be inside its box: from
    // there the object's surface need not lie in front of what is inside it. An orthographic
    // view's rays start on its near plane: the box must lie wholly beyond it.
    const bool eye_outside =
        orthographic_view_
            ? whollyInside(box, near_plane_)
            : !nearPlaneTouchesBox(box, view_eye_, view_near_radius_) && !contains(box, view_eye_);
    if (options_.simplified_occluders && object < meshes.object_occluder_mesh.size() &&
        meshes.object_occluder_mesh[object] != kNoOccluderMesh && eye_outside) {
        mesh = meshes.object_occluder_mesh[object];
    }
    if (mesh >= meshes.meshes.size()) return;
    const MeshRange& r = meshes.meshes[mesh];
    if (uint64_t{r.first_vertex} + r.vertex_count > meshes.positions.size() ||
        uint64_t{r.first_index} + r.index_count > meshes.indices.size()) {
        return;
    }
    const uint32_t triangles = r.index_count / 3;
    if (triangles == 0 || triangles > budget_) return;
    if (role != kOccluderAlways && buffer_.screenExtent(box) < options_.occluder_size) return;
    budget_ -= triangles;
    ++occluders_;
    occluder_in_[object] = stamp_;
    const std::span<const uint32_t> indices = meshes.indices.subspan(r.first_index, r.index_count);
    const std::span<const glm::vec3> positions =
        meshes.positions.subspan(r.first_vertex, r.vertex_count);
    if (has_neighbours_.size() != meshes.meshes.size()) {
        has_neighbours_.assign(meshes.meshes.size(), 0);
        welded_.assign(meshes.meshes.size(), {});
        neighbours_.assign(meshes.meshes.size(), {});
    }
    if (!has_neighbours_[mesh]) {
        // Once per mesh and run.
        welded_[mesh] = weldedIndices(positions, indices);
        neighbours_[mesh] = edgeNeighbours(welded_[mesh]);
        has_neighbours_[mesh] = 1;
    }
    buffer_.rasteriseMesh(positions, welded_[mesh], meshes.object_to_culling[object],
                          neighbours_[mesh]);
}

void MaskedCuller::rasteriseOccluders(const BspTree& tree, const CullFrame& frame) {
    candidates_.clear();
    const glm::vec3 eye = frame.view.eye;
    for (uint32_t o = 0; o < tree.objectCount(); ++o) {
        const Aabb& box = tree.objectBox(o);
        if (classify(view_.frustum, box) == FrustumTest::Outside) continue;
        const uint8_t role = o < frame.meshes.object_occluder.size()
                                 ? frame.meshes.object_occluder[o]
                                 : kOccluderBySize;
        if (role == kOccluderNever) continue;
        if (role != kOccluderAlways && buffer_.screenExtent(box) < options_.occluder_size) continue;
        const glm::vec3 nearest = glm::clamp(eye, box.min, box.max);
        const glm::vec3 d = nearest - eye;
        candidates_.push_back({glm::dot(d, d), o});
    }
    // Nearest first; the object index breaks ties, so that the order is the same on every run.
    std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
        return a.distance2 < b.distance2 || (a.distance2 == b.distance2 && a.object < b.object);
    });
    for (const Candidate& c : candidates_) {
        if (budget_ == 0) break;
        // An occluder the buffer already hides would change nothing: every cell it reaches holds
        // a reference nearer than all of it.
        if (!mayBeVisible(tree.objectBox(c.object), frame.view)) continue;
        tryOccluder(tree, frame.meshes, c.object);
    }
}

void MaskedCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                 RenderDevice& device) {
    view_ = prepareView(frame);
    view_eye_ = frame.view.eye;
    view_near_radius_ = frame.view.near_radius;
    orthographic_view_ = frame.view.kind == ViewKind::Light;
    near_plane_ = frame.view.frustum.planes[4];
    if (rasterised_in_.size() != tree.objectCount()) {
        rasterised_in_.assign(tree.objectCount(), 0);
        occluder_in_.assign(tree.objectCount(), 0);
    }
    ++stamp_;
    occluders_ = 0;
    budget_ = options_.occluder_triangles;
    if (frame.view.kind == ViewKind::Light) {  // a light's view is orthographic
        buffer_.beginOrthographicFrame(frame.view.view_projection, frame.view.viewport_width,
                                       frame.view.viewport_height, options_.width);
    } else {
        buffer_.beginFrame(frame.view.view_projection, frame.view.eye, frame.view.viewport_width,
                           frame.view.viewport_height, options_.width);
    }
    // Without meshes (a caller that gives none) nothing occludes: every box is found visible.
    const CullMeshes& meshes = frame.meshes;
    const bool have_meshes = meshes.object_mesh.size() == tree.objectCount();

    if (have_meshes && !options_.drawn_occluders) rasteriseOccluders(tree, frame);
    if (have_meshes && options_.drawn_occluders && options_.last_drawn_first) {
        for (const uint32_t o : drawn_last_) {
            if (o < tree.objectCount() &&
                classify(view_.frustum, tree.objectBox(o)) != FrustumTest::Outside) {
                tryOccluder(tree, meshes, o);
            }
        }
    }
    drawn_now_.clear();
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        if (!mayBeVisible(tree.bounds(visit.node), frame.view)) {
            recordDecision(view_.decisions, QueryTag::node(visit.node),
                           decisionOf(DecisionKind::CulledOnTiles));
            return false;
        }
        forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum, [&](uint32_t o) {
            const Aabb& box = tree.objectBox(o);
            const bool near = nearPlaneTouchesBox(box, frame.view.eye, frame.view.near_radius);
            if (!near && !buffer_.testBox(box)) {
                recordDecision(view_.decisions, QueryTag::object(o),
                               decisionOf(DecisionKind::CulledOnTiles));
                return;
            }
            device.drawObject(o);
            drawn_now_.push_back(o);
            if (have_meshes && options_.drawn_occluders) tryOccluder(tree, meshes, o);
            if (view_.decisions) {
                Decision why =
                    decisionOf(near ? DecisionKind::DrawnNearPlane : DecisionKind::DrawnOnTiles);
                if (occluder_in_[o] == stamp_) why.flags |= kDecisionOccluder;
                view_.decisions->add(QueryTag::object(o), why);
            }
        });
        return true;
    });
    std::swap(drawn_last_, drawn_now_);
}

// --- Registration -------------------------------------------------------------------------------

namespace {

const OptionTable<MaskedOptions>& maskedOptionTable() {
    using O = MaskedOptions;
    static const OptionTable<O> table = {
        integerOption(OCCSIM_OPTION_MEMBER(O, width), "pixels", 0, 8192,
                      "the software depth buffer's width at most: the viewport divided by the "
                      "smallest whole number that fits; 0 = the viewport's"),
        integerOption(OCCSIM_OPTION_MEMBER(O, cell_width), "pixels", 8, 32,
                      "a depth cell's width (8, 16 or 32): two depths per cell"),
        integerOption(OCCSIM_OPTION_MEMBER(O, cell_height), "pixels", 4, 8,
                      "a depth cell's height (4 or 8)"),
        booleanOption(OCCSIM_OPTION_MEMBER(O, accurate_merge),
                      "cells keep whichever of merging, replacing and dropping a triangle leaves "
                      "the nearest bounds; off = the paper's quick rule"),
        booleanOption(OCCSIM_OPTION_MEMBER(O, working_layer_test),
                      "boxes may be hidden by the working layer where its mask holds them; off "
                      "= the reference layer only, as in the paper"),
        actingOn(tunable(numberOption(OCCSIM_OPTION_MEMBER(O, occluder_size), "viewport heights",
                                      0.0, std::numeric_limits<double>::infinity(),
                                      "an object occludes when its box's projection is at least "
                                      "this large (its larger side)"),
                         0.0, 0.5),
                 OptionScope::OccludersBySize),
        booleanOption(OCCSIM_OPTION_MEMBER(O, simplified_occluders),
                      "an object with an inscribed occluder mesh (fewer triangles) occludes with "
                      "it, when the eye is outside its box; off = every object with its own mesh"),
        booleanOption(OCCSIM_OPTION_MEMBER(O, drawn_occluders),
                      "the drawn objects are the occluders, each as it is drawn; off = an "
                      "occluder pass first over every large object in the frustum, nearest first"),
        switchable(booleanOption(OCCSIM_OPTION_MEMBER(O, last_drawn_first),
                                 "with drawn_occluders: last frame's drawn occluders are "
                                 "rasterised before the traversal; off = each as it is drawn"),
                   0.0),
        integerOption(OCCSIM_OPTION_MEMBER(O, occluder_triangles), "triangles", 0, 4294967295.0,
                      "occluder triangles rasterised per frame at most"),
        booleanOption(OCCSIM_OPTION_MEMBER(O, simd),
                      "AVX2 kernels where the CPU has them (same decisions as the plain path)"),
    };
    return table;
}

}  // namespace

CullerRow maskedRegistration() {
    CullerRow t;
    t.name = "masked";
    t.summary = "masked software occlusion culling on the CPU (Hasselgren et al. 2016)";
    t.needs_meshes = true;
    t.options = maskedOptionTable().descriptor(MaskedOptions{});
    t.factory = [](const CullerContext& c) -> std::unique_ptr<Culler> {
        return std::make_unique<MaskedCuller>(maskedOptionTable().read(c.options));
    };
    t.validate = [](const OptionValues& values) -> std::string {
        const std::string problem = validMaskedLayout(layoutOf(maskedOptionTable().read(values)));
        return problem.empty() ? problem : "cell_width, cell_height: " + problem;
    };
    return t;
}

}  // namespace occsim
