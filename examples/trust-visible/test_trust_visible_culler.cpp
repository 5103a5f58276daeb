// Unit test of the example culler on occsim's CPU test devices: no OpenGL, no window, no GPU.
// ScriptedQueryDevice answers each query with the number of visible objects its box overlaps.
#include <occsim/culling/plugin.h>
#include <occsim/culling/testing/scripted_query_device.h>

#include <algorithm>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "trust_visible_culler.h"

namespace {

int failures = 0;

void check(bool ok, const char* what) {
    std::printf("%s: %s\n", ok ? "pass" : "FAIL", what);
    failures += ok ? 0 : 1;
}

bool drew(const occsim::ScriptedQueryDevice& device, uint32_t object) {
    const auto& d = device.drawnObjects();
    return std::find(d.begin(), d.end(), object) != d.end();
}

}  // namespace

int main() {
    // A row of 64 unit boxes along -z, seen from the front.
    std::vector<occsim::Aabb> boxes;
    for (int i = 0; i < 64; ++i) {
        const float z = -5.0f - 3.0f * static_cast<float>(i);
        boxes.push_back({glm::vec3(-0.5f, 0.0f, z - 0.5f), glm::vec3(0.5f, 1.0f, z + 0.5f)});
    }
    occsim::BspTree tree;
    tree.build(boxes, occsim::BspBuildOptions{});

    occsim::CullFrame frame;
    frame.view.eye = glm::vec3(0.0f, 0.5f, 0.0f);
    const glm::mat4 vp =
        glm::perspective(glm::radians(60.0f), 4.0f / 3.0f, 0.1f, 500.0f) *
        glm::lookAt(frame.view.eye, glm::vec3(0.0f, 0.5f, -1.0f), glm::vec3(0, 1, 0));
    frame.view.frustum = occsim::frustumFromViewProjection(vp);
    frame.view.near_radius = 0.2f;

    // Only objects 3 and 40 are visible.
    std::vector<uint8_t> visible(boxes.size(), 0);
    visible[3] = visible[40] = 1;
    occsim::ScriptedQueryDevice device;
    device.setVisibility(visible, boxes);

    example::TrustVisibleCuller culler(/*trust_s=*/1.0);
    culler.reset(tree);
    culler.cullAndRender(tree, frame, device);
    check(drew(device, 3) && drew(device, 40), "every visible object is drawn (conservative)");
    check(device.drawnObjects().size() < boxes.size(), "occluded subtrees are skipped");
    const size_t first_queries = device.queriedBoxes().size();
    check(first_queries > 0, "the first frame queries");

    // Half a second later the visible nodes are trusted: fewer queries, the same visible objects.
    device.clearLog();
    frame.frame_index = 15;
    frame.time_s = 0.5;
    culler.cullAndRender(tree, frame, device);
    check(drew(device, 3) && drew(device, 40), "trusted nodes still draw their visible objects");
    check(device.queriedBoxes().size() < first_queries, "trusted nodes are not queried again");

    // After the trust ran out, everything is queried again.
    device.clearLog();
    frame.time_s = 2.0;
    culler.cullAndRender(tree, frame, device);
    check(device.queriedBoxes().size() == first_queries,
          "after `trust` seconds nodes are queried again");

    std::printf("%d passed, %d failed\n", 6 - failures, failures);
    return failures == 0 ? 0 : 1;
}
