// How a culled frame differs from ground truth at each pixel, from the object IDs and the depth
// of both renders (docs/error.md). Both renders use the same depth buffer, matrices and state,
// and a drawn object's fragments are the same in both, so a pixel can differ in two ways only:
// - an error: ground truth shows a surface nearer than what the culled frame shows there
//   (background counts as infinitely far), because the culler left that surface out;
// - a tie: another object at the same depth, within kDepthTieSteps, won the depth test because
//   the two renders drew in another order. The image is the same surface; it is no error.
// A third kind is ground truth's own: a stray fragment (sim/run/stray_fragments.h), nearer than
// any point of its object, which no query on the object's bounds can see. Where the culled
// frame differs only because it lacks such a fragment, the pixel is stray, not an error.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace occsim {

// The tolerance, in steps of the depth format (one step: from one representable depth value to
// the next; see GlRenderer::readDepthRanks). Derivation in docs/error.md: invariance makes a
// drawn object's stored depth identical in both renders (0 steps); one step more is the
// resolution of the buffer itself, below which the depth test cannot order two surfaces either.
inline constexpr uint32_t kDepthTieSteps = 1;

enum class PixelDifference : uint8_t { Same = 0, Tie = 1, Error = 2, Stray = 3 };

// IDs are object index + 1 (0: background); ranks as GlRenderer::readDepthRanks gives them
// (nearer is larger). Any other difference than a tie is an error, including the culled frame
// showing something nearer than ground truth, which no subset of the same fragments can do.
PixelDifference classifyPixel(uint32_t truth_id, uint32_t truth_rank, uint32_t culled_id,
                              uint32_t culled_rank);

struct PixelCounts {
    int64_t error = 0;
    int64_t tie = 0;
    int64_t stray = 0;
};

// Over a frame (all spans the same size; truth_stray may be empty: no stray fragments). With
// `marks`, also each pixel's PixelDifference.
PixelCounts comparePixels(std::span<const uint32_t> truth_ids,
                          std::span<const uint32_t> truth_ranks,
                          std::span<const uint32_t> culled_ids,
                          std::span<const uint32_t> culled_ranks,
                          std::span<const uint8_t> truth_stray = {},
                          std::vector<uint8_t>* marks = nullptr);

// One object's pixels in a frame.
struct ObjectPixels {
    uint32_t truth = 0;  // ground truth shows it there (stray fragments left out)
    uint32_t error = 0;  // error pixels it accounts for
    uint32_t tie = 0;    // tie pixels where ground truth shows it
};

// The frame's pixels per object, from comparePixels()'s marks: an error or tie pixel belongs to
// the object ground truth shows there (what the culled frame lacks), an error pixel where ground
// truth shows background to the object the culled frame shows (something nearer than ground
// truth, which no subset of the same fragments can be). per_object is resized to `objects`
// (IDs past it are ignored); the sum of `error` over objects is the frame's error count.
void attributePixels(std::span<const uint32_t> truth_ids, std::span<const uint8_t> truth_stray,
                     std::span<const uint32_t> culled_ids, std::span<const uint8_t> marks,
                     uint32_t objects, std::vector<ObjectPixels>& per_object);

}  // namespace occsim
