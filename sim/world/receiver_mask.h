// Receiver-masked caster culling for a directional light's shadow pass (Bittner, Mattausch,
// Silvennoinen and Wimmer, "Shadow Caster Culling for Efficient Shadow Mapping", I3D 2011; the
// paper's fragment mask, docs/views.md): the points the camera sees (its depth buffer's pixels,
// each grown by a margin) are laid into a grid across the light, each texel keeping the greatest
// depth (along the light) of any receiver point over it; a caster is drawn only where its box
// covers a texel whose receivers lie at least as deep as its nearest point.
//
// Conservative by construction: a shadow on a visible point p falls from a caster point on the
// ray from p toward the light, at p's position across the light and nearer the light. p's texel
// holds a depth at least p's, and the caster's box covers that texel with a nearest depth at most
// the caster point's. The margin covers what the shadow lookup does beside p (its normal offset)
// and what p's stored depth rounds away. Pure geometry in double, no OpenGL.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "occsim/culling/geometry/aabb.h"
#include "sim/world/light_view.h"

namespace occsim {

class ReceiverMask {
  public:
    // An empty mask of resolution x resolution texels over `box`'s extent across the light
    // (resolution >= 1). Allocates only when the resolution grows.
    void reset(const LightBox& box, uint32_t resolution);

    // A receiver point (world coordinates) and every point within `margin_m` of it, as a box.
    void addReceiver(const glm::dvec3& point, double margin_m);

    // Whether a caster with this box can shadow any receiver added since reset().
    bool mayShadow(const Aabb& box, const glm::dvec3& culling_origin) const;

    uint32_t resolution() const { return n_; }
    // Texels some receiver covers (tests, figures).
    uint32_t coveredTexels() const;

  private:
    struct TexelRange {
        uint32_t x0 = 1, x1 = 0, y0 = 1, y1 = 0;  // inclusive; empty when x0 > x1
        double near_depth = 0.0, far_depth = 0.0;
    };
    // The texels a world box covers, and its depth range.
    TexelRange footprint(const glm::dvec3& lo, const glm::dvec3& hi) const;

    LightBox box_;
    uint32_t n_ = 0;
    glm::dvec2 texel_{1.0};
    std::vector<double> deepest_;  // per texel; -infinity: no receiver
};

}  // namespace occsim
