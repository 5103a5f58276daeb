// The Utah teapot: Martin Newell's 1975 teapot (University of Utah), the public patch dataset of
// 32 bicubic Bezier patches over 306 control points (rim 4, body 8, handle 4, spout 4, lid 8,
// bottom 4). The control points and patch indices below are that dataset, 1-based as published.
//
// Conventions:
//  - The dataset is z-up with the bottom at z = 0, the lid top at z = 3.15, the spout towards +x
//    and the handle towards -x. We convert to y-up with (x, y, z) -> (x, z, -y), a rotation about
//    the x axis (determinant +1), so winding and handedness are preserved.
//  - After tessellation the mesh is translated and uniformly scaled so that its bounding box has
//    height (y extent) exactly 1.0, its bottom at y = 0 and its x/z centre at the origin. The x/z
//    extent depends slightly on the level (the spout tip is curved), so the centring uses the
//    tessellated vertices of that level.
//  - Patch (u, v): u runs along the four rows of a patch's 16 indices, v along each row. The
//    analytic normal is cross(dP/du, dP/dv). Whether that points outward is decided per patch
//    (once, by ray-parity votes against a reference tessellation), so the dataset's own
//    parametrisation order does not matter; triangles are wound to match the outward normal.
//  - Where a patch edge collapses to a point (the lid top and the bottom centre), dP/dv vanishes:
//    the normal there is taken from a sample nudged slightly into the patch interior, with the
//    averaged adjacent face normals as a last resort. The zero-area triangles along such an edge
//    are not emitted.
#include "sim/scene/teapot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace occsim {
namespace {

// clang-format off
constexpr std::array<std::array<uint16_t, 16>, kTeapotPatchCount> kPatches = {{
    // rim
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    // body, upper
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    // body, lower
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    // handle
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69},
    // spout
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194},
    // lid, knob
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212},
    // lid, rim
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242},
    // bottom
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271},
}};

