// The masked software depth buffer's cost (occsim/culling/raster/masked_depth_buffer.h): one frame
// (clear, rasterise the occluders, test boxes) at its default resolution, and how that grows with
// occluder triangles and with resolution, for the plain and the AVX2 kernels. Figures only; the
// machine's load moves them (docs/masked.md).
#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "culling/cullers/masked_culler.h"
#include "occsim/culling/raster/masked_depth_buffer.h"

namespace occsim {
namespace {

constexpr uint32_t kViewportWidth = 1280, kViewportHeight = 720;

// A bumpy grid of n×n quads (2n² triangles) filling most of the view between 10 and 30 m, and
// 1000 boxes scattered behind and in front of it.
struct Scene {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    std::vector<Aabb> boxes;
    glm::mat4 view_projection;

    explicit Scene(uint32_t n) {
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (uint32_t y = 0; y <= n; ++y) {
            for (uint32_t x = 0; x <= n; ++x) {
                const float fx = static_cast<float>(x) / n, fy = static_cast<float>(y) / n;
                positions.emplace_back(fx * 30.0f - 15.0f, fy * 16.0f - 8.0f,
                                       -10.0f - 20.0f * fx - u(rng));
            }
        }
        for (uint32_t y = 0; y < n; ++y) {
            for (uint32_t x = 0; x < n; ++x) {
                const uint32_t i = y * (n + 1) + x;
                indices.insert(indices.end(), {i, i + 1, i + n + 2, i, i + n + 2, i + n + 1});
            }
        }
        for (int b = 0; b < 1000; ++b) {
            const glm::vec3 at(u(rng) * 40.0f - 20.0f, u(rng) * 20.0f - 10.0f,
                               -5.0f - u(rng) * 60.0f);
            boxes.push_back(makeAabb(at, at + glm::vec3(0.5f + u(rng))));
        }
        view_projection = glm::perspective(glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 1000.0f);
    }
};

void frame(benchmark::State& state, MaskedKernel kernel) {
    const uint32_t n = static_cast<uint32_t>(state.range(0));
    const uint32_t width = static_cast<uint32_t>(state.range(1));
    const Scene scene(n);
    MaskedDepthBuffer buffer(kernel);
    if (buffer.kernel() != kernel) {
        state.SkipWithError("kernel not available on this CPU");
        return;
    }
    uint64_t hidden = 0;
    for (auto _ : state) {
        buffer.beginFrame(scene.view_projection, glm::vec3(0.0f), kViewportWidth, kViewportHeight,
                          width);
        buffer.rasteriseMesh(scene.positions, scene.indices, glm::mat4(1.0f));
        for (const Aabb& box : scene.boxes) hidden += buffer.testBox(box) ? 0 : 1;
        benchmark::DoNotOptimize(hidden);
    }
    state.counters["triangles"] = 2.0 * n * n;
    state.counters["buffer_width"] = buffer.width();
    state.counters["hidden"] = static_cast<double>(buffer.stats().boxes_hidden);
    state.counters["tri/s"] =
        benchmark::Counter(2.0 * n * n, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_MaskedFramePlain(benchmark::State& state) { frame(state, MaskedKernel::Plain); }
void BM_MaskedFrameAvx2(benchmark::State& state) { frame(state, MaskedKernel::Avx2); }

// Triangles (2n²) at the culler's default width, then widths at 2·32² triangles.
void arguments(benchmark::internal::Benchmark* b) {
    const int default_width = static_cast<int>(MaskedOptions{}.width);
    for (int n : {4, 16, 32, 64, 128}) b->Args({n, default_width});
    for (int w : {64, 160, 640, 1280}) b->Args({32, w});
    b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_MaskedFramePlain)->Apply(arguments);
BENCHMARK(BM_MaskedFrameAvx2)->Apply(arguments);

}  // namespace
}  // namespace occsim

BENCHMARK_MAIN();
