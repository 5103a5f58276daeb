#include "sim/output/birds_eye.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "occsim/culling/geometry/frustum.h"

namespace occsim {
namespace {

// ---- classification ------------------------------------------------------------------------

struct QueryMarks {
    std::vector<uint8_t> zero, visible, pending;  // per node
};

// What each node's queries said, from the subjects the culler tagged them with. A query on a
// node's own objects (a virtual leaf) is made after they were drawn, so its zero result culls
// nothing: only its visible or pending state counts. Per-object queries mark no node. A query
// that draws were conditioned on (conditional rendering) is never fetched; its node counts as
// drawn after a query, which it was, the device having had the last word.
QueryMarks markQueriedNodes(const BspTree& tree, const FrameTrace& trace) {
    QueryMarks m;
    m.zero.assign(tree.nodeCount(), 0);
    m.visible.assign(tree.nodeCount(), 0);
    m.pending.assign(tree.nodeCount(), 0);
    for (const TracedQuery& q : trace.queries) {
        for (const QueryTag& tag : q.subjects) {
            if (tag.subject == QueryTag::Subject::Object || tag.index >= tree.nodeCount()) continue;
            const uint32_t n = tag.index;
            if (q.conditional)  // objects drawn under its condition: the device decided them
                m.visible[n] = 1;
            else if (!q.fetched)
                m.pending[n] = 1;
            else if (q.visible)
                m.visible[n] = 1;
            else if (tag.subject == QueryTag::Subject::Node)
                m.zero[n] = 1;
        }
    }
    return m;
}

}  // namespace

const char* nodeClassName(NodeClass c) {
    switch (c) {
        case NodeClass::Empty:
            return "empty";
        case NodeClass::FrustumCulled:
            return "frustum culled";
        case NodeClass::OcclusionCulled:
            return "occlusion culled";
        case NodeClass::DrawnAfterQuery:
            return "drawn after query";
        case NodeClass::DrawnWithoutQuery:
            return "drawn without query";
        case NodeClass::NotReached:
            return "not reached";
        case NodeClass::Passed:
            return "passed through";
        case NodeClass::CulledWithoutQuery:
            return "culled without query";
    }
    return "?";
}

Rgb nodeClassColour(NodeClass c) {
    switch (c) {
        case NodeClass::Empty:
            return {0, 0, 0};
        case NodeClass::FrustumCulled:
            return {235, 64, 52};  // red, as in the CHC figure
        case NodeClass::OcclusionCulled:
            return {66, 135, 255};  // blue, as in the CHC figure
        case NodeClass::DrawnAfterQuery:
            return {64, 220, 110};  // green
        case NodeClass::DrawnWithoutQuery:
            return {225, 95, 225};  // magenta
        case NodeClass::NotReached:
            return {72, 84, 150};  // dim blue: behind a blue one
        case NodeClass::Passed:
            return {70, 150, 150};  // dim teal
        case NodeClass::CulledWithoutQuery:
            return {150, 110, 255};  // violet: occlusion culled like blue, by another test
    }
    return {};
}

std::vector<NodeClass> classifyNodes(const BspTree& tree, const CullView& view,
                                     const FrameTrace& trace) {
    const uint32_t count = tree.nodeCount();
    std::vector<uint8_t> own_drawn(count, 0), subtree_drawn(count, 0);
    for (uint32_t o : trace.drawn_objects) {
        if (o < tree.objectCount()) own_drawn[tree.nodeOf(o)] = 1;
    }
    subtree_drawn = own_drawn;
    // Children come after their parents, so a reverse scan sees every child before its parent.
    // Slots a merge freed (no parent) hold no node.
    for (uint32_t n = count; n-- > 1;) {
        if (tree.isLive(n)) subtree_drawn[tree.node(n).parent] |= subtree_drawn[n];
    }
    const QueryMarks q = markQueriedNodes(tree, trace);
    // A frame without queries culled by a test of its own (a depth pyramid, a software buffer):
    // what it hid is what it did not draw, and says so in the picture.
    const bool no_queries = trace.queries.empty() && trace.earlier_results_fetched == 0;

    std::vector<NodeClass> out(count, NodeClass::Empty);
    for (uint32_t n = 0; n < count; ++n) {  // parents first: NotReached needs the parent's class
        const Aabb& b = tree.bounds(n);
        const uint32_t parent = tree.node(n).parent;
        const bool below_culled =
            parent != BspTree::kNone &&
            (out[parent] == NodeClass::OcclusionCulled || out[parent] == NodeClass::NotReached ||
             out[parent] == NodeClass::CulledWithoutQuery);
        if (isEmpty(b))
            out[n] = NodeClass::Empty;
        else if (classify(view.frustum, b) == FrustumTest::Outside)
            out[n] = NodeClass::FrustumCulled;
        else if (q.zero[n] && !q.visible[n])
            out[n] = NodeClass::OcclusionCulled;
        else if (q.visible[n] && subtree_drawn[n])
            out[n] = NodeClass::DrawnAfterQuery;
        else if (own_drawn[n])
            out[n] = NodeClass::DrawnWithoutQuery;
        else if (below_culled)
            out[n] = NodeClass::NotReached;
        else if (no_queries && !subtree_drawn[n])
            out[n] = NodeClass::CulledWithoutQuery;
        else
            out[n] = NodeClass::Passed;
    }
    return out;
}

// ---- picture ------------------------------------------------------------------------------

namespace {

constexpr int kFontScale = 2;
constexpr int kPad = 14;  // pixels around the fitted region and the legend

// World (x, z) to pixel: uniform scale, the region's centre at the drawing area's centre.
struct TopView {
    double scale = 1.0;
    double world_cx = 0.0, world_cz = 0.0;
    double pixel_cx = 0.0, pixel_cy = 0.0;