constexpr std::array<std::array<double, 3>, 306> kControlPoints = {{
    // 1 - 48: rim
    {1.4, 0.0, 2.4}, {1.4, -0.784, 2.4}, {0.784, -1.4, 2.4}, {0.0, -1.4, 2.4},
    {1.3375, 0.0, 2.53125}, {1.3375, -0.749, 2.53125}, {0.749, -1.3375, 2.53125},
    {0.0, -1.3375, 2.53125},
    {1.4375, 0.0, 2.53125}, {1.4375, -0.805, 2.53125}, {0.805, -1.4375, 2.53125},
    {0.0, -1.4375, 2.53125},
    {1.5, 0.0, 2.4}, {1.5, -0.84, 2.4}, {0.84, -1.5, 2.4}, {0.0, -1.5, 2.4},
    {-0.784, -1.4, 2.4}, {-1.4, -0.784, 2.4}, {-1.4, 0.0, 2.4},
    {-0.749, -1.3375, 2.53125}, {-1.3375, -0.749, 2.53125}, {-1.3375, 0.0, 2.53125},
    {-0.805, -1.4375, 2.53125}, {-1.4375, -0.805, 2.53125}, {-1.4375, 0.0, 2.53125},
    {-0.84, -1.5, 2.4}, {-1.5, -0.84, 2.4}, {-1.5, 0.0, 2.4},
    {-1.4, 0.784, 2.4}, {-0.784, 1.4, 2.4}, {0.0, 1.4, 2.4},
    {-1.3375, 0.749, 2.53125}, {-0.749, 1.3375, 2.53125}, {0.0, 1.3375, 2.53125},
    {-1.4375, 0.805, 2.53125}, {-0.805, 1.4375, 2.53125}, {0.0, 1.4375, 2.53125},
    {-1.5, 0.84, 2.4}, {-0.84, 1.5, 2.4}, {0.0, 1.5, 2.4},
    {0.784, 1.4, 2.4}, {1.4, 0.784, 2.4},
    {0.749, 1.3375, 2.53125}, {1.3375, 0.749, 2.53125},
    {0.805, 1.4375, 2.53125}, {1.4375, 0.805, 2.53125},
    {0.84, 1.5, 2.4}, {1.5, 0.84, 2.4},
    // 49 - 120: body
    {1.75, 0.0, 1.875}, {1.75, -0.98, 1.875}, {0.98, -1.75, 1.875}, {0.0, -1.75, 1.875},
    {2.0, 0.0, 1.35}, {2.0, -1.12, 1.35}, {1.12, -2.0, 1.35}, {0.0, -2.0, 1.35},
    {2.0, 0.0, 0.9}, {2.0, -1.12, 0.9}, {1.12, -2.0, 0.9}, {0.0, -2.0, 0.9},
    {-0.98, -1.75, 1.875}, {-1.75, -0.98, 1.875}, {-1.75, 0.0, 1.875},
    {-1.12, -2.0, 1.35}, {-2.0, -1.12, 1.35}, {-2.0, 0.0, 1.35},
    {-1.12, -2.0, 0.9}, {-2.0, -1.12, 0.9}, {-2.0, 0.0, 0.9},
    {-1.75, 0.98, 1.875}, {-0.98, 1.75, 1.875}, {0.0, 1.75, 1.875},
    {-2.0, 1.12, 1.35}, {-1.12, 2.0, 1.35}, {0.0, 2.0, 1.35},
    {-2.0, 1.12, 0.9}, {-1.12, 2.0, 0.9}, {0.0, 2.0, 0.9},
    {0.98, 1.75, 1.875}, {1.75, 0.98, 1.875},
    {1.12, 2.0, 1.35}, {2.0, 1.12, 1.35},
    {1.12, 2.0, 0.9}, {2.0, 1.12, 0.9},
    {2.0, 0.0, 0.45}, {2.0, -1.12, 0.45}, {1.12, -2.0, 0.45}, {0.0, -2.0, 0.45},
    {1.5, 0.0, 0.225}, {1.5, -0.84, 0.225}, {0.84, -1.5, 0.225}, {0.0, -1.5, 0.225},
    {1.5, 0.0, 0.15}, {1.5, -0.84, 0.15}, {0.84, -1.5, 0.15}, {0.0, -1.5, 0.15},
    {-1.12, -2.0, 0.45}, {-2.0, -1.12, 0.45}, {-2.0, 0.0, 0.45},
    {-0.84, -1.5, 0.225}, {-1.5, -0.84, 0.225}, {-1.5, 0.0, 0.225},
    {-0.84, -1.5, 0.15}, {-1.5, -0.84, 0.15}, {-1.5, 0.0, 0.15},
    {-2.0, 1.12, 0.45}, {-1.12, 2.0, 0.45}, {0.0, 2.0, 0.45},
    {-1.5, 0.84, 0.225}, {-0.84, 1.5, 0.225}, {0.0, 1.5, 0.225},
    {-1.5, 0.84, 0.15}, {-0.84, 1.5, 0.15}, {0.0, 1.5, 0.15},
    {1.12, 2.0, 0.45}, {2.0, 1.12, 0.45},
    {0.84, 1.5, 0.225}, {1.5, 0.84, 0.225},
    {0.84, 1.5, 0.15}, {1.5, 0.84, 0.15},
    // 121 - 161: handle
    {-1.6, 0.0, 2.025}, {-1.6, -0.3, 2.025}, {-1.5, -0.3, 2.25}, {-1.5, 0.0, 2.25},
    {-2.3, 0.0, 2.025}, {-2.3, -0.3, 2.025}, {-2.5, -0.3, 2.25}, {-2.5, 0.0, 2.25},
    {-2.7, 0.0, 2.025}, {-2.7, -0.3, 2.025}, {-3.0, -0.3, 2.25}, {-3.0, 0.0, 2.25},
    {-2.7, 0.0, 1.8}, {-2.7, -0.3, 1.8}, {-3.0, -0.3, 1.8}, {-3.0, 0.0, 1.8},
    {-1.5, 0.3, 2.25}, {-1.6, 0.3, 2.025}, {-2.5, 0.3, 2.25}, {-2.3, 0.3, 2.025},
    {-3.0, 0.3, 2.25}, {-2.7, 0.3, 2.025}, {-3.0, 0.3, 1.8}, {-2.7, 0.3, 1.8},
    {-2.7, 0.0, 1.575}, {-2.7, -0.3, 1.575}, {-3.0, -0.3, 1.35}, {-3.0, 0.0, 1.35},
    {-2.5, 0.0, 1.125}, {-2.5, -0.3, 1.125}, {-2.65, -0.3, 0.9375}, {-2.65, 0.0, 0.9375},
    {-2.0, -0.3, 0.9}, {-1.9, -0.3, 0.6}, {-1.9, 0.0, 0.6},
    {-3.0, 0.3, 1.35}, {-2.7, 0.3, 1.575}, {-2.65, 0.3, 0.9375}, {-2.5, 0.3, 1.125},
    {-1.9, 0.3, 0.6}, {-2.0, 0.3, 0.9},
    // 162 - 203: spout
    {1.7, 0.0, 1.425}, {1.7, -0.66, 1.425}, {1.7, -0.66, 0.6}, {1.7, 0.0, 0.6},
    {2.6, 0.0, 1.425}, {2.6, -0.66, 1.425}, {3.1, -0.66, 0.825}, {3.1, 0.0, 0.825},
    {2.3, 0.0, 2.1}, {2.3, -0.25, 2.1}, {2.4, -0.25, 2.025}, {2.4, 0.0, 2.025},
    {2.7, 0.0, 2.4}, {2.7, -0.25, 2.4}, {3.3, -0.25, 2.4}, {3.3, 0.0, 2.4},
    {1.7, 0.66, 0.6}, {1.7, 0.66, 1.425}, {3.1, 0.66, 0.825}, {2.6, 0.66, 1.425},
    {2.4, 0.25, 2.025}, {2.3, 0.25, 2.1}, {3.3, 0.25, 2.4}, {2.7, 0.25, 2.4},
    {2.8, 0.0, 2.475}, {2.8, -0.25, 2.475}, {3.525, -0.25, 2.49375}, {3.525, 0.0, 2.49375},
    {2.9, 0.0, 2.475}, {2.9, -0.15, 2.475}, {3.45, -0.15, 2.5125}, {3.45, 0.0, 2.5125},
    {2.8, 0.0, 2.4}, {2.8, -0.15, 2.4}, {3.2, -0.15, 2.4}, {3.2, 0.0, 2.4},
    {3.525, 0.25, 2.49375}, {2.8, 0.25, 2.475}, {3.45, 0.15, 2.5125}, {2.9, 0.15, 2.475},
    {3.2, 0.15, 2.4}, {2.8, 0.15, 2.4},
    // 204 - 269: lid (205, 206, 216 and 223 are in the dataset but no patch uses them)
    {0.0, 0.0, 3.15}, {0.0, -0.002, 3.15}, {0.002, 0.0, 3.15},
    {0.8, 0.0, 3.15}, {0.8, -0.45, 3.15}, {0.45, -0.8, 3.15}, {0.0, -0.8, 3.15},
    {0.0, 0.0, 2.85},
    {0.2, 0.0, 2.7}, {0.2, -0.112, 2.7}, {0.112, -0.2, 2.7}, {0.0, -0.2, 2.7},
    {-0.002, 0.0, 3.15}, {-0.45, -0.8, 3.15}, {-0.8, -0.45, 3.15}, {-0.8, 0.0, 3.15},
    {-0.112, -0.2, 2.7}, {-0.2, -0.112, 2.7}, {-0.2, 0.0, 2.7},
    {0.0, 0.002, 3.15}, {-0.8, 0.45, 3.15}, {-0.45, 0.8, 3.15}, {0.0, 0.8, 3.15},
    {-0.2, 0.112, 2.7}, {-0.112, 0.2, 2.7}, {0.0, 0.2, 2.7},
    {0.45, 0.8, 3.15}, {0.8, 0.45, 3.15}, {0.112, 0.2, 2.7}, {0.2, 0.112, 2.7},
    {0.4, 0.0, 2.55}, {0.4, -0.224, 2.55}, {0.224, -0.4, 2.55}, {0.0, -0.4, 2.55},
    {1.3, 0.0, 2.55}, {1.3, -0.728, 2.55}, {0.728, -1.3, 2.55}, {0.0, -1.3, 2.55},
    {1.3, 0.0, 2.4}, {1.3, -0.728, 2.4}, {0.728, -1.3, 2.4}, {0.0, -1.3, 2.4},
    {-0.224, -0.4, 2.55}, {-0.4, -0.224, 2.55}, {-0.4, 0.0, 2.55},
    {-0.728, -1.3, 2.55}, {-1.3, -0.728, 2.55}, {-1.3, 0.0, 2.55},
    {-0.728, -1.3, 2.4}, {-1.3, -0.728, 2.4}, {-1.3, 0.0, 2.4},
    {-0.4, 0.224, 2.55}, {-0.224, 0.4, 2.55}, {0.0, 0.4, 2.55},
    {-1.3, 0.728, 2.55}, {-0.728, 1.3, 2.55}, {0.0, 1.3, 2.55},
    {-1.3, 0.728, 2.4}, {-0.728, 1.3, 2.4}, {0.0, 1.3, 2.4},
    {0.224, 0.4, 2.55}, {0.4, 0.224, 2.55},
    {0.728, 1.3, 2.55}, {1.3, 0.728, 2.55},
    {0.728, 1.3, 2.4}, {1.3, 0.728, 2.4},
    // 270 - 306: bottom
    {0.0, 0.0, 0.0},
    {1.5, 0.0, 0.15}, {1.5, 0.84, 0.15}, {0.84, 1.5, 0.15}, {0.0, 1.5, 0.15},
    {1.5, 0.0, 0.075}, {1.5, 0.84, 0.075}, {0.84, 1.5, 0.075}, {0.0, 1.5, 0.075},
    {1.425, 0.0, 0.0}, {1.425, 0.798, 0.0}, {0.798, 1.425, 0.0}, {0.0, 1.425, 0.0},
    {-0.84, 1.5, 0.15}, {-1.5, 0.84, 0.15}, {-1.5, 0.0, 0.15},
    {-0.84, 1.5, 0.075}, {-1.5, 0.84, 0.075}, {-1.5, 0.0, 0.075},
    {-0.798, 1.425, 0.0}, {-1.425, 0.798, 0.0}, {-1.425, 0.0, 0.0},
    {-1.5, -0.84, 0.15}, {-0.84, -1.5, 0.15}, {0.0, -1.5, 0.15},
    {-1.5, -0.84, 0.075}, {-0.84, -1.5, 0.075}, {0.0, -1.5, 0.075},
    {-1.425, -0.798, 0.0}, {-0.798, -1.425, 0.0}, {0.0, -1.425, 0.0},
    {0.84, -1.5, 0.15}, {1.5, -0.84, 0.15},
    {0.84, -1.5, 0.075}, {1.5, -0.84, 0.075},
    {0.798, -1.425, 0.0}, {1.425, -0.798, 0.0},
}};
// clang-format on

