// A picture of a frame that went wrong: the culled frame, ground truth, and the differences
// marked (errors apart from ties), side by side, for a person to look at when a regression fails.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/run/simulation.h"

namespace occsim {

// Error pixels in magenta; tie pixels (another object at the same depth: no error) in yellow;
// stray pixels (a fragment of ground truth's nearer than its object: no error) in cyan.
inline constexpr uint8_t kErrorColour[3] = {255, 0, 255};
inline constexpr uint8_t kTieColour[3] = {255, 210, 0};
inline constexpr uint8_t kStrayColour[3] = {0, 220, 255};
// The ring around a cluster of error pixels and the label of a missed object, in the labelled
// picture: green on a black edge, seen on any background.
inline constexpr uint8_t kRingColour[3] = {0, 255, 0};

// A connected cluster of error pixels (8-connected), in frame pixels, rows bottom-up as the
// frame's: its bounds (inclusive) and size.
struct PixelCluster {
    uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    uint32_t pixels = 0;
};
// Every cluster of PixelDifference::Error pixels, largest first.
std::vector<PixelCluster> errorClusters(const std::vector<uint8_t>& differences, uint32_t width,
                                        uint32_t height);

// An object ground truth shows where the culled frame is in error: missed (or left out behind
// another), with its error pixels and their bounds, most pixels first.
struct MissedInFrame {
    uint32_t object = 0;  // index (ground truth's ID - 1)
    PixelCluster where;   // its error pixels' bounds and count
};
std::vector<MissedInFrame> missedObjects(const ErrorFrame& frame, uint32_t width, uint32_t height);

// RGBA8, (3 * width) x height, rows bottom-up (encode with encodePngBottomUp): culled | ground
// truth | ground truth dimmed with every error pixel in magenta, every tie pixel in yellow, every
// stray one in cyan.
std::vector<uint8_t> composeErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height);

// How many picture pixels per frame pixel: a whole factor that brings a panel to about 800
// pixels wide (a 200 x 150 frame: 4), so that a single error pixel is a square one can see; 1 to
// 8.
uint32_t errorPictureScale(uint32_t frame_width);

// The worst-frame picture report.md shows: the three panels of composeErrorPicture() one above
// the other, each scaled up by errorPictureScale() and under its label (the culled frame with the
// algorithm and frame, ground truth, the difference with its counts and colours). On the culled
// frame and the difference every cluster of error pixels is ringed (a box a few picture pixels
// outside it, however small the cluster or the scale), and each object ground truth shows there
// is labelled near its error pixels ("#123", or "#123 name" with `object_names`), the 24 with the
// most error pixels by name and the count of the rest in the difference's label.
struct LabelledPicture {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;  // RGBA8, rows bottom-up (encodePngBottomUp)
};
LabelledPicture labelledErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height,
                                     const std::string& algorithm,
                                     const std::vector<std::string>* object_names = nullptr);

}  // namespace occsim
