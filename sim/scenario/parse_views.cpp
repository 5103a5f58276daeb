// The "lights" and "stereo" sections of a scenario (sim/scenario/view_specs.h).
#include <cmath>
#include <string>
#include <vector>

#include "sim/scenario/parser_parts.h"

namespace occsim {
namespace {

const std::vector<std::string> kLightTypes = {"directional", "spot"};
const std::vector<std::string> kStereoCulling = {"enclosing", "per_eye"};

// A direction must have a length to normalise: zero (or a length that underflows) is refused.
glm::dvec3 readDirection(JsonObjectReader& light) {
    const glm::dvec3 d = light.requiredVec3("direction");
    const double length = glm::length(d);
    if (!(length > 0.0) || !std::isfinite(length)) {
        light.fail("direction",
                   "expected a non-zero direction [x, y, z] (the way the light "
                   "travels), got [" +
                       formatNumber(d.x) + ", " + formatNumber(d.y) + ", " + formatNumber(d.z) +
                       "]");
    }
    return d / length;
}

LightSpec readLight(const JsonValueReader& value) {
    JsonObjectReader light = value.asObject();
    LightSpec spec;
    spec.type = light.requiredEnumeration("type", kLightTypes) == "spot" ? LightType::Spot
                                                                         : LightType::Directional;
    spec.direction = readDirection(light);
    if (spec.type == LightType::Spot) {
        spec.position = light.requiredVec3("position");
        spec.outer_cone_deg =
            light.number("outer_cone", spec.outer_cone_deg, NumberRange::open(0.0, 90.0));
        spec.range_m = light.number("range", spec.range_m, NumberRange::greaterThan(0.0));
    }
    spec.shadow_map = static_cast<uint32_t>(
        light.unsignedInteger("shadow_map", spec.shadow_map, 1, kMaxShadowMapSize));
    spec.casts_shadows = light.boolean("casts_shadows", spec.casts_shadows);
    light.finish();
    return spec;
}

}  // namespace

std::vector<LightSpec> readLights(JsonObjectReader& top) {
    std::vector<LightSpec> lights;
    const auto list = top.optionalArray("lights");
    if (!list) return lights;
    for (size_t i = 0; i < list->size(); ++i) lights.push_back(readLight(list->at(i)));
    return lights;
}

std::optional<StereoSpec> readStereo(JsonObjectReader& top) {
    auto stereo = top.optionalObject("stereo");
    if (!stereo) return std::nullopt;
    StereoSpec spec;
    spec.eye_separation_m =
        stereo->number("eye_separation", spec.eye_separation_m, NumberRange::greaterThan(0.0));
    spec.culling = stereo->enumeration("culling", kStereoCulling, "enclosing") == "per_eye"
                       ? StereoCulling::PerEye
                       : StereoCulling::Enclosing;
    stereo->finish();
    return spec;
}

}  // namespace occsim
