// Frame orders: see frame_order.h.
#include "sim/run/frame_order.h"

namespace occsim {

size_t balancedPeriod(size_t n) { return n <= 1 ? 1 : (n % 2 == 0 ? n : 2 * n); }

size_t configurationAt(FrameOrder order, size_t n, uint64_t frame, size_t k) {
    if (n <= 1) return 0;
    switch (order) {
        case FrameOrder::fixed:
            return k;
        case FrameOrder::rotated:
            return static_cast<size_t>((frame + k) % n);
        case FrameOrder::balanced:
            break;
    }
    // Williams design: the first row is 0, 1, n-1, 2, n-2, 3, ...; row r adds r to every entry
    // (mod n). For even n its n rows hold every ordered pair of neighbours once; for odd n the
    // n rows after them are the same rows reversed, and the 2n hold every pair twice.
    const size_t row = static_cast<size_t>(frame % balancedPeriod(n));
    const size_t shift = row % n;
    const size_t column = row < n ? k : n - 1 - k;
    const size_t base = column == 0 ? 0 : (column % 2 == 1 ? (column + 1) / 2 : n - column / 2);
    return (base + shift) % n;
}

std::string_view frameOrderName(FrameOrder order) {
    switch (order) {
        case FrameOrder::balanced:
            return "balanced";
        case FrameOrder::rotated:
            return "rotated";
        case FrameOrder::fixed:
            return "fixed";
    }
    return "balanced";
}

std::optional<FrameOrder> parseFrameOrder(std::string_view name) {
    for (const FrameOrder o : {FrameOrder::balanced, FrameOrder::rotated, FrameOrder::fixed}) {
        if (name == frameOrderName(o)) return o;
    }
    return std::nullopt;
}

}  // namespace occsim