using Vec = glm::dvec3;

Vec controlPoint(std::size_t patch, std::size_t row, std::size_t col) {
    const auto& c = kControlPoints[kPatches[patch][row * 4 + col] - 1u];
    return Vec(c[0], c[1], c[2]);
}

// Cubic Bernstein basis and its derivative at t.
void bernstein(double t, double b[4], double db[4]) {
    const double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
    db[0] = -3.0 * s * s;
    db[1] = 3.0 * s * s - 6.0 * t * s;
    db[2] = 6.0 * t * s - 3.0 * t * t;
    db[3] = 3.0 * t * t;
}

struct PatchSample {
    Vec p;   // position
    Vec pu;  // dP/du
    Vec pv;  // dP/dv
};

PatchSample evalPatch(std::size_t patch, double u, double v) {
    double bu[4], dbu[4], bv[4], dbv[4];
    bernstein(u, bu, dbu);
    bernstein(v, bv, dbv);
    PatchSample s{Vec(0.0), Vec(0.0), Vec(0.0)};
    for (std::size_t i = 0; i < 4; ++i) {
        for (std::size_t j = 0; j < 4; ++j) {
            const Vec c = controlPoint(patch, i, j);
            s.p += bu[i] * bv[j] * c;
            s.pu += dbu[i] * bv[j] * c;
            s.pv += bu[i] * dbv[j] * c;
        }
    }
    return s;
}

