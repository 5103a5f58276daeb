// A glTF file's KHR_lights_punctual lights as a scene's lights (docs/views.md): directional and
// spot lights, each at its node's world transform (a light shines down its node's -z); a point
// light, or a light of a type the extension does not define, is refused with one line naming the
// file, the light and what the source's "lights" key can do about it.
#include <cmath>
#include <glm/glm.hpp>
#include <string>

#include "sim/scene/gltf_detail.h"

namespace occsim::gltf_detail {

int nodeLight(const Context& c, const tg::Node& node, size_t index) {
    const auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end()) return -1;
    const tg::Value& ext = it->second;
    if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber()) {
        fail(c.file, "node " + std::to_string(index) +
                         "'s KHR_lights_punctual names no light (expected {\"light\": index})");
    }
    return ext.Get("light").GetNumberAsInt();
}

namespace {

std::string lightWhere(const tg::Model& model, size_t light) {
    const std::string& name = model.lights[light].name;
    return "light " + std::to_string(light) + (name.empty() ? "" : " ('" + name + "')");
}

}  // namespace

std::vector<LightSpec> convertLights(const Context& c, const std::vector<LightNode>& nodes,
                                     double scale, GltfLights use) {
    std::vector<LightSpec> lights;
    if (use == GltfLights::Ignore) return lights;
    for (const LightNode& at : nodes) {
        if (at.light < 0 || static_cast<size_t>(at.light) >= c.model.lights.size()) {
            fail(c.file, "node " + std::to_string(at.node) + " refers to light " +
                             std::to_string(at.light) + ", but the file has " +
                             plural(c.model.lights.size(), "light"));
        }
        const auto index = static_cast<size_t>(at.light);
        const tg::Light& gltf = c.model.lights[index];
        LightSpec light;
        if (gltf.type == "directional") {
            light.type = LightType::Directional;
        } else if (gltf.type == "spot") {
            light.type = LightType::Spot;
        } else {
            fail(c.file, lightWhere(c.model, index) + " is a " + gltf.type +
                             " light; occsim reads directional and spot lights only (a point "
                             "light's shadow needs a cube map): \"lights\": \"ignore\" on the "
                             "source leaves the file's lights out");
        }
        const glm::dvec3 down = glm::dmat3(at.world) * glm::dvec3(0.0, 0.0, -1.0);
        const double length = glm::length(down);
        if (!(length > 0.0) || !std::isfinite(length)) {
            fail(c.file, lightWhere(c.model, index) + " has no direction (node " +
                             std::to_string(at.node) + "'s transform flattens its -z)");
        }
        light.direction = down / length;
        if (light.type == LightType::Spot) {
            light.position = scale * glm::dvec3(at.world[3]);
            const double outer = glm::degrees(gltf.spot.outerConeAngle);
            if (!(outer > 0.0 && outer < 90.0)) {
                fail(c.file, lightWhere(c.model, index) + " has an outer cone angle of " +
                                 std::to_string(gltf.spot.outerConeAngle) +
                                 " rad; expected (0, pi/2)");
            }
            light.outer_cone_deg = outer;
            if (gltf.range > 0.0) light.range_m = scale * gltf.range;
        }
        // The sun casts the scene's shadows; a spot light shades (one shadow-casting light is
        // what a frame renders first).
        light.casts_shadows = use == GltfLights::Shadows && light.type == LightType::Directional;
        lights.push_back(light);
    }
    return lights;
}

}  // namespace occsim::gltf_detail