    glm::dvec2 toPixel(double x, double z) const {
        return {pixel_cx + (x - world_cx) * scale, pixel_cy + (z - world_cz) * scale};
    }
    glm::dvec2 toWorld(double px, double py) const {
        return {world_cx + (px - pixel_cx) / scale, world_cz + (py - pixel_cy) / scale};
    }
};

struct PixelRect {
    int x0, y0, x1, y1;
};

// The region to show in x and z: every finite object box and the eye, plus a margin.
void fittedRegion(const BirdsEyeInput& in, glm::dvec2& lo, glm::dvec2& hi) {
    lo = glm::dvec2(in.view.eye.x, in.view.eye.z);
    hi = lo;
    for (const Aabb& b : in.object_boxes) {
        if (!isFiniteAndOrdered(b)) continue;
        lo = glm::min(lo, glm::dvec2(b.min.x, b.min.z));
        hi = glm::max(hi, glm::dvec2(b.max.x, b.max.z));
    }
    const glm::dvec2 size = glm::max(hi - lo, glm::dvec2(1e-3));
    const double margin = 0.04 * std::max(size.x, size.y);
    lo -= margin;
    hi += margin;
}

int titleBand() { return RasterCanvas::textHeight(kFontScale) + 2 * 8; }

struct LegendLine {
    Rgb colour;
    bool filled;  // a filled swatch (objects, camera) or an outline (nodes)
    std::string label;
};

std::vector<LegendLine> legendLines(const BirdsEyeInput& in) {
    std::array<uint32_t, kNodeClassCount> counts{};
    for (NodeClass c : in.node_classes) ++counts[static_cast<size_t>(c)];
    const size_t objects = in.object_boxes.size();
    const size_t drawn = std::min(in.drawn_objects.size(), objects);
    std::vector<LegendLine> lines = {
        {kDrawnObjectColour, true, "drawn object: " + std::to_string(drawn)},
        {kHiddenObjectColour, true, "not drawn: " + std::to_string(objects - drawn)},
    };
    for (NodeClass c : {NodeClass::FrustumCulled, NodeClass::OcclusionCulled,
                        NodeClass::CulledWithoutQuery, NodeClass::DrawnAfterQuery,
                        NodeClass::DrawnWithoutQuery, NodeClass::NotReached, NodeClass::Passed}) {
        lines.push_back({nodeClassColour(c), false,
                         std::string(nodeClassName(c)) + ": " +
                             std::to_string(counts[static_cast<size_t>(c)])});
    }
    lines.push_back({kCameraColour, true, "camera, view wedge"});
    return lines;
}

int legendLineHeight() { return RasterCanvas::textHeight(kFontScale) + 6; }

// Width and height of the legend panel.
glm::ivec2 legendSize(const BirdsEyeInput& in) {
    if (!in.draw_legend) return {0, 0};
    const std::vector<LegendLine> lines = legendLines(in);
    int text_w = 0;
    for (const LegendLine& l : lines) {
        text_w = std::max(text_w, RasterCanvas::textWidth(l.label, kFontScale));
    }
    const int swatch = RasterCanvas::textHeight(kFontScale);
    return {8 + swatch + 8 + text_w + 8,
            8 + static_cast<int>(lines.size()) * legendLineHeight() + 2};
}

// Where the scene and the legend go: the legend in a column on the right or a band at the
// bottom, whichever leaves the scene the larger scale, so that it never hides the scene.
struct Layout {
    TopView view;
    PixelRect legend;
};

Layout layOut(const BirdsEyeInput& in, uint32_t width, uint32_t height) {
    glm::dvec2 lo, hi;
    fittedRegion(in, lo, hi);
    const glm::ivec2 legend = legendSize(in);
    const int W = static_cast<int>(width), H = static_cast<int>(height), top = titleBand();
    auto scaleFor = [&](double area_w, double area_h) {
        return std::min(std::max(1.0, area_w) / (hi.x - lo.x),
                        std::max(1.0, area_h) / (hi.y - lo.y));
    };
    const double full_w = W - 2.0 * kPad, full_h = H - 2.0 * kPad - top;
    const double column_w = full_w - (legend.x ? legend.x + kPad : 0);
    const double band_h = full_h - (legend.y ? legend.y + kPad : 0);
    const bool column = scaleFor(column_w, full_h) >= scaleFor(full_w, band_h);
    const double area_w = column ? column_w : full_w, area_h = column ? full_h : band_h;

    Layout l;
    l.view.scale = scaleFor(area_w, area_h);
    l.view.world_cx = 0.5 * (lo.x + hi.x);
    l.view.world_cz = 0.5 * (lo.y + hi.y);
    l.view.pixel_cx = kPad + 0.5 * area_w;
    l.view.pixel_cy = top + kPad + 0.5 * area_h;
    l.legend = column ? PixelRect{W - kPad - legend.x, top + kPad, W - kPad, top + kPad + legend.y}
                      : PixelRect{kPad, H - kPad - legend.y, kPad + legend.x, H - kPad};
    return l;
}

PixelRect rectOf(const TopView& v, const Aabb& b) {
    const glm::dvec2 a = v.toPixel(b.min.x, b.min.z), c = v.toPixel(b.max.x, b.max.z);
    // Clamp before converting: a huge box must not overflow int.
    auto px = [](double p) { return static_cast<int>(std::lround(std::clamp(p, -1e6, 1e6))); };
    return {px(a.x), px(a.y), std::max(px(a.x), px(c.x)), std::max(px(a.y), px(c.y))};
}

// The horizontal view wedge: the forward direction in the ground plane and the half angle.
struct Wedge {
    bool valid = false;
    glm::dvec2 eye, dir, left, right;  // unit directions of the two edges
    double length = 0.0;               // along an edge, to the far plane
};

Wedge viewWedge(const BirdsEyeInput& in) {
    Wedge w;
    const glm::dvec2 f(in.forward.x, in.forward.z);
    const double flat = glm::length(f);
    // Looking (almost) straight down or up: the wedge has no horizontal direction.
    if (!(flat > 1e-3) || !(in.fov_y_rad > 0.0f)) return w;
    const double half = std::atan(std::tan(0.5 * in.fov_y_rad) * in.aspect);
    w.valid = true;
    w.eye = {in.view.eye.x, in.view.eye.z};
    w.dir = f / flat;
    auto rotate = [](glm::dvec2 d, double a) {
        return glm::dvec2(d.x * std::cos(a) - d.y * std::sin(a),
                          d.x * std::sin(a) + d.y * std::cos(a));
    };
    w.left = rotate(w.dir, -half);
    w.right = rotate(w.dir, half);
    // The far plane is at far along the view direction; its horizontal reach shrinks as the
    // camera pitches.
    w.length = in.far_m * flat / std::cos(half);
    return w;
}

void tintWedge(RasterCanvas& canvas, const TopView& v, const Wedge& w) {
    if (!w.valid) return;
    const double reach = glm::dot(w.left * w.length, w.dir);
    // Inward normals of the two edges.
    const glm::dvec2 n_left(-w.left.y, w.left.x), n_right(w.right.y, -w.right.x);
    const double sign = glm::dot(n_left, w.dir) < 0.0 ? -1.0 : 1.0;
    for (uint32_t y = 0; y < canvas.height(); ++y) {
        for (uint32_t x = 0; x < canvas.width(); ++x) {
            const glm::dvec2 d = v.toWorld(x, y) - w.eye;
            if (sign * glm::dot(d, n_left) >= 0 && sign * glm::dot(d, n_right) >= 0 &&
                glm::dot(d, w.dir) <= reach) {
                canvas.pixel(static_cast<int>(x), static_cast<int>(y), kWedgeColour, 0.10f);
            }
        }
    }
}

void drawWedgeLines(RasterCanvas& canvas, const TopView& v, const Wedge& w) {
    if (!w.valid) return;
    const glm::dvec2 e = v.toPixel(w.eye.x, w.eye.y);
    const glm::dvec2 l = w.eye + w.left * w.length, r = w.eye + w.right * w.length;
    const glm::dvec2 pl = v.toPixel(l.x, l.y), pr = v.toPixel(r.x, r.y);
    canvas.line(e.x, e.y, pl.x, pl.y, kWedgeColour);
    canvas.line(e.x, e.y, pr.x, pr.y, kWedgeColour);
    canvas.line(pl.x, pl.y, pr.x, pr.y, kWedgeColour, 0.5f);  // the far plane
}

Rgb darker(Rgb c) {
    return {static_cast<uint8_t>(c.r / 2), static_cast<uint8_t>(c.g / 2),
            static_cast<uint8_t>(c.b / 2)};
}

// Footprints covering at least this share of the picture's area are ground: floors and slabs.
constexpr double kGroundShare = 0.05;

void drawObjects(RasterCanvas& canvas, const TopView& v, const BirdsEyeInput& in) {
    std::vector<uint8_t> drawn(in.object_boxes.size(), 0);
    for (uint32_t o : in.drawn_objects) {
        if (o < drawn.size()) drawn[o] = 1;
    }
    // Ground first (the largest footprint lowest), whether drawn or not: the always-drawn floor
    // of a city or a library must lie under the objects on it, not be painted over them. Then
    // the hidden ones, so a drawn object is never painted over by a hidden neighbour. A darker
    // border keeps overlapping objects apart.
    const double picture_area = double(canvas.width()) * double(canvas.height());
    std::vector<std::pair<double, size_t>> ground;
    std::vector<uint8_t> is_ground(in.object_boxes.size(), 0);
    for (size_t o = 0; o < in.object_boxes.size(); ++o) {
        if (!isFiniteAndOrdered(in.object_boxes[o])) continue;
        const PixelRect r = rectOf(v, in.object_boxes[o]);
        const double area = double(r.x1 - r.x0 + 1) * double(r.y1 - r.y0 + 1);
        if (area >= kGroundShare * picture_area) {
            ground.emplace_back(area, o);
            is_ground[o] = 1;
        }
    }
    std::sort(ground.begin(), ground.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    auto paint = [&](size_t o) {
        const Rgb fill = drawn[o] ? kDrawnObjectColour : kHiddenObjectColour;
        const PixelRect r = rectOf(v, in.object_boxes[o]);
        canvas.fillRect(r.x0, r.y0, r.x1, r.y1, fill);
        if (r.x1 - r.x0 >= 3 && r.y1 - r.y0 >= 3)
            canvas.outlineRect(r.x0, r.y0, r.x1, r.y1, darker(fill));
    };
    for (const auto& g : ground) paint(g.second);
    for (int pass = 0; pass < 2; ++pass) {
        for (size_t o = 0; o < in.object_boxes.size(); ++o) {
            if (drawn[o] != pass || is_ground[o] || !isFiniteAndOrdered(in.object_boxes[o]))
                continue;
            paint(o);
        }
    }
}

// Draw order: the dim classes first, the decisions a reader looks for last (on top).
constexpr NodeClass kOutlineOrder[] = {NodeClass::Passed,          NodeClass::NotReached,
                                       NodeClass::FrustumCulled,   NodeClass::DrawnWithoutQuery,
                                       NodeClass::DrawnAfterQuery, NodeClass::OcclusionCulled};

void drawNodeOutlines(RasterCanvas& canvas, const TopView& v, const BirdsEyeInput& in) {
    const BspTree& tree = *in.tree;
    const uint32_t count = std::min<uint32_t>(tree.nodeCount(), in.node_classes.size());
    for (NodeClass cls : kOutlineOrder) {
        for (uint32_t n = 0; n < count; ++n) {
            if (in.node_classes[n] != cls) continue;
            // Only the top of a frustum-culled subtree: that is where the traversal stopped, and
            // its descendants would fill the outside of the wedge with red.
            const uint32_t parent = tree.node(n).parent;
            if (cls == NodeClass::FrustumCulled && parent != BspTree::kNone && parent < count &&
                in.node_classes[parent] == NodeClass::FrustumCulled) {
                continue;
            }
            const PixelRect r = rectOf(v, tree.bounds(n));
            canvas.outlineRect(r.x0, r.y0, r.x1, r.y1, nodeClassColour(cls));
        }
    }
}

void drawCamera(RasterCanvas& canvas, const TopView& v, const BirdsEyeInput& in) {
    const glm::dvec2 e = v.toPixel(in.view.eye.x, in.view.eye.z);
    const int x = static_cast<int>(std::lround(std::clamp(e.x, -1e6, 1e6)));
    const int y = static_cast<int>(std::lround(std::clamp(e.y, -1e6, 1e6)));
    canvas.disk(x, y, 7, kBirdsEyeBackground);
    canvas.disk(x, y, 5, kCameraColour);
}

void drawLegend(RasterCanvas& canvas, const BirdsEyeInput& in, const PixelRect& at) {
    canvas.fillRect(at.x0, at.y0, at.x1, at.y1, {8, 9, 12}, 0.85f);
    canvas.outlineRect(at.x0, at.y0, at.x1, at.y1, {90, 90, 100});
    const int swatch = RasterCanvas::textHeight(kFontScale);
    int y = at.y0 + 8;
    for (const LegendLine& l : legendLines(in)) {
        const int x = at.x0 + 8;
        if (l.filled) {
            canvas.fillRect(x, y, x + swatch - 1, y + swatch - 1, l.colour);
        } else {  // node classes are outlines in the picture, so outlines here too
            canvas.outlineRect(x, y, x + swatch - 1, y + swatch - 1, l.colour);
            canvas.outlineRect(x + 1, y + 1, x + swatch - 2, y + swatch - 2, l.colour);
        }
        canvas.text(x + swatch + 8, y, l.label, {225, 225, 225}, kFontScale);
        y += legendLineHeight();
    }
}

}  // namespace

PictureSize birdsEyeSize(const BirdsEyeInput& input, uint32_t long_side) {
    glm::dvec2 lo, hi;
    fittedRegion(input, lo, hi);
    const double aspect = std::clamp((hi.x - lo.x) / (hi.y - lo.y), 0.25, 4.0);
    const glm::ivec2 legend = legendSize(input);
    const double top = titleBand() + 2.0 * kPad;
    // The scene's own area, its longer side long_side minus the frame; the legend beside it.
    double scene_w, scene_h;
    if (aspect >= 1.0) {
        scene_w = std::max(16.0, long_side - 2.0 * kPad);
        scene_h = scene_w / aspect;
    } else {
        scene_h = std::max(16.0, long_side - top);
        scene_w = scene_h * aspect;
    }
    const double legend_w = legend.x ? legend.x + kPad : 0.0;
    const double w = 2.0 * kPad + scene_w + legend_w;
    const double h = top + std::max(scene_h, static_cast<double>(legend.y));
    return {static_cast<uint32_t>(std::lround(w)), static_cast<uint32_t>(std::lround(h))};
}

std::vector<uint8_t> renderBirdsEye(const BirdsEyeInput& in, uint32_t width, uint32_t height) {
    RasterCanvas canvas(width, height, kBirdsEyeBackground);
    if (width == 0 || height == 0) return canvas.rgbaBottomUp();
    const Layout layout = layOut(in, width, height);
    const Wedge wedge = viewWedge(in);
    tintWedge(canvas, layout.view, wedge);
    drawObjects(canvas, layout.view, in);
    if (in.tree) drawNodeOutlines(canvas, layout.view, in);
    drawWedgeLines(canvas, layout.view, wedge);
    drawCamera(canvas, layout.view, in);
    canvas.text(kPad, 8, in.title, {235, 235, 235}, kFontScale);
    if (in.draw_legend) drawLegend(canvas, in, layout.legend);
    return canvas.rgbaBottomUp();
}

}  // namespace occsim
