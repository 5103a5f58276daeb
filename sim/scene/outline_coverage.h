// How much of an object's outline an occluder covers, seen from far away: both meshes projected
// orthographically along each of seven sides (the three axes and the four diagonals) onto a grid
// laid over the object's outline there, each cell counted by its centre. An occluder made by
// moving a surface inward can lose most of the outline of a thin part (a slat thinner than the
// step becomes a sheet that hides nothing edge-on) while keeping most of its area; this measures
// what a depth buffer would get from it, from its worst side.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace occsim {

struct OutlineShare {
    double share = 1.0;      // covered cells / the object's cells (1 when it covers none)
    const char* side = "x";  // the side it was least: "x", "y", "z" or "(1, 1, -1)" and so on
};

class ObjectOutlines {
  public:
    // The object's outline from each side, `resolution` cells along each side of its grid.
    // Triangles count whichever way they face.
    ObjectOutlines(std::span<const glm::dvec3> positions, std::span<const uint32_t> indices,
                   uint32_t resolution = 128);

    // The least share of the object's outline the occluder covers, over the seven sides.
    OutlineShare worst(std::span<const glm::dvec3> positions,
                       std::span<const uint32_t> indices) const;

    struct Side {
        glm::dvec3 u{0.0}, v{0.0};  // the grid's plane
        glm::dvec2 lo{0.0}, cell{1.0};
        const char* name = "";
        std::vector<uint8_t> object;  // 1 where the object covers a cell's centre
        uint64_t object_cells = 0;
    };

  private:
    uint32_t n_ = 0;
    std::array<Side, 7> sides_;
};

}  // namespace occsim
