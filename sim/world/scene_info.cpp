#include "sim/world/scene_info.h"

#include "culling/bsp_tree.h"
#include "sim/world/world.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace occsim {

std::string describeScenario(const Scenario& scenario, std::vector<std::string>& warnings) {
    const Scene scene = buildScene(scenario);
    warnings.insert(warnings.end(), scene.warnings.begin(), scene.warnings.end());
    const WorldState state = initialState(scene);
    BspTree tree;
    tree.build(state.boxes, scenario.bsp);
    uint32_t leaves = 0, objects_in_leaves = 0, max_in_leaf = 0;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const BspNode& node = tree.node(n);
        if (!node.isLeaf()) continue;
        ++leaves;
        objects_in_leaves += node.object_count;
        max_in_leaf = std::max(max_in_leaf, node.object_count);
    }
    // Where objects live by node depth: straddlers of a split stay in inner nodes, and an object
    // high in the tree is drawn whenever its (large) node is visible.
    std::vector<uint32_t> by_depth(tree.maxDepth() + 1, 0);
    for (uint32_t o = 0; o < tree.objectCount(); ++o) ++by_depth[tree.node(tree.nodeOf(o)).depth];
    const Aabb& b = tree.bounds(tree.root());
    std::ostringstream out;
    char line[256];
    out << "scenario      " << scenario.name << " (" << scenario.file.string() << ")\n";
    out << "objects       " << scene.objectCount() << " (" << scene.meshes.size() << " meshes)\n";
    out << "triangles     " << scene.triangle_count << "\n";
    out << "movers        " << scene.initial_movers.size() << "\n";
    out << "frames        " << scenario.frames << " x " << scenario.dt_s << " s, "
        << scenario.width << "x" << scenario.height << " pixels\n";
    out << "bsp           " << tree.nodeCount() << " nodes, " << leaves << " leaves, depth "
        << tree.maxDepth() << "\n";
    std::snprintf(line, sizeof line, "objects/leaf  %.2f mean, %u max; %u objects in inner nodes\n",
                  leaves ? static_cast<double>(objects_in_leaves) / leaves : 0.0, max_in_leaf,
                  scene.objectCount() - objects_in_leaves);
    out << line;
    out << "objects/depth";
    for (size_t d = 0; d < by_depth.size(); ++d) out << ' ' << d << ':' << by_depth[d];
    out << "\n";
    // The tree lives in the culling frame; the bounds are printed in world coordinates.
    const glm::dvec3 lo = glm::dvec3(b.min) + scene.culling_origin;
    const glm::dvec3 hi = glm::dvec3(b.max) + scene.culling_origin;
    std::snprintf(line, sizeof line, "bounds        (%.2f, %.2f, %.2f) .. (%.2f, %.2f, %.2f)\n", lo.x,
                  lo.y, lo.z, hi.x, hi.y, hi.z);
    out << line;
    out << "algorithm     " << scenario.algorithm << "\n";
    return out.str();
}

}  // namespace occsim
