// The scene most render tests draw, on each backend the build has (the parameter): a wall, a small
// cube hidden behind it and one off to the side, with their boxes and the view from the origin.
#pragma once

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>
#include <vector>

#include "depth_conventions.h"
#include "headless_backends.h"
#include "render/gl_renderer.h"
#include "render/headless_context.h"

namespace occsim {

// A unit cube [-0.5, 0.5]^3 with per-face normals.
inline MeshData cubeMesh() {
    MeshData m;
    const glm::vec3 normals[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                  {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        const glm::vec3 u = glm::abs(n.x) > 0 ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 v = glm::cross(n, u);
        const auto base = static_cast<uint32_t>(m.positions.size());
        for (int k = 0; k < 4; ++k) {
            const float su = (k & 1) ? 0.5f : -0.5f, sv = (k & 2) ? 0.5f : -0.5f;
            m.positions.push_back(0.5f * n + su * u + sv * v);
            m.normals.push_back(n);
        }
        m.indices.insert(m.indices.end(), {base, base + 1, base + 3, base, base + 3, base + 2});
    }
    return m;
}

class RenderTest : public ::testing::TestWithParam<Backend> {
  protected:
    static constexpr uint32_t kW = 128, kH = 96;
    void SetUp() override {
        context_ = createHeadlessContext({GetParam(), {}}, kW, kH);
        renderer_ = std::make_unique<GlRenderer>(kW, kH);
        const MeshData cube = cubeMesh();
        renderer_->uploadMeshes(std::span<const MeshData>(&cube, 1));
        // Object 0: a wall 4 x 4 at z = -5; object 1: a small cube behind it at z = -20;
        // object 2: a small cube off to the side at z = -20, not hidden.
        renderer_->setObjectMeshes(std::vector<uint32_t>{0, 0, 0});
        world_ = {
            glm::translate(glm::dmat4(1.0), {0, 0, -5}) * glm::scale(glm::dmat4(1.0), {4, 4, 0.2}),
            glm::translate(glm::dmat4(1.0), {0, 0, -20}),
            glm::translate(glm::dmat4(1.0), {12, 0, -20})};
        boxes_ = {{{-2, -2, -5.1f}, {2, 2, -4.9f}},
                  {{-0.5f, -0.5f, -20.5f}, {0.5f, 0.5f, -19.5f}},
                  {{11.5f, -0.5f, -20.5f}, {12.5f, 0.5f, -19.5f}}};
        setEye({0, 0, 0});
    }
    // A stereo view (eye_separation > 0) draws into a framebuffer twice kH high, each eye kH.
    void setEye(glm::dvec3 eye, float near_radius = 0.0f, double eye_separation = 0.0) {
        ViewSetup view;
        view.eye = eye;
        view.near_radius = near_radius;
        view.eye_separation_m = eye_separation;
        view.view_rotation = glm::mat4(1.0f);  // looking down -z
        view.projection = reverseZPerspective(glm::radians(90.0f), float(kW) / kH, 0.1f, 1000.0f);
        model_view_.clear();
        for (const glm::dmat4& w : world_) {
            model_view_.push_back(glm::mat4(glm::translate(glm::dmat4(1.0), -eye) * w));
        }
        renderer_->setView(view, model_view_);
    }
    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<GlRenderer> renderer_;
    std::vector<glm::dmat4> world_;
    std::vector<glm::mat4> model_view_;
    std::vector<Aabb> boxes_;
};

}  // namespace occsim
