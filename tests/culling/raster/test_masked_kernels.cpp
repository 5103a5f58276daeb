// The AVX2 kernels give the plain path's buffer bit for bit, on random scenes.
#include <gtest/gtest.h>

#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>

#include "masked_scenes.h"

namespace occsim {
namespace {

using namespace testing;

// The AVX2 kernels give the plain path's buffer bit for bit.
TEST(MaskedDepthBuffer, TheAvx2KernelsGiveThePlainBuffer) {
    if (!maskedKernelAvailable(MaskedKernel::Avx2)) GTEST_SKIP() << "no AVX2 on this CPU";
    for (uint32_t seed = 1; seed <= 60; ++seed) {
        RandomCase c = randomCase(seed);
        MaskedDepthBuffer plain(MaskedKernel::Plain), avx2(MaskedKernel::Avx2);
        ASSERT_EQ(avx2.kernel(), MaskedKernel::Avx2);
        for (MaskedDepthBuffer* b : {&plain, &avx2}) {
            b->beginFrame(c.view.view_projection, c.view.eye, c.view.viewport_width,
                          c.view.viewport_height, 100);
            for (uint32_t o = 0; o < c.scene.boxes.size(); ++o) {
                const MeshRange& r = c.scene.meshes[c.scene.object_mesh[o]];
                const auto indices =
                    std::span(c.scene.indices).subspan(r.first_index, r.index_count);
                b->rasteriseMesh(
                    std::span(c.scene.positions).subspan(r.first_vertex, r.vertex_count), indices,
                    c.scene.transforms[o], edgeNeighbours(indices));
            }
        }
        ASSERT_EQ(plain.tiles().size(), avx2.tiles().size());
        EXPECT_EQ(
            std::memcmp(plain.tiles().data(), avx2.tiles().data(), plain.tiles().size_bytes()), 0)
            << "seed " << seed;
    }
}

}  // namespace
}  // namespace occsim
