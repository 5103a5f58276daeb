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

}  // namespace occsim