// The unnormalised analytic normal, or zero when the derivatives are (nearly) parallel or
// vanish, as on an edge collapsed to a point.
Vec rawNormal(const PatchSample& s) {
    const Vec n = glm::cross(s.pu, s.pv);
    const double scale = std::max(glm::dot(s.pu, s.pu), glm::dot(s.pv, s.pv));
    if (!(glm::length(n) > 1e-9 * scale)) return Vec(0.0);
    return n;
}

// Normal at (u, v); at degenerate points, from samples nudged towards the patch centre.
// Returns zero if every attempt is degenerate.
Vec patchNormal(std::size_t patch, double u, double v) {
    Vec n = rawNormal(evalPatch(patch, u, v));
    for (double nudge : {1e-4, 1e-3, 1e-2, 1e-1}) {
        if (n != Vec(0.0)) break;
        n = rawNormal(evalPatch(patch, u + nudge * (0.5 - u), v + nudge * (0.5 - v)));
    }
    return n == Vec(0.0) ? n : glm::normalize(n);
}

// Which patch edges collapse to a single point, as bits: 1 = u=0, 2 = u=1, 4 = v=0, 8 = v=1.
unsigned collapsedEdges(std::size_t patch) {
    const auto& idx = kPatches[patch];
    auto same = [&](int a, int b, int c, int d) {
        return idx[a] == idx[b] && idx[a] == idx[c] && idx[a] == idx[d];
    };
    unsigned mask = 0;
    if (same(0, 1, 2, 3)) mask |= 1u;
    if (same(12, 13, 14, 15)) mask |= 2u;
    if (same(0, 4, 8, 12)) mask |= 4u;
    if (same(3, 7, 11, 15)) mask |= 8u;
    return mask;
}

