#include "sim/scene/primitives.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace occsim {

MeshData makeBox(glm::vec3 size) {
    MeshData m;
    const glm::vec3 half(0.5f * size.x, 0.0f, 0.5f * size.z);
    const glm::vec3 lo(-half.x, 0.0f, -half.z), hi(half.x, size.y, half.z);
    // Each face: its normal and its four corners, counter-clockwise seen from outside.
    struct Face {
        glm::vec3 normal;
        glm::vec3 corners[4];
    };
    const Face faces[6] = {
        {{1, 0, 0},
         {{hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}}},
        {{-1, 0, 0},
         {{lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}}},
        {{0, 1, 0},
         {{lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}}},
        {{0, -1, 0},
         {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}}},
        {{0, 0, 1},
         {{lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}}},
        {{0, 0, -1},
         {{hi.x, lo.y, lo.z}, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}}},
    };
    for (const Face& f : faces) {
        const auto base = static_cast<uint32_t>(m.positions.size());
        for (const glm::vec3& c : f.corners) {
            m.positions.push_back(c);
            m.normals.push_back(f.normal);
        }
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return m;
}

MeshData makeCylinder(float radius, float height, uint32_t segments) {
    if (segments < 3) throw std::invalid_argument("makeCylinder: segments must be >= 3");
    MeshData m;
    const float step = 2.0f * std::numbers::pi_v<float> / static_cast<float>(segments);
    // Side: two vertices per segment edge with radial normals (smooth shading).
    for (uint32_t i = 0; i <= segments; ++i) {
        const float a = step * static_cast<float>(i % segments);
        const glm::vec3 n(std::cos(a), 0.0f, -std::sin(a));
        m.positions.push_back(radius * n);
        m.normals.push_back(n);
        m.positions.push_back(radius * n + glm::vec3(0, height, 0));
        m.normals.push_back(n);
    }
    for (uint32_t i = 0; i < segments; ++i) {
        const uint32_t b = 2 * i;
        m.indices.insert(m.indices.end(), {b, b + 2, b + 3, b, b + 3, b + 1});
    }
    // Caps: a fan around a centre vertex each.
    for (int cap = 0; cap < 2; ++cap) {
        const float y = cap ? height : 0.0f;
        const glm::vec3 n(0, cap ? 1.0f : -1.0f, 0);
        const auto centre = static_cast<uint32_t>(m.positions.size());
        m.positions.push_back({0, y, 0});
        m.normals.push_back(n);
        for (uint32_t i = 0; i < segments; ++i) {
            const float a = step * static_cast<float>(i);
            m.positions.push_back({radius * std::cos(a), y, -radius * std::sin(a)});
            m.normals.push_back(n);
        }
        for (uint32_t i = 0; i < segments; ++i) {
            const uint32_t a = centre + 1 + i, b = centre + 1 + (i + 1) % segments;
            if (cap) {
                m.indices.insert(m.indices.end(), {centre, a, b});
            } else {
                m.indices.insert(m.indices.end(), {centre, b, a});
            }
        }
    }
    return m;
}

MeshData makeSphere(float radius, uint32_t segments, uint32_t rings) {
    if (segments < 3 || rings < 2) {
        throw std::invalid_argument("makeSphere: segments must be >= 3 and rings >= 2");
    }
    MeshData m;
    const float pi = std::numbers::pi_v<float>;
    for (uint32_t r = 0; r <= rings; ++r) {
        const float polar = pi * static_cast<float>(r) / static_cast<float>(rings);
        for (uint32_t s = 0; s <= segments; ++s) {
            const float azimuth = 2.0f * pi * static_cast<float>(s) / static_cast<float>(segments);
            const glm::vec3 n(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                              -std::sin(polar) * std::sin(azimuth));
            m.positions.push_back(radius * n + glm::vec3(0, radius, 0));
            m.normals.push_back(n);
        }
    }
    const uint32_t row = segments + 1;
    for (uint32_t r = 0; r < rings; ++r) {
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t a = r * row + s, b = a + row;
            // The pole rows would make zero-area triangles; leave them out.
            if (r != 0) m.indices.insert(m.indices.end(), {a, b, a + 1});
            if (r != rings - 1) m.indices.insert(m.indices.end(), {a + 1, b, b + 1});
        }
    }
    return m;
}

void appendMesh(MeshData& mesh, const MeshData& part, glm::vec3 offset) {
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    for (const glm::vec3& p : part.positions) mesh.positions.push_back(p + offset);
    mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
    for (uint32_t i : part.indices) mesh.indices.push_back(base + i);
}

void appendBox(MeshData& mesh, glm::vec3 lo, glm::vec3 hi) {
    appendMesh(mesh, makeBox(hi - lo), glm::vec3(0.5f * (lo.x + hi.x), lo.y, 0.5f * (lo.z + hi.z)));
}

glm::mat3 scaleMatrix(glm::vec3 scale) {
    glm::mat3 m(0.0f);
    m[0][0] = scale.x;
    m[1][1] = scale.y;
    m[2][2] = scale.z;
    return m;
}

PlacedObject placeUnitBox(uint32_t unit_box_mesh, glm::dvec3 lo, glm::dvec3 hi) {
    PlacedObject o;
    o.mesh = unit_box_mesh;
    // The unit box stands on y = 0 centred in x and z, so its anchor is the middle of the base.
    o.position = glm::dvec3(0.5 * (lo.x + hi.x), lo.y, 0.5 * (lo.z + hi.z));
    o.linear = scaleMatrix(glm::vec3(hi - lo));
    return o;
}

}  // namespace occsim
