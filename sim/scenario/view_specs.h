// The views a frame renders besides the camera's, as a scenario gives them ("lights" and
// "stereo", docs/scenario-format.md): shadow-casting lights, each a depth-only pass into its
// shadow map before the camera's pass, and a second eye. Read and checked by the parser
// (parse_views.cpp); what the run does with them is in docs/views.md.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

namespace occsim {

enum class LightType : uint8_t { Directional, Spot };

// The largest shadow map a scenario may ask for, a side in texels; a device whose largest texture
// is smaller refuses the run before frame 0.
inline constexpr uint32_t kMaxShadowMapSize = 16384;

struct LightSpec {
    LightType type = LightType::Directional;
    // The way the light travels (from the light into the scene), unit length; never zero.
    glm::dvec3 direction{0.0, -1.0, 0.0};
    glm::dvec3 position{0.0};      // spot: where the light is
    double outer_cone_deg = 45.0;  // spot: the half-angle of its cone, (0, 90)
    double range_m = 100.0;        // spot: how far it reaches (its shadow frustum's far plane)
    uint32_t shadow_map = 2048;    // texels a side, [1, kMaxShadowMapSize]
    bool casts_shadows = true;
};

// How a second eye is culled: one pass over a frustum enclosing both eyes, or one pass per eye.
enum class StereoCulling : uint8_t { Enclosing, PerEye };

struct StereoSpec {
    double eye_separation_m = 0.064;  // between the two eyes, > 0; the camera is midway
    StereoCulling culling = StereoCulling::Enclosing;
};

}  // namespace occsim
