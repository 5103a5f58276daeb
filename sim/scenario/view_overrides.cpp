// See view_overrides.h.
#include "sim/scenario/view_overrides.h"

#include <cmath>
#include <glm/glm.hpp>
#include <stdexcept>
#include <variant>
#include <vector>

#include "sim/scenario/number_text.h"

namespace occsim {
namespace {

std::vector<std::string> splitCommas(const std::string& text) {
    std::vector<std::string> parts(1);
    for (const char c : text) {
        if (c == ',') {
            parts.emplace_back();
        } else {
            parts.back() += c;
        }
    }
    return parts;
}

}  // namespace

LightSpec parseSun(const std::string& text) {
    const std::string expected =
        "expected ELEVATION,AZIMUTH[,SHADOW_MAP]: degrees above the horizon in (0, 90], degrees "
        "round from +x toward +z, texels a side in [1, " +
        std::to_string(kMaxShadowMapSize) + "]; got '" + text + "'";
    const std::vector<std::string> parts = splitCommas(text);
    if (parts.size() < 2 || parts.size() > 3) throw std::invalid_argument(expected);
    double elevation = 0.0, azimuth = 0.0;
    if (!parseFiniteNumber(parts[0], elevation) || !parseFiniteNumber(parts[1], azimuth) ||
        !(elevation > 0.0 && elevation <= 90.0)) {
        throw std::invalid_argument(expected);
    }
    LightSpec sun;
    sun.type = LightType::Directional;
    sun.casts_shadows = true;
    if (parts.size() == 3) {
        double map = 0.0;
        if (!parseFiniteNumber(parts[2], map) || map != std::floor(map) || map < 1.0 ||
            map > kMaxShadowMapSize) {
            throw std::invalid_argument(expected);
        }
        sun.shadow_map = static_cast<uint32_t>(map);
    }
    const double e = glm::radians(elevation), a = glm::radians(azimuth);
    // Toward the sun: up by the elevation, round the horizon by the azimuth; the light travels
    // the other way.
    const glm::dvec3 toward(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
    sun.direction = -glm::normalize(toward);
    return sun;
}

void replaceLightsWith(Scenario& scenario, const LightSpec& sun) {
    scenario.lights = {sun};
    for (SceneSourceSpec& source : scenario.sources) {
        if (auto* gltf = std::get_if<GltfSourceSpec>(&source.spec))
            gltf->lights = GltfLights::Ignore;
    }
}

StereoSpec parseStereo(const std::string& text) {
    const std::string expected =
        "expected SEPARATION[,MODE]: metres between the eyes, > 0, and enclosing (the default) "
        "or per_eye; got '" +
        text + "'";
    const std::vector<std::string> parts = splitCommas(text);
    StereoSpec stereo;
    if (parts.size() > 2 || !parseFiniteNumber(parts[0], stereo.eye_separation_m) ||
        !(stereo.eye_separation_m > 0.0)) {
        throw std::invalid_argument(expected);
    }
    if (parts.size() == 2) {
        if (parts[1] == "per_eye") {
            stereo.culling = StereoCulling::PerEye;
        } else if (parts[1] != "enclosing") {
            throw std::invalid_argument(expected);
        }
    }
    return stereo;
}

}  // namespace occsim