// The collapsed edges of patch that grid vertex (i, j) of a level x level grid lies on.
unsigned vertexEdgeMask(unsigned patchMask, uint32_t i, uint32_t j, uint32_t level) {
    unsigned m = 0;
    if (i == 0) m |= 1u;
    if (i == level) m |= 2u;
    if (j == 0) m |= 4u;
    if (j == level) m |= 8u;
    return m & patchMask;
}

struct RawMesh {
    std::vector<Vec> positions;
    std::vector<Vec> normals;  // zero where the analytic normal failed
    std::vector<uint32_t> indices;
};

// Appends one patch as a level x level grid. With flip the analytic normal is negated and the
// triangles are wound the other way, so winding always agrees with the stored normal.
void appendPatch(RawMesh& mesh, std::size_t patch, uint32_t level, bool flip, bool withNormals) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    const unsigned mask = collapsedEdges(patch);
    const uint32_t n = level + 1;
    for (uint32_t i = 0; i < n; ++i) {
        const double u = static_cast<double>(i) / level;
        for (uint32_t j = 0; j < n; ++j) {
            const double v = static_cast<double>(j) / level;
            Vec p = evalPatch(patch, u, v).p;
            // Snap vertices on a collapsed edge exactly onto its control point.
            const unsigned m = vertexEdgeMask(mask, i, j, level);
            if (m & 1u) p = controlPoint(patch, 0, 0);
            if (m & 2u) p = controlPoint(patch, 3, 0);
            if (m & 4u) p = controlPoint(patch, 0, 0);
            if (m & 8u) p = controlPoint(patch, 0, 3);
            mesh.positions.push_back(p);
            if (withNormals) {
                const Vec nrm = patchNormal(patch, u, v);
                mesh.normals.push_back(flip ? -nrm : nrm);
            }
        }
    }
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c, unsigned ma, unsigned mb, unsigned mc) {
        if ((ma & mb) || (mb & mc) || (ma & mc)) return;  // two corners on a collapsed edge
        mesh.indices.push_back(base + a);
        mesh.indices.push_back(base + (flip ? c : b));
        mesh.indices.push_back(base + (flip ? b : c));
    };
    for (uint32_t i = 0; i < level; ++i) {
        for (uint32_t j = 0; j < level; ++j) {
            // Counter-clockwise in the (u, v) plane, so the face normal follows cross(Pu, Pv).
            const uint32_t a = i * n + j, b = (i + 1) * n + j;
            const uint32_t c = (i + 1) * n + j + 1, d = i * n + j + 1;
            const unsigned ma = vertexEdgeMask(mask, i, j, level);
            const unsigned mb = vertexEdgeMask(mask, i + 1, j, level);
            const unsigned mc = vertexEdgeMask(mask, i + 1, j + 1, level);
            const unsigned md = vertexEdgeMask(mask, i, j + 1, level);
            emit(a, b, c, ma, mb, mc);
            emit(a, c, d, ma, mc, md);
        }
    }
}

