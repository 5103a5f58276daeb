// Shared set-up for culler tests: random object boxes, a tree over them, and cameras.
#pragma once

#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/geometry/frustum.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/tree/bsp_tree.h"

namespace occsim::testing {

inline std::vector<Aabb> randomBoxes(uint32_t count, uint32_t seed, float extent = 100.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-extent, extent), size(0.1f, 3.0f);
    std::vector<Aabb> boxes;
    for (uint32_t i = 0; i < count; ++i) {
        glm::vec3 lo(pos(rng), pos(rng) * 0.1f, pos(rng));
        boxes.push_back({lo, lo + glm::vec3(size(rng), size(rng), size(rng))});
    }
    return boxes;
}

inline CullView makeView(glm::vec3 eye, glm::vec3 target, float fov_deg = 60.0f, float near = 0.1f,
                         float far = 1000.0f, float aspect = 4.0f / 3.0f) {
    CullView view;
    view.eye = eye;
    const glm::mat4 vp = glm::perspective(glm::radians(fov_deg), aspect, near, far) *
                         glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    view.frustum = frustumFromViewProjection(vp);
    view.near_radius =
        static_cast<float>(nearPlaneCornerDistance(near, glm::radians(fov_deg), aspect));
    return view;
}

// Boxes as the batch frustum kernel reads them: one array per coordinate (structure of arrays).
struct BoxColumns {
    std::vector<float> min_x, min_y, min_z, max_x, max_y, max_z;
    explicit BoxColumns(const std::vector<Aabb>& boxes) {
        for (const Aabb& b : boxes) {
            min_x.push_back(b.min.x);
            min_y.push_back(b.min.y);
            min_z.push_back(b.min.z);
            max_x.push_back(b.max.x);
            max_y.push_back(b.max.y);
            max_z.push_back(b.max.z);
        }
    }
    // classifyBatch over the first `count` boxes.
    template <typename Planes>
    void classify(const Planes& planes, size_t count, FrustumTest* out) const {
        classifyBatch(planes, min_x.data(), min_y.data(), min_z.data(), max_x.data(), max_y.data(),
                      max_z.data(), count, out);
    }
};

// Each object visible with probability p.
inline std::vector<uint8_t> randomVisibility(size_t count, double p, std::mt19937& rng) {
    std::bernoulli_distribution draw(p);
    std::vector<uint8_t> visible(count);
    for (auto& v : visible) v = draw(rng);
    return visible;
}

// Unit cubes on an nx-by-nz grid at height y with gaps between them: split planes fall into the
// gaps, so no object straddles one and every node's bounds stay inside its cell.
inline std::vector<Aabb> gridBoxes(uint32_t nx, uint32_t nz, float y = 0.0f, float spacing = 3.0f) {
    std::vector<Aabb> boxes;
    for (uint32_t z = 0; z < nz; ++z) {
        for (uint32_t x = 0; x < nx; ++x) {
            const glm::vec3 lo(spacing * static_cast<float>(x), y,
                               -spacing * static_cast<float>(z));
            boxes.push_back({lo, lo + glm::vec3(1.0f)});
        }
    }
    return boxes;
}

// A camera far above and behind a field, seeing all of it.
inline CullView overview(const std::vector<Aabb>& boxes) {
    Aabb all;
    for (const Aabb& b : boxes) extend(all, b);
    const glm::vec3 c = center(all);
    const float size = glm::length(extent(all));
    return makeView(c + glm::vec3(0.0f, size, size), c);
}

inline BspTree buildTree(const std::vector<Aabb>& boxes, uint32_t leaf_size = 4,
                         BspSplitRule rule = BspSplitRule::Median) {
    BspTree tree;
    BspBuildOptions options;
    options.max_objects_per_leaf = leaf_size;
    options.split_rule = rule;
    tree.build(boxes, options);
    return tree;
}

// The objects a brute-force per-object frustum test keeps.
inline std::set<uint32_t> inFrustum(const std::vector<Aabb>& boxes, const Frustum& f) {
    std::set<uint32_t> out;
    for (uint32_t o = 0; o < boxes.size(); ++o) {
        if (classify(f, boxes[o]) != FrustumTest::Outside) out.insert(o);
    }
    return out;
}

// A camera: the cullers' view and the OpenGL-convention view-projection a depth raster needs.
struct Camera {
    CullView view;
    glm::mat4 view_projection;
};

inline Camera makeCamera(glm::vec3 eye, glm::vec3 target, float fov_deg = 60.0f, float near = 0.1f,
                         float far = 1000.0f, float aspect = 4.0f / 3.0f) {
    Camera c;
    c.view = makeView(eye, target, fov_deg, near, far, aspect);
    c.view_projection = glm::perspective(glm::radians(fov_deg), aspect, near, far) *
                        glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    return c;
}

// Two unit boxes apart, and a box around both.
struct TwoObjects {
    std::vector<Aabb> boxes{{glm::vec3(0), glm::vec3(1)}, {glm::vec3(5), glm::vec3(6)}};
    Aabb both{glm::vec3(0), glm::vec3(6)};
};

// The registered algorithm of that name (the test fails loudly on a typo).
inline std::unique_ptr<Culler> cullerNamed(std::string_view name, const CullerOptions& options) {
    const CullerRow* algorithm = findCuller(name);
    if (algorithm == nullptr) throw std::invalid_argument("no algorithm " + std::string(name));
    return makeCuller(*algorithm, options);
}

inline CullFrame makeFrame(const CullView& view, uint64_t index, double time_s) {
    CullFrame frame;
    frame.view = view;
    frame.frame_index = index;
    frame.time_s = time_s;
    return frame;
}

// Frustum culling whose planes sit 1.5 m inside the true frustum: it drops objects at the edges
// of the view. Ground truth draws every object and lets the GPU clip, so it shares nothing with
// this mistake: an error metric that works shows it.
class ShrunkenFrustumCuller final : public Culler {
  public:
    void reset(const BspTree& tree) override { inner_->reset(tree); }
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override {
        CullFrame shrunk = frame;
        for (glm::vec4& plane : shrunk.view.frustum.planes) plane.w -= 1.5f;
        inner_->cullAndRender(tree, shrunk, device);
    }

  private:
    std::unique_ptr<Culler> inner_ = makeCuller(*findCuller("vfc"), CullerOptions{});
};

}  // namespace occsim::testing
