// The command line's views (run and bench, docs/views.md): a sun (`--sun
// ELEVATION,AZIMUTH[,SHADOW_MAP]`), one directional light casting shadows in place of every light
// the scene names, and stereo (`--stereo SEPARATION[,MODE]`), so that any scene can be run under a
// low or a high sun, or by two eyes, without a copy of its file.
#pragma once

#include <string>

#include "sim/scenario/scenario.h"
#include "sim/scenario/view_specs.h"

namespace occsim {

// "ELEVATION,AZIMUTH[,SHADOW_MAP]": the sun's height above the horizon in degrees, (0, 90]; the
// compass direction it shines from in degrees, measured in the ground plane from +x toward +z
// (any finite value); the shadow map's side in texels, [1, kMaxShadowMapSize] (default 2048).
// The light travels from that direction into the scene. std::invalid_argument saying what was
// expected, for the caller to prefix with the flag.
LightSpec parseSun(const std::string& text);

// The scenario's lights replaced by `sun`, and every glTF source's own lights left out
// (GltfLights::Ignore): the scene has that one light.
void replaceLightsWith(Scenario& scenario, const LightSpec& sun);

// "SEPARATION[,MODE]": metres between the eyes, > 0; MODE `enclosing` (the default) or `per_eye`
// (StereoCulling). std::invalid_argument saying what was expected, for the caller to prefix with
// the flag.
StereoSpec parseStereo(const std::string& text);

}  // namespace occsim
