// Scenes the masked depth buffer's and culler's tests share: a camera composed in double as the
// simulation does, and random scenes of cubes and quads as the simulation hands them to cullers.
#pragma once

#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/contract/culler.h"
#include "occsim/culling/raster/masked_depth_buffer.h"

namespace occsim::testing {

// A camera at `eye` looking at `target`, composed in double as the simulation does.
inline CullView cameraView(glm::dvec3 eye, glm::dvec3 target, uint32_t width, uint32_t height,
                           double near = 0.1, double far = 1000.0, double fov_deg = 90.0) {
    const double aspect = static_cast<double>(width) / height;
    const glm::dvec3 forward = glm::normalize(target - eye);
    const glm::dvec3 up = std::abs(forward.y) > 0.999 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
    const glm::dmat4 vp = glm::perspective(glm::radians(fov_deg), aspect, near, far) *
                          glm::lookAt(eye, eye + forward, up);
    CullView view;
    view.eye = glm::vec3(eye);
    view.frustum = frustumFromViewProjection(vp);
    view.near_radius =
        static_cast<float>(nearPlaneCornerDistance(near, glm::radians(fov_deg), aspect));
    view.view_projection = glm::mat4(vp);
    view.viewport_width = width;
    view.viewport_height = height;
    return view;
}

// The rule tests about coverage look at single pixels: their buffer lets the working layer hide
// boxes, so that a pixel's own coverage shows without a whole cell filling.
inline MaskedLayout everyPixel(uint32_t cell_width = 8, uint32_t cell_height = 4) {
    MaskedLayout layout;
    layout.cell_width = cell_width;
    layout.cell_height = cell_height;
    layout.test_working_layer = true;
    return layout;
}

// Meshes and objects as the simulation hands them to cullers (CullMeshes).
struct TestScene {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    std::vector<MeshRange> meshes;
    std::vector<uint32_t> object_mesh;
    std::vector<glm::mat4> transforms;
    std::vector<Aabb> boxes;
    std::vector<uint8_t> occluder;        // per object, kOccluder*; empty: every one by size
    std::vector<uint32_t> occluder_mesh;  // per object, kNoOccluderMesh or a mesh; may be empty

