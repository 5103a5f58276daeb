// Aabb helpers: extend, closed containment, transformAabb against brute-force corner transforms,
// and isFiniteAndOrdered on NaN, infinite and inverted boxes.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <random>

#include "occsim/culling/geometry/aabb.h"

namespace occsim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

void expectVecEq(glm::vec3 actual, glm::vec3 expected) {
    EXPECT_EQ(actual.x, expected.x);
    EXPECT_EQ(actual.y, expected.y);
    EXPECT_EQ(actual.z, expected.z);
}

TEST(Aabb, DefaultBoxIsEmptyAndExtendingItByABoxYieldsThatBox) {
    Aabb box;
    EXPECT_TRUE(isEmpty(box));
    const Aabb other = makeAabb({-1.0f, 2.0f, 3.0f}, {4.0f, 5.0f, 6.0f});
    extend(box, other);
    EXPECT_FALSE(isEmpty(box));
    expectVecEq(box.min, other.min);
    expectVecEq(box.max, other.max);
}

TEST(Aabb, ExtendByBoxGivesTheUnionPerAxis) {
    Aabb box = makeAabb({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});
    extend(box, makeAabb({-2.0f, 0.5f, 0.25f}, {0.5f, 3.0f, 0.75f}));
    expectVecEq(box.min, {-2.0f, 0.0f, 0.0f});
    expectVecEq(box.max, {1.0f, 3.0f, 1.0f});
}

TEST(Aabb, ExtendByPointGrowsOnlyTheAxesThePointLiesOutside) {
    Aabb box = makeAabb({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});
    extend(box, glm::vec3(0.5f, -1.0f, 2.0f));
    expectVecEq(box.min, {0.0f, -1.0f, 0.0f});
    expectVecEq(box.max, {1.0f, 1.0f, 2.0f});

    Aabb from_empty;
    extend(from_empty, glm::vec3(3.0f, 4.0f, 5.0f));
    expectVecEq(from_empty.min, {3.0f, 4.0f, 5.0f});
    expectVecEq(from_empty.max, {3.0f, 4.0f, 5.0f});
}

TEST(Aabb, ContainsIsClosedSoTouchingFacesAndEqualBoxesAreInside) {
    const Aabb outer = makeAabb({0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f});
    EXPECT_TRUE(contains(outer, outer));
    EXPECT_TRUE(contains(outer, makeAabb({0.0f, 0.5f, 0.5f}, {1.0f, 1.0f, 1.0f})));  // min face
    EXPECT_TRUE(contains(outer, makeAabb({1.0f, 1.0f, 1.0f}, {2.0f, 2.0f, 2.0f})));  // max corner
    EXPECT_TRUE(
        contains(outer, makeAabb({2.0f, 1.0f, 1.0f}, {2.0f, 1.0f, 1.0f})));  // flat, on face
    EXPECT_FALSE(contains(outer, makeAabb({-0.001f, 0.5f, 0.5f}, {1.0f, 1.0f, 1.0f})));
    EXPECT_FALSE(contains(outer, makeAabb({1.0f, 1.0f, 1.0f}, {1.5f, 2.001f, 1.5f})));
    EXPECT_FALSE(contains(outer, makeAabb({-1.0f, -1.0f, -1.0f}, {3.0f, 3.0f, 3.0f})));

    EXPECT_TRUE(contains(outer, glm::vec3(0.0f, 2.0f, 1.0f)));
    EXPECT_FALSE(contains(outer, glm::vec3(0.0f, 2.0001f, 1.0f)));
}

TEST(Aabb, OverlapsAndDistanceSquaredTreatTouchingAsOverlapAndInsideAsZero) {
    const Aabb a = makeAabb({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});
    EXPECT_TRUE(overlaps(a, makeAabb({1.0f, 0.0f, 0.0f}, {2.0f, 1.0f, 1.0f})));
    EXPECT_FALSE(overlaps(a, makeAabb({1.01f, 0.0f, 0.0f}, {2.0f, 1.0f, 1.0f})));
    EXPECT_EQ(distanceSquared(a, glm::vec3(0.5f)), 0.0f);
    EXPECT_FLOAT_EQ(distanceSquared(a, glm::vec3(3.0f, 0.5f, -2.0f)), 4.0f + 4.0f);
}

