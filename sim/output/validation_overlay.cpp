#include "sim/output/validation_overlay.h"

#include <array>

#include "sim/output/box_wireframe.h"

namespace occsim {
namespace {

// Culled first and dim (there are many), then over-draw, then what was missed, on top.
constexpr std::array<ValidationClass, 3> kClasses = {{
    {ObjectVerdict::Culled, kCulledColour, "culled (not drawn, not seen)"},
    {ObjectVerdict::DrawnHidden, kDrawnHiddenColour, "drawn while hidden"},
    {ObjectVerdict::Missed, kMissedColour, "missed (seen, not drawn)"},
}};

constexpr float kMissedTint = 0.6f;

}  // namespace

std::span<const ValidationClass> validationClasses() { return kClasses; }

void drawValidationOverlay(RasterCanvas& canvas, const ValidationInput& in) {
    const uint32_t w = canvas.width(), h = canvas.height();
    // The missed objects' own pixels, as ground truth shows them.
    if (in.truth_ids.size() == size_t{w} * h) {
        for (uint32_t y = 0; y < h; ++y) {
            const uint32_t* row = in.truth_ids.data() + size_t{h - 1 - y} * w;
            for (uint32_t x = 0; x < w; ++x) {
                const uint32_t id = row[x];
                if (id == 0 || id - 1 >= in.verdicts.size()) continue;
                if (static_cast<ObjectVerdict>(in.verdicts[id - 1]) == ObjectVerdict::Missed)
                    canvas.pixel(static_cast<int>(x), static_cast<int>(y), kMissedColour,
                                 kMissedTint);
            }
        }
    }
    for (const ValidationClass& c : kClasses) {
        for (size_t o = 0; o < in.verdicts.size() && o < in.object_boxes.size(); ++o) {
            if (static_cast<ObjectVerdict>(in.verdicts[o]) != c.verdict) continue;
            drawBoxWireframe(canvas, in.view, in.near_m, in.object_boxes[o], c.colour);
        }
    }
}

}  // namespace occsim
