// The cost model (occsim/culling/contract/cost_model.h): plain data, unknown when all zero, valid
// when every figure is finite and >= 0.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "occsim/culling/contract/cost_model.h"

namespace occsim {
namespace {

TEST(CostModel, AllZeroIsValidAndUnknown) {
    const CostModel none;
    std::string error = "untouched";
    EXPECT_TRUE(none.isValid(&error));
    EXPECT_EQ(error, "untouched") << "no message for a valid model";
    EXPECT_FALSE(none.known());
}

TEST(CostModel, DrawingCostsTheCallPlusEachTriangle) {
    const CostModel m{0.01, 0.002, 0.5};
    EXPECT_TRUE(m.known());
    EXPECT_DOUBLE_EQ(m.drawMs(0), 0.5);
    EXPECT_DOUBLE_EQ(m.drawMs(100), 0.5 + 100 * 0.002);
}

TEST(CostModel, ANegativeOrNonFiniteFigureIsInvalidWithOneMessage) {
    const double bad[] = {-1e-9, std::numeric_limits<double>::infinity(),
                          std::numeric_limits<double>::quiet_NaN()};
    for (double v : bad) {
        for (int field = 0; field < 3; ++field) {
            CostModel m;
            (field == 0 ? m.query_box_ms : field == 1 ? m.triangle_ms : m.draw_call_ms) = v;
            std::string error;
            EXPECT_FALSE(m.isValid(&error)) << field << " " << v;
            EXPECT_EQ(error,
                      "query_box_ms, triangle_ms and draw_call_ms must be finite numbers >= 0 "
                      "(milliseconds)");
            EXPECT_FALSE(m.isValid(nullptr)) << "no message asked for";
        }
    }
}

}  // namespace
}  // namespace occsim