// Builds a random affine transform: rotation about a random axis, non-uniform scale (sometimes
// negative, sometimes zero on one axis), translation.
glm::mat4 randomAffine(std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_real_distribution<float> angle(0.0f, 6.2831853f);
    std::uniform_real_distribution<float> scale(0.1f, 5.0f);
    std::uniform_real_distribution<float> offset(-100.0f, 100.0f);
    glm::vec3 axis(unit(rng), unit(rng), unit(rng));
    if (glm::length(axis) < 1e-3f) axis = glm::vec3(0.0f, 1.0f, 0.0f);
    glm::vec3 scales(scale(rng), scale(rng), scale(rng));
    if (rng() % 4 == 0) scales.x = -scales.x;  // mirrored
    if (rng() % 8 == 0) scales.z = 0.0f;       // flattened
    glm::mat4 m(1.0f);
    m = glm::translate(m, glm::vec3(offset(rng), offset(rng), offset(rng)));
    m = glm::rotate(m, angle(rng), glm::normalize(axis));
    m = glm::scale(m, scales);
    return m;
}

TEST(Aabb, TransformAabbEqualsBoundsOfTheEightTransformedCorners) {
    std::mt19937 rng(20240601u);
    std::uniform_real_distribution<float> coordinate(-10.0f, 10.0f);
    std::uniform_real_distribution<float> size(0.0f, 8.0f);
    for (int trial = 0; trial < 2000; ++trial) {
        const glm::vec3 low(coordinate(rng), coordinate(rng), coordinate(rng));
        glm::vec3 sizes(size(rng), size(rng), size(rng));
        if (trial % 10 == 0) sizes.y = 0.0f;  // zero-extent axis
        const Aabb local = makeAabb(low, low + sizes);
        const glm::mat4 m = randomAffine(rng);

        Aabb expected;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p((corner & 1) ? local.max.x : local.min.x,
                              (corner & 2) ? local.max.y : local.min.y,
                              (corner & 4) ? local.max.z : local.min.z);
            extend(expected, glm::vec3(m * glm::vec4(p, 1.0f)));
        }
        const Aabb actual = transformAabb(local, m);
        const float tolerance =
            1e-4f * (1.0f + glm::length(extent(expected)) + glm::length(glm::vec3(m[3])));
        for (int axis = 0; axis < 3; ++axis) {
            ASSERT_NEAR(actual.min[axis], expected.min[axis], tolerance) << "trial " << trial;
            ASSERT_NEAR(actual.max[axis], expected.max[axis], tolerance) << "trial " << trial;
        }
    }
}

TEST(Aabb, TransformAabbOfIdentityIsTheSameBox) {
    const Aabb box = makeAabb({-1.0f, 2.0f, -3.0f}, {4.0f, 5.0f, 6.0f});
    const Aabb out = transformAabb(box, glm::mat4(1.0f));
    expectVecEq(out.min, box.min);
    expectVecEq(out.max, box.max);
}

TEST(Aabb, IsFiniteAndOrderedAcceptsZeroExtentAndRejectsNanInfiniteAndInverted) {
    EXPECT_TRUE(isFiniteAndOrdered(makeAabb({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f})));
    EXPECT_TRUE(isFiniteAndOrdered(makeAabb({1.0f, 2.0f, 3.0f}, {1.0f, 2.0f, 3.0f})));
    EXPECT_FALSE(isFiniteAndOrdered(Aabb{}));  // the empty box (+inf, -inf)
    for (int axis = 0; axis < 3; ++axis) {
        Aabb nan_min = makeAabb(glm::vec3(0.0f), glm::vec3(1.0f));
        nan_min.min[axis] = kNan;
        EXPECT_FALSE(isFiniteAndOrdered(nan_min)) << "NaN min on axis " << axis;
        Aabb nan_max = makeAabb(glm::vec3(0.0f), glm::vec3(1.0f));
        nan_max.max[axis] = kNan;
        EXPECT_FALSE(isFiniteAndOrdered(nan_max)) << "NaN max on axis " << axis;
        Aabb infinite = makeAabb(glm::vec3(0.0f), glm::vec3(1.0f));
        infinite.max[axis] = kInf;
        EXPECT_FALSE(isFiniteAndOrdered(infinite)) << "+inf max on axis " << axis;
        Aabb minus_infinite = makeAabb(glm::vec3(0.0f), glm::vec3(1.0f));
        minus_infinite.min[axis] = -kInf;
        EXPECT_FALSE(isFiniteAndOrdered(minus_infinite)) << "-inf min on axis " << axis;
        Aabb inverted = makeAabb(glm::vec3(0.0f), glm::vec3(1.0f));
        inverted.min[axis] = 2.0f;
        EXPECT_FALSE(isFiniteAndOrdered(inverted)) << "inverted on axis " << axis;
    }
}

}  // namespace
}  // namespace occsim
