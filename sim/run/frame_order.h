// The order in which a frame renders its configurations. A configuration pays for what the one
// before it left behind in the same frame (on llvmpipe the one after vfc's heavy frame was 2.5 to
// 3 times slower than itself elsewhere in --algos): with a fixed order the same configuration
// pays every frame, and the table depends on how --algos was typed.
//
//   balanced  (the default) frame f takes row f of a Williams design: over every n frames (2n
//             when n is odd) each configuration renders right after each other one equally
//             often, and takes every place equally often
//   rotated   frame f renders configuration (f + k) mod n as its k-th: every place equally
//             often, but each configuration always after the same one (the tuner's order)
//   fixed     the order of --algos every frame (biased: kept to reproduce older tables)
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace occsim {

enum class FrameOrder { balanced, rotated, fixed };

// The configuration frame `frame` renders `k`-th of `n` (k < n).
size_t configurationAt(FrameOrder order, size_t n, uint64_t frame, size_t k);

// The frames after which a balanced order has given every ordered pair its share: n for even n,
// 2n for odd n (1 for n = 1).
size_t balancedPeriod(size_t n);

std::string_view frameOrderName(FrameOrder order);
std::optional<FrameOrder> parseFrameOrder(std::string_view name);

}  // namespace occsim