// Ray (origin o, direction d) against triangle (p0, p1, p2): true on a hit at t > 0.
bool rayHitsTriangle(const Vec& o, const Vec& d, const Vec& p0, const Vec& p1, const Vec& p2) {
    const Vec e1 = p1 - p0, e2 = p2 - p0;
    const Vec h = glm::cross(d, e2);
    const double det = glm::dot(e1, h);
    if (std::abs(det) < 1e-14) return false;
    const double inv = 1.0 / det;
    const Vec s = o - p0;
    const double bu = glm::dot(s, h) * inv;
    if (bu < 0.0 || bu > 1.0) return false;
    const Vec q = glm::cross(s, e1);
    const double bv = glm::dot(d, q) * inv;
    if (bv < 0.0 || bu + bv > 1.0) return false;
    return glm::dot(e2, q) * inv > 0.0;
}

// For each patch, whether cross(dP/du, dP/dv) points into the teapot. Decided by votes: from a
// few points just off the patch along that normal, rays in several directions are cast against
// a reference tessellation and an odd crossing count means "inside". The teapot is not exactly
// closed (the lid does not meet the rim; the spout tip is open), so single rays can be fooled;
// the majority is not.
std::array<bool, kTeapotPatchCount> computeInwardPatches() {
    RawMesh ref;
    constexpr uint32_t kRefLevel = 10;
    for (std::size_t p = 0; p < kTeapotPatchCount; ++p) {
        appendPatch(ref, p, kRefLevel, false, false);
    }

    const std::array<Vec, 5> dirs = {
        glm::normalize(Vec(0.31, 0.77, 0.56)), glm::normalize(Vec(-0.62, 0.21, 0.75)),
        glm::normalize(Vec(0.45, -0.83, -0.33)), glm::normalize(Vec(-0.37, -0.29, -0.88)),
        glm::normalize(Vec(0.93, 0.17, -0.32))};
    const std::array<std::array<double, 2>, 5> samples = {
        {{0.5, 0.5}, {0.3, 0.3}, {0.3, 0.7}, {0.7, 0.3}, {0.7, 0.7}}};
    constexpr double kOffset = 0.01;  // dataset units; the teapot is 3.15 tall

    std::array<bool, kTeapotPatchCount> inward{};
    for (std::size_t p = 0; p < kTeapotPatchCount; ++p) {
        int votesInward = 0, votesOutward = 0;
        for (const auto& uv : samples) {
            const PatchSample s = evalPatch(p, uv[0], uv[1]);
            const Vec n = rawNormal(s);
            if (n == Vec(0.0)) continue;
            const Vec origin = s.p + kOffset * glm::normalize(n);
            for (const Vec& d : dirs) {
                int hits = 0;
                for (std::size_t t = 0; t + 2 < ref.indices.size(); t += 3) {
                    hits += rayHitsTriangle(origin, d, ref.positions[ref.indices[t]],
                                            ref.positions[ref.indices[t + 1]],
                                            ref.positions[ref.indices[t + 2]]);
                }
                (hits % 2 == 1 ? votesInward : votesOutward) += 1;
            }
        }
        inward[p] = votesInward > votesOutward;
    }
    return inward;
}

