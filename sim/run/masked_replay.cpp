// A recorded frame replayed into masked's buffer and an exact raster: see masked_replay.h.
#include "sim/run/masked_replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "occsim/culling/raster/exact_triangle_raster.h"

namespace occsim {
namespace {

constexpr double kBehind = 0.99;   // of the farthest 1/w: just behind every occluder pixel
constexpr double kInFront = 1.01;  // just in front of the farthest one

struct Rect {
    uint32_t x0, y0, x1, y1;  // pixels, inclusive
};

// The exact buffer's farthest 1/w over the rectangle's pixel centres; 0 if one is uncovered.
double farthest(const std::vector<double>& exact, uint32_t width, const Rect& r) {
    double d = INFINITY;
    for (uint32_t y = r.y0; y <= r.y1; ++y) {
        for (uint32_t x = r.x0; x <= r.x1; ++x) {
            d = std::min(d, exact[static_cast<size_t>(y) * width + x]);
            if (d <= 0.0) return 0.0;
        }
    }
    return d;
}

void addTally(ReplayTally& into, const ReplayTally& t) {
    into.exact_hidden += t.exact_hidden;
    into.both_hidden += t.both_hidden;
    into.exact_hidden_area += t.exact_hidden_area;
    into.both_hidden_area += t.both_hidden_area;
    into.tests += t.tests;
    into.wrongly_hidden += t.wrongly_hidden;
}

std::vector<Rect> blocks(uint32_t width, uint32_t height, uint32_t w, uint32_t h) {
    std::vector<Rect> out;
    for (uint32_t y = 0; y < height; y += h) {
        for (uint32_t x = 0; x < width; x += w) {
            out.push_back({x, y, std::min(x + w, width) - 1, std::min(y + h, height) - 1});
        }
    }
    return out;
}

// Object-sized rectangles, each with the depth (1/w) it is tested at: the exact buffer's at a
// seeded random covered pixel of the screen, as if an object stood somewhere in the scene.
std::vector<Rect> objectRects(const std::vector<double>& exact, uint32_t width, uint32_t height,
                              uint64_t seed, std::vector<double>& depths) {
    std::mt19937_64 rng(seed);
    std::vector<Rect> out;
    std::vector<double> covered;
    for (const double iw : exact) {
        if (iw > 0.0) covered.push_back(iw);
    }
    const uint32_t largest = std::min<uint32_t>({256, width, height});
    if (largest < 16 || covered.empty()) return out;
    std::uniform_int_distribution<uint32_t> side(16, largest);
    std::uniform_int_distribution<size_t> pick(0, covered.size() - 1);
    for (int i = 0; i < 4000; ++i) {
        const uint32_t w = side(rng), h = side(rng);
        const uint32_t x = std::uniform_int_distribution<uint32_t>(0, width - w)(rng);
        const uint32_t y = std::uniform_int_distribution<uint32_t>(0, height - h)(rng);
        out.push_back({x, y, x + w - 1, y + h - 1});
        depths.push_back(covered[pick(rng)]);
    }
    return out;
}

}  // namespace

double ReplayTally::share() const {
    return exact_hidden == 0 ? 1.0 : static_cast<double>(both_hidden) / exact_hidden;
}

double ReplayTally::areaShare() const {
    return exact_hidden_area == 0.0 ? 1.0 : both_hidden_area / exact_hidden_area;
}

std::vector<ReplayLayout> replayLayouts() {
    std::vector<ReplayLayout> out(3);
    out[0].name = "8x4";
    out[1].name = "32x4";
    out[1].layout.cell_width = 32;
    out[2].name = "32x8";
    out[2].layout.cell_width = 32;
    out[2].layout.cell_height = 8;
    return out;
}

MaskedReplay replayMaskedFrame(const MocFrame& frame, std::span<const ReplayLayout> layouts,
                               uint64_t seed) {
    MaskedReplay replay;
    replay.width = frame.width;
    replay.height = frame.height;
    replay.triangles = frame.triangles();
    const double near = frame.near_clip;

    // Into OpenGL's clip convention for the exact raster: z = w - 2 near puts its near clip
    // plane (z >= -w) at w = near, the recorded near plane, and its far plane nowhere (MOC's
    // depth runs to infinity). masked reads x, y and w only.
    std::vector<std::vector<glm::dvec4>> clip(frame.occluders.size());
    for (size_t b = 0; b < frame.occluders.size(); ++b) {
        for (const glm::dvec4& v : frame.occluders[b].clip) {
            clip[b].push_back({v.x, v.y, v.w - 2.0 * near, v.w});
        }
    }
    replay.exact.assign(static_cast<size_t>(frame.width) * frame.height, 0.0);
    for (size_t b = 0; b < frame.occluders.size(); ++b) {
        const std::vector<uint32_t>& idx = frame.occluders[b].indices;
        for (size_t t = 0; t + 2 < idx.size(); t += 3) {
            rasteriseExactTriangle(clip[b][idx[t]], clip[b][idx[t + 1]], clip[b][idx[t + 2]],
                                   frame.width, frame.height, [&](size_t p, double iw) {
                                       replay.exact[p] = std::max(replay.exact[p], iw);
                                   });
        }
    }

    std::vector<double> object_depths;
    const std::vector<std::pair<std::string, std::vector<Rect>>> sets = {
        {"8x4 blocks", blocks(frame.width, frame.height, 8, 4)},
        {"32x32 blocks", blocks(frame.width, frame.height, 32, 32)},
        {"objects", objectRects(replay.exact, frame.width, frame.height, seed, object_depths)}};
    // Per rectangle, the exact buffer's farthest 1/w over it (0: a pixel is uncovered): it does
    // not depend on the layout.
    std::vector<std::vector<double>> far_of(sets.size());
    for (size_t s = 0; s < sets.size(); ++s) {
        for (const Rect& r : sets[s].second) {
            far_of[s].push_back(farthest(replay.exact, frame.width, r));
        }
    }
    const size_t objects = 2;  // the set tested at sampled depths
    // Triangles meeting at an edge share it by index once welded by position: no coverage
    // margin along it (masked_depth_buffer.h).
    std::vector<std::vector<uint32_t>> welded(frame.occluders.size());
    std::vector<std::vector<uint32_t>> neighbours(frame.occluders.size());
    for (size_t b = 0; b < frame.occluders.size(); ++b) {
        welded[b] = weldedIndices(clip[b], frame.occluders[b].indices);
        neighbours[b] = edgeNeighbours(welded[b]);
    }

    for (const ReplayLayout& l : layouts) {
        MaskedDepthBuffer buffer(MaskedKernel::Avx2, l.layout);
        const auto start = std::chrono::steady_clock::now();
        buffer.beginClipFrame(frame.width, frame.height, near, 0);
        for (size_t b = 0; b < frame.occluders.size(); ++b) {
            buffer.rasteriseClipMesh(clip[b], welded[b], neighbours[b]);
        }
        LayoutReplay out;
        out.layout = l.name;
        out.raster_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        out.missed_blocks.assign(sets[0].second.size(), 0);
        for (size_t s = 0; s < sets.size(); ++s) {
            ReplaySet set;
            set.name = sets[s].first;
            for (size_t i = 0; i < sets[s].second.size(); ++i) {
                const Rect& r = sets[s].second[i];
                const double area = static_cast<double>(r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1);
                auto hidden = [&](double inv_w) {
                    return !buffer.testRect(r.x0, r.x1 + 1.0, r.y0, r.y1 + 1.0, 1.0 / inv_w);
                };
                const double d = far_of[s][i];
                if (s == objects) {
                    // At its sampled depth: hidden in the exact buffer when every pixel centre
                    // holds an occluder nearer than it.
                    const double at = object_depths[i];
                    const bool exact_hides = d > 0.0 && d > at;
                    const bool masked_hides = hidden(at);
                    ++set.tally.tests;
                    if (exact_hides) {
                        ++set.tally.exact_hidden;
                        set.tally.exact_hidden_area += area;
                        if (masked_hides) {
                            ++set.tally.both_hidden;
                            set.tally.both_hidden_area += area;
                        }
                    } else {
                        set.tally.wrongly_hidden += masked_hides ? 1 : 0;
                    }
                    continue;
                }
                if (d <= 0.0) {
                    // An uncovered pixel: seen at any depth. Tested at the far end of the view.
                    ++set.tally.tests;
                    set.tally.wrongly_hidden += hidden(1e-9) ? 1 : 0;
                    continue;
                }
                set.tally.tests += 2;
                ++set.tally.exact_hidden;
                set.tally.exact_hidden_area += area;
                if (hidden(d * kBehind)) {
                    ++set.tally.both_hidden;
                    set.tally.both_hidden_area += area;
                } else if (s == 0) {
                    out.missed_blocks[i] = 1;
                }
                set.tally.wrongly_hidden += hidden(d * kInFront) ? 1 : 0;
            }
            addTally(out.total, set.tally);
            out.sets.push_back(std::move(set));
        }
        out.bounds.resize(static_cast<size_t>(frame.width) * frame.height);
        for (uint32_t y = 0; y < frame.height; ++y) {
            for (uint32_t x = 0; x < frame.width; ++x) {
                out.bounds[static_cast<size_t>(y) * frame.width + x] =
                    buffer.pixelBound(x / buffer.pixelSize(), y / buffer.pixelSize());
            }
        }
        replay.layouts.push_back(std::move(out));
    }
    return replay;
}

std::vector<uint8_t> replayDepthPicture(const MaskedReplay& replay, double near_w,
                                        uint32_t* picture_width, uint32_t* picture_height) {
    const uint32_t half_w = std::max<uint32_t>(replay.width / 2, 1);
    const uint32_t half_h = std::max<uint32_t>(replay.height / 2, 1);
    *picture_width = 2 * half_w;
    *picture_height = half_h;
    std::vector<uint8_t> rgba(static_cast<size_t>(*picture_width) * half_h * 4, 0);
    // The farthest depth either buffer holds sets the scale.
    double far_w = near_w * 2.0;
    for (const double iw : replay.exact) {
        if (iw > 0.0) far_w = std::max(far_w, 1.0 / iw);
    }
    const double span = std::log(far_w / near_w);
    auto grey = [&](double iw) -> uint8_t {
        if (!(iw > 0.0)) return 0;
        const double t = std::clamp(std::log(1.0 / (iw * near_w)) / span, 0.0, 1.0);
        return static_cast<uint8_t>(std::lround(40.0 + 215.0 * (1.0 - t)));
    };
    for (uint32_t y = 0; y < half_h; ++y) {
        for (uint32_t x = 0; x < half_w; ++x) {
            // The nearer of the four pixels halved into one (what hides most there).
            double exact = 0.0, masked = 0.0;
            for (uint32_t dy = 0; dy < 2; ++dy) {
                for (uint32_t dx = 0; dx < 2; ++dx) {
                    const uint32_t sx = std::min(2 * x + dx, replay.width - 1);
                    const uint32_t sy = std::min(2 * y + dy, replay.height - 1);
                    const size_t p = static_cast<size_t>(sy) * replay.width + sx;
                    exact = std::max(exact, replay.exact[p]);
                    if (!replay.layouts.empty()) {
                        masked = std::max(masked, double(replay.layouts[0].bounds[p]));
                    }
                }
            }
            const uint32_t blocks_across = (replay.width + 7) / 8;
            const bool missed =
                !replay.layouts.empty() &&
                replay.layouts[0].missed_blocks[(2 * y / 4) * blocks_across + 2 * x / 8] != 0;
            for (int side = 0; side < 2; ++side) {
                const uint8_t g = grey(side == 0 ? exact : masked);
                uint8_t* px =
                    &rgba[(static_cast<size_t>(y) * *picture_width + side * half_w + x) * 4];
                px[0] = side == 1 && missed ? 255 : g;
                px[1] = px[2] = side == 1 && missed ? 0 : g;
                px[3] = 255;
            }
        }
    }
    return rgba;
}

}  // namespace occsim
