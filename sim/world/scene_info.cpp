#include "sim/world/scene_info.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "occsim/culling/tree/bsp_tree.h"
#include "sim/world/occluder_roles.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

// The tree's shape and where its objects live, in the lines `occsim info` prints under a heading.
// Objects high in the tree are what hierarchical culling pays for: an object in an inner node is
// drawn whenever its (large) node is visible.
void describeTree(const BspTree& tree, const glm::dvec3& culling_origin, std::ostringstream& out) {
    uint32_t leaves = 0, objects_in_leaves = 0, max_in_leaf = 0;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const BspNode& node = tree.node(n);
        if (!tree.isLive(n) || !node.isLeaf()) continue;
        ++leaves;
        objects_in_leaves += node.object_count;
        max_in_leaf = std::max(max_in_leaf, node.object_count);
    }
    std::vector<uint32_t> by_depth(tree.maxDepth() + 1, 0);
    for (uint32_t o = 0; o < tree.objectCount(); ++o) ++by_depth[tree.node(tree.nodeOf(o)).depth];
    const uint32_t objects = tree.objectCount();
    const uint32_t in_inner = objects - objects_in_leaves;
    char line[256];
    std::snprintf(line, sizeof line, "  nodes       %u (%u leaves), depth %u\n",
                  tree.liveNodeCount(), leaves, tree.maxDepth());
    out << line;
    std::snprintf(
        line, sizeof line,
        "  objects     %.2f per leaf (max %u); %u in inner nodes (%.1f%%), %u in the root\n",
        leaves ? static_cast<double>(objects_in_leaves) / leaves : 0.0, max_in_leaf, in_inner,
        objects ? 100.0 * in_inner / objects : 0.0, tree.node(tree.root()).object_count);
    out << line;
    out << "  by depth   ";
    for (size_t d = 0; d < by_depth.size(); ++d) out << ' ' << d << ':' << by_depth[d];
    out << "\n";
    // The tree lives in the culling frame; the bounds are printed in world coordinates.
    const Aabb& b = tree.bounds(tree.root());
    const glm::dvec3 lo = glm::dvec3(b.min) + culling_origin;
    const glm::dvec3 hi = glm::dvec3(b.max) + culling_origin;
    std::snprintf(line, sizeof line, "  bounds      (%.2f, %.2f, %.2f) .. (%.2f, %.2f, %.2f)\n",
                  lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    out << line;
}

const char* propertyName(AnimatedProperty p) {
    switch (p) {
        case AnimatedProperty::Translation:
            return "translation";
        case AnimatedProperty::Rotation:
            return "rotation";
        case AnimatedProperty::Scale:
            return "scale";
    }
    return "?";
}

const char* interpolationName(Interpolation i) {
    switch (i) {
        case Interpolation::Linear:
            return "LINEAR";
        case Interpolation::Step:
            return "STEP";
        case Interpolation::CubicSpline:
            return "CUBICSPLINE";
    }
    return "?";
}

const char* modeName(AnimationMode m) {
    switch (m) {
        case AnimationMode::Loop:
            return "loop";
        case AnimationMode::Clamp:
            return "clamp";
        case AnimationMode::PingPong:
            return "ping_pong";
    }
    return "?";
}

// Each glTF source's animations: channels (node, property, interpolation), duration, whether it
// plays and how, and the objects it moves (indices within a copy, as movers' "objects" count).
void describeAnimations(const Scene& scene, std::ostringstream& out) {
    for (size_t mi = 0; mi < scene.models.size(); ++mi) {
        const SceneModel& m = scene.models[mi];
        const AnimatedModel& model = *m.model;
        if (model.animations.empty()) continue;
        uint32_t animated_copies = 0;
        for (const ModelCopy& copy : scene.initial_copies) {
            if (copy.model == mi && copy.animated) ++animated_copies;
        }
        out << "animations    source " << m.source << ": " << model.animations.size()
            << (model.animations.size() == 1 ? " animation" : " animations") << ", "
            << animated_copies << " animated copies of " << m.objectsPerCopy() << " objects; "
            << modeName(m.mode) << ", speed " << m.speed << ", time offset " << m.time_offset_s
            << " s\n";
        for (size_t a = 0; a < model.animations.size(); ++a) {
            const NodeAnimation& animation = model.animations[a];
            char line[256];
            std::snprintf(line, sizeof line, "  #%zu %s%s%s  %zu channel%s, %.3f s, %s\n", a,
                          animation.name.empty() ? "" : "'", animation.name.c_str(),
                          animation.name.empty() ? "(unnamed)" : "'", animation.channels.size(),
                          animation.channels.size() == 1 ? "" : "s", animation.duration_s,
                          m.playing[a] ? "plays" : "does not play");
            out << line;
            for (const AnimationChannel& c : animation.channels) {
                const AnimationSampler& sampler = animation.samplers[c.sampler];
                out << "      node " << c.node << " " << propertyName(c.property) << ", "
                    << interpolationName(sampler.interpolation) << ", " << sampler.times.size()
                    << (sampler.times.size() == 1 ? " key\n" : " keys\n");
            }
            const std::vector<uint8_t> moved = model.objectsMovedBy(a);
            std::string list;
            size_t count = 0;
            for (size_t o = 0; o < moved.size(); ++o) {
                if (!moved[o]) continue;
                if (++count > 12) continue;
                if (!list.empty()) list += ' ';
                list += std::to_string(o);
            }
            if (count > 12) list += " ...";
            out << "      moves " << count << " object" << (count == 1 ? "" : "s")
                << " of each copy" << (count ? " (" + list + ")" : std::string()) << "\n";
        }
    }
}

}  // namespace