    uint32_t addMesh(std::vector<glm::vec3> p, std::vector<uint32_t> i) {
        meshes.push_back({static_cast<uint32_t>(indices.size()), static_cast<uint32_t>(i.size()),
                          static_cast<uint32_t>(positions.size()),
                          static_cast<uint32_t>(p.size())});
        positions.insert(positions.end(), p.begin(), p.end());
        indices.insert(indices.end(), i.begin(), i.end());
        return static_cast<uint32_t>(meshes.size() - 1);
    }
    void addObject(uint32_t mesh, const glm::dmat4& to_culling) {
        object_mesh.push_back(mesh);
        transforms.push_back(glm::mat4(to_culling));
        const MeshRange& r = meshes[mesh];
        Aabb box;
        for (uint32_t v = 0; v < r.vertex_count; ++v) {
            // As the simulation does: in double, rounded outward to float.
            const glm::dvec3 p =
                glm::dvec3(glm::dmat4(transforms.back()) *
                           glm::dvec4(glm::dvec3(positions[r.first_vertex + v]), 1.0));
            extend(box, glm::vec3(p));
            for (int k = 0; k < 3; ++k) {
                box.min[k] =
                    std::min(box.min[k], std::nextafter(static_cast<float>(p[k]), -INFINITY));
                box.max[k] =
                    std::max(box.max[k], std::nextafter(static_cast<float>(p[k]), INFINITY));
            }
        }
        boxes.push_back(box);
    }
    // Every object's box again from its mesh and transform, after either changed.
    void recomputeBoxes() {
        boxes.clear();
        const std::vector<glm::mat4> old_transforms = transforms;
        const std::vector<uint32_t> old_meshes = object_mesh;
        transforms.clear();
        object_mesh.clear();
        for (size_t o = 0; o < old_meshes.size(); ++o)
            addObject(old_meshes[o], glm::dmat4(old_transforms[o]));
    }
    CullMeshes view() const {
        return CullMeshes{positions,  indices,  meshes,       object_mesh,
                          transforms, occluder, occluder_mesh};
    }
};

inline uint32_t cubeMesh(TestScene& s) {
    std::vector<glm::vec3> p;
    for (int i = 0; i < 8; ++i)
        p.emplace_back(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f);
    return s.addMesh(p, {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                         2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5});
}

inline uint32_t quadMesh(TestScene& s) {
    return s.addMesh({{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}},
                     {0, 1, 2, 0, 2, 3});
}

struct RandomCase {
    TestScene scene;
    CullView view;
};

// Objects (cubes, walls, thin slabs, single triangles) in a 40 m region, a camera somewhere in
// it (sometimes inside an object or against a surface), odd viewport sizes, deep depth ranges,
// and sometimes the whole thing a million metres from the culling frame's origin.
inline RandomCase randomCase(uint32_t seed, bool large_viewport = false, bool full_hd = false) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    RandomCase c;
    TestScene& s = c.scene;
    const uint32_t cube = cubeMesh(s), quad = quadMesh(s);
    const uint32_t tri =
        s.addMesh({{-0.5f, -0.5f, 0}, {0.7f, -0.2f, 0.1f}, {0.0f, 0.6f, -0.2f}}, {0, 1, 2});
    const glm::dvec3 offset = u(rng) < 0.2 ? glm::dvec3(1e6, -3e5, 2e6) : glm::dvec3(0.0);
    const uint32_t objects = 20 + static_cast<uint32_t>(u(rng) * 60);
    for (uint32_t o = 0; o < objects; ++o) {
        const glm::dvec3 at =
            offset + glm::dvec3(u(rng) * 40 - 20, u(rng) * 10 - 5, u(rng) * 40 - 20);
        glm::dvec3 size(0.3 + u(rng) * 6, 0.3 + u(rng) * 6, 0.3 + u(rng) * 6);
        const double kind = u(rng);
        uint32_t mesh = cube;
        if (kind < 0.3) {
            mesh = quad;
        } else if (kind < 0.4) {
            mesh = tri;
        } else if (kind < 0.55) {
            size[static_cast<int>(u(rng) * 3) % 3] = 0.01;  // a thin slab
        }
        glm::dmat4 m = glm::translate(glm::dmat4(1.0), at);
        m = glm::rotate(m, u(rng) * 6.3,
                        glm::normalize(glm::dvec3(u(rng), u(rng) + 0.5, u(rng)) - 0.4));
        s.addObject(mesh, glm::scale(m, size));
    }
    glm::dvec3 eye = offset + glm::dvec3(u(rng) * 30 - 15, u(rng) * 6 - 3, u(rng) * 30 - 15);
    if (u(rng) < 0.2) {
        // Against or inside an object.
        const Aabb& b = s.boxes[static_cast<size_t>(u(rng) * objects) % objects];
        eye = offset + glm::dvec3(b.min) + (glm::dvec3(b.max) - glm::dvec3(b.min)) * u(rng);
    }
    const glm::dvec3 target = eye + glm::dvec3(u(rng) - 0.5, u(rng) * 0.6 - 0.3, u(rng) - 0.5);
    uint32_t width = large_viewport ? 301 + static_cast<uint32_t>(u(rng) * 700)
                                    : 17 + static_cast<uint32_t>(u(rng) * 180);
    uint32_t height = large_viewport ? 171 + static_cast<uint32_t>(u(rng) * 400)
                                     : 9 + static_cast<uint32_t>(u(rng) * 120);
    if (full_hd) {
        width = 1920;
        height = 1080;
    }
    const double near = u(rng) < 0.3 ? 1e-3 : 0.05 + u(rng) * 0.3;
    const double far = u(rng) < 0.3 ? 1e6 : 200.0;
    c.view =
        cameraView(eye - offset, target - offset, width, height, near, far, 40.0 + u(rng) * 60);
    // Into the culling frame: the objects relative to the offset, as the simulation does.
    for (glm::mat4& t : s.transforms) {
        t = glm::mat4(glm::translate(glm::dmat4(1.0), -offset) * glm::dmat4(t));
    }
    s.recomputeBoxes();
    return c;
}

}  // namespace occsim::testing
