// Frustum plane extraction and box classification, checked against clip-space brute force.
//
// The classification is exact for the conservative criterion: a box is Outside exactly when all
// eight corners violate one common clip plane, and Inside exactly when all eight corners are
// inside the clip volume. The brute force evaluates those clip-plane inequalities (w + x >= 0,
// w - x >= 0, ...) on corners transformed to clip space, with a small tolerance band in which
// either answer is accepted (float rounding differs between the two computations).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/geometry/frustum.h"

namespace occsim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

struct Camera {
    glm::vec3 eye;
    glm::mat4 view_projection;
};

Camera makeCamera(glm::vec3 eye, glm::vec3 target, float fovy_degrees, float aspect, float near,
                  float far) {
    const glm::mat4 projection = glm::perspective(glm::radians(fovy_degrees), aspect, near, far);
    const glm::mat4 view = glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
    return Camera{eye, projection * view};
}

// Signed value of each clip plane at a clip-space point, in the Frustum's plane order, and the
// magnitude of the terms involved (for a relative tolerance).
struct ClipPlaneValues {
    std::array<double, 6> value;
    std::array<double, 6> scale;
};

ClipPlaneValues clipPlaneValues(const glm::mat4& view_projection, glm::vec3 p) {
    const glm::vec4 c = view_projection * glm::vec4(p, 1.0f);
    ClipPlaneValues v{};
    const double coordinate[3] = {c.x, c.y, c.z};
    for (int axis = 0; axis < 3; ++axis) {
        v.value[2 * axis] = double(c.w) + coordinate[axis];      // left, bottom, near
        v.value[2 * axis + 1] = double(c.w) - coordinate[axis];  // right, top, far
        v.scale[2 * axis] = v.scale[2 * axis + 1] = std::fabs(c.w) + std::fabs(coordinate[axis]);
    }
    return v;
}

enum class Verdict { DefinitelyOutside, DefinitelyInside, Borderline };

Verdict planeVerdict(const ClipPlaneValues& v, int plane) {
    const double tolerance = 1e-4 * (1.0 + v.scale[plane]);
    if (v.value[plane] < -tolerance) return Verdict::DefinitelyOutside;
    if (v.value[plane] > tolerance) return Verdict::DefinitelyInside;
    return Verdict::Borderline;
}