std::string describeScenario(const Scenario& scenario, std::vector<std::string>& warnings) {
    const Scene scene = buildScene(scenario);
    warnings.insert(warnings.end(), scene.warnings.begin(), scene.warnings.end());
    WorldState state = initialState(scene);
    BspTree tree;
    tree.build(state.boxes, scenario.bsp);

    std::ostringstream out;
    char line[256];
    out << "scenario      " << scenario.name << " (" << scenario.file.string() << ")\n";
    out << "objects       " << scene.objectCount() << " (" << scene.meshes.size() << " meshes)\n";
    out << "triangles     " << scene.triangle_count << "\n";
    out << "movers        " << scene.initial_movers.size() << " (" << state.moved.size()
        << " objects move each frame)\n";
    describeAnimations(scene, out);
    // What masked's occluder pass may use: the roles the scenario and the glTF nodes gave.
    out << "occluders     " << occluderRolesText(countOccluderRoles(scene)) << "\n";
    out << "frames        " << scenario.frames << " x " << scenario.dt_s << " s, " << scenario.width
        << "x" << scenario.height << " pixels\n";
    std::snprintf(line, sizeof line, "bsp           %s split, looseness %.2f, %s\n",
                  scenario.bsp.split_rule == BspSplitRule::Sah ? "sah" : "median",
                  static_cast<double>(scenario.bsp.looseness),
                  scenario.bsp.adapt ? "adapting to movers" : "static cells");
    out << line;
    out << "after build\n";
    describeTree(tree, scene.culling_origin, out);

    // The world layer alone: the movers stepped through every frame of the scenario exactly as a
    // run does (frame 0 shows the initial state), each moved object reinserted and the tree
    // adapted once per frame; nothing is rendered.
    if (!state.moved.empty() && scenario.frames > 1) {
        tree.resetStats();
        const uint64_t version_before = tree.structureVersion();
        for (uint32_t frame = 1; frame < scenario.frames; ++frame) {
            stepMovers(scene, state, scenario.dt_s);
            requireFiniteBoxes(state, frame);
            for (const uint32_t o : state.moved) tree.reinsert(o, state.boxes[o]);
            tree.refitDirtyBounds();
        }
        const BspStats& s = tree.stats();
        out << "after " << scenario.frames - 1 << " steps of the movers\n";
        describeTree(tree, scene.culling_origin, out);
        const double reinserts = s.reinserts ? static_cast<double>(s.reinserts) : 1.0;
        std::snprintf(line, sizeof line,
                      "  reinserts   %llu: %.1f%% kept their node without a walk, %.1f%% moved; "
                      "%.2f nodes walked each\n",
                      static_cast<unsigned long long>(s.reinserts),
                      100.0 * static_cast<double>(s.reinserts_in_place) / reinserts,
                      100.0 * static_cast<double>(s.reinserts_moved) / reinserts,
                      static_cast<double>(s.nodes_walked) / reinserts);
        out << line;
        std::snprintf(line, sizeof line,
                      "  adaptation  %llu splits (%llu nodes), %llu merges, %llu root growths; "
                      "structure version +%llu\n",
                      static_cast<unsigned long long>(s.splits),
                      static_cast<unsigned long long>(s.nodes_created),
                      static_cast<unsigned long long>(s.merges),
                      static_cast<unsigned long long>(s.root_growths),
                      static_cast<unsigned long long>(tree.structureVersion() - version_before));
        out << line;
    }
    out << "algorithm     " << scenario.algorithm << "\n";
    return out.str();
}

}  // namespace occsim
