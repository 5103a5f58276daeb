#include "occsim/culling/testing/triangle_raster_device.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "occsim/culling/raster/exact_triangle_raster.h"

namespace occsim {

TriangleRasterDevice::TriangleRasterDevice(uint32_t width, uint32_t height,
                                           uint32_t latency_commands)
    : width_(width), height_(height), queries_(latency_commands, "TriangleRasterDevice") {}

void TriangleRasterDevice::beginFrame(const glm::mat4& view_projection, const CullMeshes& meshes) {
    view_projection_ = glm::dmat4(view_projection);
    meshes_ = meshes;
    depth_.assign(static_cast<size_t>(width_) * height_, 0.0);
    truth_.clear();
    drawn_.clear();
}

template <class Fragment>
void TriangleRasterDevice::rasteriseObject(uint32_t object, Fragment&& fragment) const {
    const MeshRange& r = meshes_.meshes[meshes_.object_mesh[object]];
    const glm::dmat4 to_clip = view_projection_ * glm::dmat4(meshes_.object_to_culling[object]);
    for (uint32_t t = 0; t + 2 < r.index_count; t += 3) {
        glm::dvec4 v[3];
        for (uint32_t k = 0; k < 3; ++k) {
            const glm::vec3 p =
                meshes_.positions[r.first_vertex + meshes_.indices[r.first_index + t + k]];
            v[k] = to_clip * glm::dvec4(glm::dvec3(p), 1.0);
        }
        rasteriseExactTriangle(v[0], v[1], v[2], width_, height_, fragment);
    }
}

void TriangleRasterDevice::drawObject(uint32_t object) {
    drawn_.push_back(object);
    queries_.countDraw();
    ++counters_.objects_drawn;
    if (object >= meshes_.object_mesh.size()) return;  // no mesh given for it: nothing to draw
    rasteriseObject(object, [&](size_t p, double iw) { depth_[p] = std::max(depth_[p], iw); });
}

uint64_t TriangleRasterDevice::boxSamples(const Aabb& box, const std::vector<double>& depth) const {
    double w_min = INFINITY, x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 corner(c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y,
                                c & 4 ? box.max.z : box.min.z);
        const glm::dvec4 v = view_projection_ * glm::dvec4(corner, 1.0);
        if (!(v.z >= -v.w))
            return static_cast<uint64_t>(width_) * height_;  // reaches the near plane
        w_min = std::min(w_min, v.w);
        x_lo = std::min(x_lo, (v.x / v.w + 1.0) * 0.5 * width_);
        x_hi = std::max(x_hi, (v.x / v.w + 1.0) * 0.5 * width_);
        y_lo = std::min(y_lo, (v.y / v.w + 1.0) * 0.5 * height_);
        y_hi = std::max(y_hi, (v.y / v.w + 1.0) * 0.5 * height_);
    }
    const double nearest = 1.0 / w_min;
    uint64_t samples = 0;
    const int j0 = std::max(0.0, std::ceil(x_lo - 0.5)), i0 = std::max(0.0, std::ceil(y_lo - 0.5));
    const int j1 = std::min(width_ - 1.0, std::floor(x_hi - 0.5));
    const int i1 = std::min(height_ - 1.0, std::floor(y_hi - 0.5));
    for (int i = i0; i <= i1; ++i) {
        for (int j = j0; j <= j1; ++j)
            samples += nearest >= depth[static_cast<size_t>(i) * width_ + j];
    }
    return samples;
}

QueryId TriangleRasterDevice::issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag>) {
    uint64_t samples = 0;
    for (const Aabb& box : boxes) samples += boxSamples(box, depth_);
    return queries_.issue(samples, boxes.size(), counters_);
}

bool TriangleRasterDevice::isQueryReady(QueryId id) { return queries_.ready(id); }

QueryAnswer TriangleRasterDevice::takeAnswer(QueryId id) { return queries_.take(id, counters_); }

std::vector<uint8_t> TriangleRasterDevice::groundTruth() {
    const uint32_t objects = static_cast<uint32_t>(meshes_.object_mesh.size());
    truth_.assign(static_cast<size_t>(width_) * height_, 0.0);
    for (uint32_t o = 0; o < objects; ++o) {
        rasteriseObject(o, [&](size_t p, double iw) { truth_[p] = std::max(truth_[p], iw); });
    }
    std::vector<uint8_t> visible(objects, 0);
    for (uint32_t o = 0; o < objects; ++o) {
        rasteriseObject(o, [&](size_t p, double iw) { visible[o] |= iw >= truth_[p] ? 1 : 0; });
    }
    return visible;
}

bool TriangleRasterDevice::boxHiddenInTruth(const Aabb& box) const {
    assert(!truth_.empty());
    return boxSamples(box, truth_) == 0;
}

}  // namespace occsim