const std::array<bool, kTeapotPatchCount>& inwardPatches() {
    static const std::array<bool, kTeapotPatchCount> inward = computeInwardPatches();
    return inward;
}

}  // namespace

MeshData tessellateTeapot(uint32_t level) {
    if (level == 0 || level > kTeapotMaxLevel) {
        throw std::invalid_argument("tessellateTeapot: level must be in [1, " +
                                    std::to_string(kTeapotMaxLevel) + "], got " +
                                    std::to_string(level));
    }
    const auto& inward = inwardPatches();
    RawMesh raw;
    raw.positions.reserve(teapotVertexCount(level));
    raw.normals.reserve(teapotVertexCount(level));
    raw.indices.reserve(3 * teapotTriangleCount(level));
    for (std::size_t p = 0; p < kTeapotPatchCount; ++p) {
        appendPatch(raw, p, level, inward[p], true);
    }

    // Last resort for normals the analytic evaluation could not give: averaged face normals.
    bool anyMissing = false;
    for (const Vec& n : raw.normals) anyMissing = anyMissing || n == Vec(0.0);
    if (anyMissing) {
        std::vector<Vec> faceSum(raw.positions.size(), Vec(0.0));
        for (std::size_t t = 0; t + 2 < raw.indices.size(); t += 3) {
            const uint32_t i0 = raw.indices[t], i1 = raw.indices[t + 1], i2 = raw.indices[t + 2];
            const Vec fn = glm::cross(raw.positions[i1] - raw.positions[i0],
                                      raw.positions[i2] - raw.positions[i0]);
            for (uint32_t i : {i0, i1, i2}) faceSum[i] += fn;
        }
        for (std::size_t i = 0; i < raw.normals.size(); ++i) {
            if (raw.normals[i] != Vec(0.0)) continue;
            const double len = glm::length(faceSum[i]);
            raw.normals[i] = len > 0.0 ? faceSum[i] / len : Vec(0.0, 0.0, 1.0);
        }
    }

    // z-up -> y-up: (x, y, z) -> (x, z, -y).
    auto toYUp = [](const Vec& v) { return Vec(v.x, v.z, -v.y); };
    Vec lo(std::numeric_limits<double>::infinity());
    Vec hi(-std::numeric_limits<double>::infinity());
    for (Vec& p : raw.positions) {
        p = toYUp(p);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const double height = hi.y - lo.y;
    const Vec origin(0.5 * (lo.x + hi.x), lo.y, 0.5 * (lo.z + hi.z));

    MeshData mesh;
    mesh.positions.reserve(raw.positions.size());
    mesh.normals.reserve(raw.normals.size());
    for (const Vec& p : raw.positions) mesh.positions.push_back(glm::vec3((p - origin) / height));
    for (const Vec& n : raw.normals) mesh.normals.push_back(glm::vec3(glm::normalize(toYUp(n))));
    mesh.indices = std::move(raw.indices);
    return mesh;
}

}  // namespace occsim
