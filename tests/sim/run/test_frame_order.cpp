// Frame orders (sim/run/frame_order.h): every order renders each configuration once a frame; the
// balanced one gives every ordered pair of neighbours and every place its equal share over its
// period, for 1 to 9 configurations; the rotated one every place but always the same neighbour.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <utility>
#include <vector>

#include "sim/run/frame_order.h"

namespace occsim {
namespace {

std::vector<size_t> row(FrameOrder order, size_t n, uint64_t frame) {
    std::vector<size_t> r;
    for (size_t k = 0; k < n; ++k) r.push_back(configurationAt(order, n, frame, k));
    return r;
}

TEST(FrameOrder, EveryOrderRendersEachConfigurationOnceAFrame) {
    for (const FrameOrder order : {FrameOrder::balanced, FrameOrder::rotated, FrameOrder::fixed}) {
        for (size_t n = 1; n <= 9; ++n) {
            for (uint64_t f = 0; f < 40; ++f) {
                const std::vector<size_t> r = row(order, n, f);
                EXPECT_EQ(std::set<size_t>(r.begin(), r.end()).size(), n)
                    << frameOrderName(order) << " n " << n << " frame " << f;
            }
        }
    }
}

TEST(FrameOrder, BalancedGivesEveryPairOfNeighboursAndEveryPlaceItsShare) {
    for (size_t n = 2; n <= 9; ++n) {
        const size_t period = balancedPeriod(n);
        EXPECT_EQ(period, n % 2 == 0 ? n : 2 * n);
        std::map<std::pair<size_t, size_t>, int> pairs, places;
        for (uint64_t f = 0; f < period; ++f) {
            const std::vector<size_t> r = row(FrameOrder::balanced, n, f);
            for (size_t k = 0; k < n; ++k) ++places[{r[k], k}];
            for (size_t k = 0; k + 1 < n; ++k) ++pairs[{r[k], r[k + 1]}];
        }
        EXPECT_EQ(pairs.size(), n * (n - 1)) << "n " << n;  // every ordered pair
        for (const auto& [pair, count] : pairs) EXPECT_EQ(count, n % 2 == 0 ? 1 : 2) << "n " << n;
        EXPECT_EQ(places.size(), n * n) << "n " << n;
        for (const auto& [place, count] : places) {
            EXPECT_EQ(count, static_cast<int>(period / n)) << "n " << n;
        }
        EXPECT_EQ(row(FrameOrder::balanced, n, period), row(FrameOrder::balanced, n, 0));
    }
}

// Rotation gives every place but not every neighbour: configuration 1 always follows 0 when
// both render in a frame, so whatever 0 leaves behind, 1 pays.
TEST(FrameOrder, RotatedAndFixedKeepEachConfigurationsNeighbour) {
    for (uint64_t f = 0; f < 6; ++f) {
        const std::vector<size_t> r = row(FrameOrder::rotated, 3, f);
        for (size_t k = 0; k + 1 < 3; ++k) EXPECT_EQ(r[k + 1], (r[k] + 1) % 3);
        EXPECT_EQ(row(FrameOrder::fixed, 3, f), (std::vector<size_t>{0, 1, 2}));
    }
}

TEST(FrameOrder, NamesParseBackAndNothingElseDoes) {
    for (const FrameOrder order : {FrameOrder::balanced, FrameOrder::rotated, FrameOrder::fixed})
        EXPECT_EQ(parseFrameOrder(frameOrderName(order)), order);
    EXPECT_EQ(parseFrameOrder("Balanced"), std::nullopt);
    EXPECT_EQ(parseFrameOrder(""), std::nullopt);
}

}  // namespace
}  // namespace occsim
