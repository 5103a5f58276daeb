#include "sim/run/calibration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "occsim/culling/tree/bsp_tree.h"
#include "render/gl_query_device.h"
#include "sim/run/frame_view.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

// Enough draws and boxes that a measurement spans a few milliseconds on llvmpipe, few enough
// that calibration stays near 150 ms.
constexpr size_t kMaxSampleObjects = 128;
constexpr size_t kMaxQueryBoxes = 256;
constexpr int kRepetitions = 9;  // timed, after one that is thrown away

// Runs `work` (ending in glFinish) once to warm up, then kRepetitions times; the fastest, in ms.
// A shared machine only ever adds time to a run, so the fastest is the steadiest estimate of what
// the work costs: the median of five gave 0.034 to 0.095 ms per query box in runs of the same
// library scene, enough to flip the cost model's draw-or-query decisions on its books.
template <class Work>
double fastestMs(GlRenderer& renderer, Work&& work) {
    std::vector<double> times;
    for (int r = 0; r <= kRepetitions; ++r) {
        renderer.beginFrame();
        renderer.finish();
        const auto start = Clock::now();
        work();
        renderer.finish();
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        if (r > 0) times.push_back(ms);
    }
    return *std::min_element(times.begin(), times.end());
}

// Up to `count` entries of `items`, spread evenly (deterministic).
template <class T>
std::vector<T> evenSample(const std::vector<T>& items, size_t count) {
    if (items.size() <= count) return items;
    std::vector<T> out;
    for (size_t i = 0; i < count; ++i) out.push_back(items[i * items.size() / count]);
    return out;
}

}  // namespace

CostModel referenceCostModel() {
    CostModel c;
    c.query_box_ms = 0.008;
    c.triangle_ms = 6.4e-5;
    c.draw_call_ms = 0.0;
    return c;
}

CostModel calibrateCostModel(const Scene& scene, const Scenario& scenario, GlRenderer& renderer,
                             uint32_t queries_in_flight) {
    const WorldState state = initialState(scene);
    const FrameView view = makeFrameView(scenario.camera, 0.0, scenario.width, scenario.height,
                                         scene.culling_origin, depthConventionOf(scenario));
    // Camera-relative model-view matrices, as the simulation composes them.
    std::vector<glm::mat4> model_view(scene.objectCount());
    const glm::dmat4 rotation(view.render.view_rotation);
    const glm::dmat4 to_eye = glm::translate(glm::dmat4(1.0), -view.render.eye);
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        model_view[o] = glm::mat4(rotation * to_eye * modelMatrix(state.poses[o]));
    }
    renderer.setView(view.render, model_view);

    // The objects the first view sees (all of them if it sees none), sorted by triangle count.
    std::vector<uint32_t> in_view;
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        if (classify(view.cull.frustum, state.boxes[o]) != FrustumTest::Outside)
            in_view.push_back(o);
    }
    if (in_view.empty()) {
        for (uint32_t o = 0; o < scene.objectCount(); ++o) in_view.push_back(o);
    }
    std::vector<uint32_t> sample = evenSample(in_view, kMaxSampleObjects);
    if (sample.empty()) return referenceCostModel();
    std::stable_sort(sample.begin(), sample.end(), [&](uint32_t a, uint32_t b) {
        return renderer.triangleCount(a) < renderer.triangleCount(b);
    });

    GlQueryDevice device(renderer, LatencyMode{});
    struct Part {
        double calls = 0, triangles = 0, ms = 0;
    };
    auto timeDraws = [&](size_t first, size_t last) {
        Part p;
        for (size_t i = first; i < last; ++i) {
            p.calls += 1;
            p.triangles += renderer.triangleCount(sample[i]);
        }
        p.ms = fastestMs(renderer, [&] {
            for (size_t i = first; i < last; ++i) device.drawObject(sample[i]);
        });
        return p;
    };

    CostModel costs;
    const Part all = timeDraws(0, sample.size());
    // Split per call and per triangle: time the half with fewer triangles per mesh and the half
    // with more, and solve ms = calls * draw_call_ms + triangles * triangle_ms for both.
    const size_t half = sample.size() / 2;
    bool split = false;
    if (half > 0 &&
        renderer.triangleCount(sample.front()) != renderer.triangleCount(sample.back())) {
        const Part small = timeDraws(0, half);
        const Part large = timeDraws(half, sample.size());
        const double det = small.calls * large.triangles - large.calls * small.triangles;
        if (std::abs(det) > 1e-9 * small.calls * large.triangles) {
            const double call = (small.ms * large.triangles - large.ms * small.triangles) / det;
            const double tri = (small.calls * large.ms - large.calls * small.ms) / det;
            if (call >= 0.0 && tri >= 0.0) {
                costs.draw_call_ms = call;
                costs.triangle_ms = tri;
                split = true;
            }
        }
    }
    if (!split) {
        costs.draw_call_ms = 0.0;
        costs.triangle_ms = all.triangles > 0 ? all.ms / all.triangles : 0.0;
        if (all.triangles == 0) costs.draw_call_ms = all.ms / all.calls;
    }

    // Queries: the boxes of the tree's nodes in view, each its own query, all answered (the wait
    // for the answers is part of their cost), with as many in flight as the culler keeps.
    BspTree tree;
    tree.build(state.boxes, scenario.bsp);
    std::vector<Aabb> node_boxes;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const Aabb& b = tree.bounds(n);
        if (isEmpty(b) || !isFiniteAndOrdered(b)) continue;
        if (classify(view.cull.frustum, b) == FrustumTest::Outside) continue;
        if (nearPlaneTouchesBox(b, view.cull.eye, view.cull.near_radius)) continue;
        node_boxes.push_back(b);
    }
    node_boxes = evenSample(node_boxes, kMaxQueryBoxes);
    if (!node_boxes.empty()) {
        std::vector<QueryId> ids(node_boxes.size());
        const size_t lag = queries_in_flight > 0 ? queries_in_flight : node_boxes.size();
        const double ms = fastestMs(renderer, [&] {
            for (size_t i = 0; i < node_boxes.size(); ++i) {
                if (i >= lag) device.takeAnswer(ids[i - lag]);
                ids[i] = device.issueQuery(node_boxes[i]);
            }
            for (size_t i = node_boxes.size() > lag ? node_boxes.size() - lag : 0;
                 i < node_boxes.size(); ++i) {
                device.takeAnswer(ids[i]);
            }
        });
        costs.query_box_ms = ms / static_cast<double>(node_boxes.size());
    } else {
        costs.query_box_ms = referenceCostModel().query_box_ms;
    }
    return costs;
}

}  // namespace occsim