std::array<glm::vec3, 8> cornersOf(const Aabb& box) {
    std::array<glm::vec3, 8> corners;
    for (int i = 0; i < 8; ++i) {
        corners[i] = glm::vec3((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                               (i & 4) ? box.max.z : box.min.z);
    }
    return corners;
}

const char* name(FrustumTest t) {
    switch (t) {
        case FrustumTest::Outside:
            return "Outside";
        case FrustumTest::Intersects:
            return "Intersects";
        case FrustumTest::Inside:
            return "Inside";
    }
    return "?";
}

TEST(Frustum, IdentityMatrixGivesTheClipCubeFacesInLeftRightBottomTopNearFarOrder) {
    const Frustum f = frustumFromViewProjection(glm::mat4(1.0f));
    const glm::vec4 expected[6] = {
        {1.0f, 0.0f, 0.0f, 1.0f}, {-1.0f, 0.0f, 0.0f, 1.0f},  // left, right
        {0.0f, 1.0f, 0.0f, 1.0f}, {0.0f, -1.0f, 0.0f, 1.0f},  // bottom, top
        {0.0f, 0.0f, 1.0f, 1.0f}, {0.0f, 0.0f, -1.0f, 1.0f},  // near, far
    };
    for (int p = 0; p < 6; ++p) {
        for (int i = 0; i < 4; ++i) {
            EXPECT_FLOAT_EQ(f.planes[p][i], expected[p][i])
                << "plane " << p << " coefficient " << i;
        }
    }
}

TEST(Frustum, PerspectivePlanesAreNormalisedInwardAndGiveWorldDistances) {
    const float fovy = glm::radians(60.0f);
    const float aspect = 16.0f / 9.0f;
    const glm::mat4 vp =
        glm::perspective(fovy, aspect, 0.5f, 50.0f) *
        glm::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const Frustum f = frustumFromViewProjection(vp);
    for (int p = 0; p < 6; ++p) {
        EXPECT_NEAR(glm::length(glm::vec3(f.planes[p])), 1.0f, 1e-5f) << "plane " << p;
    }

    // A point on the view axis 5 units ahead: its distance to each side plane (through the eye)
    // is 5 * sin(half field of view); to the near and far planes, 5 - near and far - 5.
    const glm::vec4 on_axis(0.0f, 0.0f, -5.0f, 1.0f);
    const float half_horizontal = std::atan(aspect * std::tan(0.5f * fovy));
    const float half_vertical = 0.5f * fovy;
    const float expected[6] = {5.0f * std::sin(half_horizontal),
                               5.0f * std::sin(half_horizontal),
                               5.0f * std::sin(half_vertical),
                               5.0f * std::sin(half_vertical),
                               4.5f,
                               45.0f};
    for (int p = 0; p < 6; ++p) {
        EXPECT_NEAR(glm::dot(f.planes[p], on_axis), expected[p], 1e-3f) << "plane " << p;
    }

    // Points pushed out through one face violate exactly that face's plane.
    const glm::vec4 beyond[6] = {
        {-100.0f, 0.0f, -5.0f, 1.0f}, {100.0f, 0.0f, -5.0f, 1.0f},  // left, right
        {0.0f, -100.0f, -5.0f, 1.0f}, {0.0f, 100.0f, -5.0f, 1.0f},  // bottom, top
        {0.0f, 0.0f, -0.25f, 1.0f},   {0.0f, 0.0f, -60.0f, 1.0f},   // near, far
    };
    for (int face = 0; face < 6; ++face) {
        for (int p = 0; p < 6; ++p) {
            const float distance = glm::dot(f.planes[p], beyond[face]);
            if (p == face) {
                EXPECT_LT(distance, 0.0f) << "point beyond face " << face << ", plane " << p;
            } else {
                EXPECT_GT(distance, 0.0f) << "point beyond face " << face << ", plane " << p;
            }
        }
    }
}

// Random boxes around a perspective camera; each answer is checked against the clip-space
// corners. Returns how many boxes fell in each category so callers can check coverage.
std::array<int, 3> checkRandomBoxesAgainstClipSpace(const Camera& camera, uint32_t seed,
                                                    int box_count) {
    const Frustum f = frustumFromViewProjection(camera.view_projection);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> offset(-40.0f, 40.0f);
    std::uniform_real_distribution<float> log_size(std::log(0.01f), std::log(30.0f));
    std::array<int, 3> counts{};
    for (int i = 0; i < box_count; ++i) {
        const glm::vec3 centre = camera.eye + glm::vec3(offset(rng), offset(rng), offset(rng));
        glm::vec3 size(std::exp(log_size(rng)), std::exp(log_size(rng)), std::exp(log_size(rng)));
        if (i % 17 == 0) size.x = 0.0f;  // flat boxes are valid boxes
        const Aabb box = makeAabb(centre - 0.5f * size, centre + 0.5f * size);
        const FrustumTest result = classify(f, box);
        ++counts[static_cast<int>(result)];

        std::array<ClipPlaneValues, 8> corner_values;
        const auto corners = cornersOf(box);
        for (int c = 0; c < 8; ++c) {
            corner_values[c] = clipPlaneValues(camera.view_projection, corners[c]);
        }

        // Per plane: are all corners surely outside it / possibly outside it?
        bool some_plane_surely_excludes_all = false;
        bool some_plane_possibly_excludes_all = false;
        bool all_corners_surely_inside = true;
        bool all_corners_possibly_inside = true;
        bool some_corner_surely_inside = false;
        for (int p = 0; p < 6; ++p) {
            bool all_surely_outside = true;
            bool all_possibly_outside = true;
            for (int c = 0; c < 8; ++c) {
                const Verdict v = planeVerdict(corner_values[c], p);
                all_surely_outside &= v == Verdict::DefinitelyOutside;
                all_possibly_outside &= v != Verdict::DefinitelyInside;
                all_corners_surely_inside &= v == Verdict::DefinitelyInside;
                all_corners_possibly_inside &= v != Verdict::DefinitelyOutside;
            }
            some_plane_surely_excludes_all |= all_surely_outside;
            some_plane_possibly_excludes_all |= all_possibly_outside;
        }
        for (int c = 0; c < 8; ++c) {
            bool inside = true;
            for (int p = 0; p < 6; ++p) {
                inside &= planeVerdict(corner_values[c], p) == Verdict::DefinitelyInside;
            }
            some_corner_surely_inside |= inside;
        }

        const auto describe = [&] {
            return ::testing::Message()
                   << "box " << i << " min (" << box.min.x << ", " << box.min.y << ", " << box.min.z
                   << ") max (" << box.max.x << ", " << box.max.y << ", " << box.max.z
                   << ") classified " << name(result);
        };
        if (result == FrustumTest::Outside) {
            EXPECT_TRUE(some_plane_possibly_excludes_all)
                << describe() << " but no clip plane has all 8 corners outside";
            EXPECT_FALSE(some_corner_surely_inside)
                << describe() << " but a corner is inside the clip volume";
        }
        if (some_plane_surely_excludes_all) {
            EXPECT_EQ(result, FrustumTest::Outside)
                << describe() << " but all 8 corners are outside one clip plane";
        }
        if (all_corners_surely_inside) {
            EXPECT_EQ(result, FrustumTest::Inside)
                << describe() << " but all 8 corners are inside the clip volume";
        }
        if (result == FrustumTest::Inside) {
            EXPECT_TRUE(all_corners_possibly_inside)
                << describe() << " but a corner is outside the clip volume";
        }
        if (::testing::Test::HasFailure()) break;  // one detailed failure is enough
    }
    return counts;
}

// Near 10^-3 m, far 10^6 m: the far plane is the difference of two nearly equal rows. Extracted
// in double it faces back along the view from 10^6 m away in every direction; a box 50 m ahead
// is inside. (Extracted from a float matrix it was rounding noise and culled visible objects in
// scenarios/small/deep-depth-small.json.)
TEST(Frustum, ADeepDepthRangeKeepsItsFarPlaneWhenExtractedInDouble) {
    std::mt19937 rng(19);
    std::uniform_real_distribution<double> angle(-3.14159, 3.14159), pitch(-1.2, 1.2);
    for (int i = 0; i < 200; ++i) {
        const double yaw = angle(rng), up_down = pitch(rng);
        const glm::dvec3 forward(std::cos(up_down) * std::sin(yaw), std::sin(up_down),
                                 -std::cos(up_down) * std::cos(yaw));
        const glm::dvec3 eye(3.7, 2.1, -11.3);
        const glm::dmat4 view_projection =
            glm::perspective(glm::radians(60.0), 4.0 / 3.0, 1e-3, 1e6) *
            glm::lookAt(eye, eye + forward, glm::dvec3(0, 1, 0));
        const Frustum f = frustumFromViewProjection(view_projection);
        const glm::dvec3 far_normal(f.planes[5]);
        EXPECT_GT(glm::dot(far_normal, -forward), 0.9999) << "direction " << i;
        const glm::vec3 ahead(eye + 50.0 * forward);
        EXPECT_EQ(classify(f, Aabb{ahead - 0.5f, ahead + 0.5f}), FrustumTest::Inside)
            << "direction " << i;
    }
}

TEST(Frustum, ClassifyAgreesWithClipSpaceCornersForRandomBoxesAroundPerspectiveCameras) {
    const Camera cameras[] = {
        makeCamera({3.0f, 2.0f, 10.0f}, {0.0f, 0.0f, 0.0f}, 60.0f, 16.0f / 9.0f, 0.5f, 60.0f),
        makeCamera({-20.0f, 5.0f, 4.0f}, {10.0f, -3.0f, 1.0f}, 90.0f, 1.0f, 0.1f, 30.0f),
        makeCamera({100.0f, -50.0f, 30.0f}, {90.0f, -40.0f, 10.0f}, 35.0f, 0.75f, 1.0f, 45.0f),
    };
    uint32_t seed = 7;
    for (const Camera& camera : cameras) {
        const std::array<int, 3> counts = checkRandomBoxesAgainstClipSpace(camera, seed++, 20000);
        // The sample must exercise every outcome, or the checks above prove little.
        EXPECT_GT(counts[static_cast<int>(FrustumTest::Outside)], 1000);
        EXPECT_GT(counts[static_cast<int>(FrustumTest::Intersects)], 200);
        EXPECT_GT(counts[static_cast<int>(FrustumTest::Inside)], 100);
        if (HasFailure()) return;
    }
}

TEST(Frustum, BoxesBehindInsideAndAroundTheEyeClassifyAsExpected) {
    const Camera camera =
        makeCamera({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 60.0f, 1.0f, 0.5f, 50.0f);
    const Frustum f = frustumFromViewProjection(camera.view_projection);
    EXPECT_EQ(classify(f, makeAabb({-1.0f, -1.0f, 5.0f}, {1.0f, 1.0f, 7.0f})),
              FrustumTest::Outside);  // behind
    EXPECT_EQ(classify(f, makeAabb({-1.0f, -1.0f, -11.0f}, {1.0f, 1.0f, -9.0f})),
              FrustumTest::Inside);
    EXPECT_EQ(classify(f, makeAabb({-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f})),
              FrustumTest::Intersects);  // around the eye
    EXPECT_EQ(classify(f, makeAabb(glm::vec3(-1000.0f), glm::vec3(1000.0f))),
              FrustumTest::Intersects);  // encloses the whole frustum
    EXPECT_EQ(classify(f, makeAabb({-1.0f, -1.0f, -80.0f}, {1.0f, 1.0f, -60.0f})),
              FrustumTest::Outside);  // beyond the far plane
}

TEST(Frustum, EmptyBoxesAreOutsideEvenWhereTheFrustumIs) {
    const Camera camera =
        makeCamera({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 60.0f, 1.0f, 0.5f, 50.0f);
    const Frustum f = frustumFromViewProjection(camera.view_projection);
    EXPECT_EQ(classify(f, Aabb{}), FrustumTest::Outside);
    for (int axis = 0; axis < 3; ++axis) {
        Aabb inverted = makeAabb({-1.0f, -1.0f, -11.0f}, {1.0f, 1.0f, -9.0f});  // in view
        std::swap(inverted.min[axis], inverted.max[axis]);
        EXPECT_EQ(classify(f, inverted), FrustumTest::Outside) << "inverted axis " << axis;
    }
}

TEST(Frustum, NanBoxesAreNeverOutsideAndInfiniteBoxesAreNotOutside) {
    const Camera camera =
        makeCamera({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 60.0f, 1.0f, 0.5f, 50.0f);
    const Frustum f = frustumFromViewProjection(camera.view_projection);
    // A box far behind the camera: Outside while finite, so any NaN must override the planes.
    const Aabb behind = makeAabb({-1.0f, -1.0f, 5.0f}, {1.0f, 1.0f, 7.0f});
    ASSERT_EQ(classify(f, behind), FrustumTest::Outside);
    for (int coordinate = 0; coordinate < 6; ++coordinate) {
        Aabb box = behind;
        (coordinate < 3 ? box.min : box.max)[coordinate % 3] = kNan;
        EXPECT_EQ(classify(f, box), FrustumTest::Intersects) << "NaN coordinate " << coordinate;
    }
    EXPECT_EQ(classify(f, makeAabb(glm::vec3(kNan), glm::vec3(kNan))), FrustumTest::Intersects);
    // NaN wins over an inverted (empty-looking) axis: nothing about such a box can be trusted.
    Aabb nan_and_inverted = behind;
    nan_and_inverted.min.y = kNan;
    std::swap(nan_and_inverted.min.x, nan_and_inverted.max.x);
    EXPECT_EQ(classify(f, nan_and_inverted), FrustumTest::Intersects);

    // Infinite bounds (what the BSP tree gives a subtree with a non-finite object).
    EXPECT_NE(classify(f, makeAabb(glm::vec3(-kInf), glm::vec3(kInf))), FrustumTest::Outside);
    Aabb half_infinite = makeAabb({-1.0f, -1.0f, -kInf}, {1.0f, 1.0f, -9.0f});
    EXPECT_NE(classify(f, half_infinite), FrustumTest::Outside);
}

TEST(Frustum, ClassifyBatchEqualsClassifyElementWiseIncludingSpecialBoxes) {
    const Camera camera =
        makeCamera({3.0f, 2.0f, 10.0f}, {0.0f, 0.0f, 0.0f}, 60.0f, 16.0f / 9.0f, 0.5f, 60.0f);
    const Frustum f = frustumFromViewProjection(camera.view_projection);
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> offset(-40.0f, 40.0f);
    std::uniform_real_distribution<float> size(0.0f, 20.0f);

    std::vector<Aabb> boxes;
    const size_t count = 1027;  // not a multiple of any vector width: exercises the loop tail
    for (size_t i = 0; i < count; ++i) {
        const glm::vec3 centre(offset(rng), offset(rng), offset(rng));
        const glm::vec3 half = 0.5f * glm::vec3(size(rng), size(rng), size(rng));
        Aabb box = makeAabb(centre - half, centre + half);
        switch (i % 50) {
            case 0:
                box.min.y = kNan;
                break;
            case 1:
                box = Aabb{};
                break;
            case 2:
                std::swap(box.min.z, box.max.z);
                break;
            case 3:
                box = makeAabb(glm::vec3(-kInf), glm::vec3(kInf));
                break;
            case 4:
                box.max.x = kInf;
                break;
            default:
                break;
        }
        boxes.push_back(box);
    }
    const testing::BoxColumns columns(boxes);
    // One extra slot after the end checks the batch writes exactly `count` results.
    const auto sentinel = static_cast<FrustumTest>(0xAB);
    std::vector<FrustumTest> out(count + 1, sentinel);
    columns.classify(f, count, out.data());
    std::array<int, 3> seen{};
    for (size_t i = 0; i < count; ++i) {
        ASSERT_EQ(out[i], classify(f, boxes[i])) << "box " << i;
        ++seen[static_cast<int>(out[i])];
    }
    EXPECT_EQ(out[count], sentinel);
    EXPECT_GT(seen[0], 0);
    EXPECT_GT(seen[1], 0);
    EXPECT_GT(seen[2], 0);

    // count 0 writes nothing.
    FrustumTest untouched = sentinel;
    columns.classify(f, 0, &untouched);
    EXPECT_EQ(untouched, sentinel);
}

// The production path (a plane table built once per frame, then the inline kernel per node and
// object, or the batch over arrays) against the one-off classify(Frustum, box) that builds the
// table per call: the same answer, bit for bit, on random boxes around random cameras, including
// points (zero extent), huge finite boxes, infinite ones, inverted ones and NaN. A NaN box is
// never Outside (it is always drawn).
TEST(Frustum, ThePerFrameTableTheBatchAndTheSingleBoxPathsAgreeOnEveryKindOfBox) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), size(0.0f, 30.0f), fov(20.0f, 120.0f);
    constexpr float kHuge = std::numeric_limits<float>::max();
    size_t nan_boxes = 0;
    for (int c = 0; c < 20; ++c) {
        const glm::vec3 eye(50.0f * unit(rng), 20.0f * unit(rng), 50.0f * unit(rng));
        const Camera camera =
            makeCamera(eye, eye + glm::vec3(unit(rng), 0.3f * unit(rng), unit(rng)), fov(rng),
                       1.0f + unit(rng) * 0.5f, 0.1f, 200.0f);
        const Frustum f = frustumFromViewProjection(camera.view_projection);
        const FrustumPlanes table = planeTableOf(f);  // once, as a culler's frame does

        std::vector<Aabb> boxes;
        for (int i = 0; i < 500; ++i) {
            const glm::vec3 centre = eye + 120.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
            const glm::vec3 half = 0.5f * glm::vec3(size(rng), size(rng), size(rng));
            Aabb box = makeAabb(centre - half, centre + half);
            switch (i % 25) {
                case 0:
                    box.max = box.min;
                    break;  // a point
                case 1:
                    box.min.x = box.max.x;
                    break;  // a flat box
                case 2:
                    box = makeAabb(glm::vec3(-kHuge), glm::vec3(kHuge));
                    break;  // huge
                case 3:
                    box.max.y = kHuge;
                    break;
                case 4:
                    box.min.z = -kInf;
                    break;
                case 5:
                    box = makeAabb(glm::vec3(-kInf), glm::vec3(kInf));
                    break;
                case 6:
                    (i % 2 ? box.min : box.max)[i % 3] = kNan;
                    break;
                case 7:
                    box = makeAabb(glm::vec3(kNan), glm::vec3(kNan));
                    break;
                case 8:
                    std::swap(box.min.x, box.max.x);
                    break;  // inverted: empty
                case 9:
                    box = Aabb{};
                    break;
                default:
                    break;
            }
            boxes.push_back(box);
        }
        const testing::BoxColumns columns(boxes);
        std::vector<FrustumTest> batch(boxes.size());
        columns.classify(table, boxes.size(), batch.data());
        for (size_t i = 0; i < boxes.size(); ++i) {
            const FrustumTest single = classify(f, boxes[i]);
            ASSERT_EQ(classify(table, boxes[i]), single) << "camera " << c << ", box " << i;
            ASSERT_EQ(batch[i], single) << "camera " << c << ", box " << i;
            const Aabb& b = boxes[i];
            const bool has_nan = glm::any(glm::isnan(b.min)) || glm::any(glm::isnan(b.max));
            if (has_nan) {
                ++nan_boxes;
                EXPECT_EQ(single, FrustumTest::Intersects) << "a NaN box is drawn, box " << i;
            }
        }
    }
    EXPECT_GT(nan_boxes, 0u);
}

}  // namespace
}  // namespace occsim
