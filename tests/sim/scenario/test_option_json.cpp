// Option values in JSON (option_json.h): written in their JSON types, read back as written, and a
// wrong type or range refused at its pointer.
#include <gtest/gtest.h>

#include <string>

#include "scenario_fixtures.h"
#include "sim/scenario/option_json.h"

namespace occsim {
namespace {

using namespace fixtures;

TEST(OptionJson, WritesEachOptionInItsJsonTypeInDescriptorOrder) {
    const nlohmann::ordered_json j = optionValuesJson(OptionValues(findCuller("chc++")->options));
    EXPECT_EQ(j.dump(), R"({"visible_frames_skip":2,"batch_size":50,"multiqueries":true,)"
                        R"("tight_bounds_depth":2,"seed":1})");
    EXPECT_TRUE(j["seed"].is_number_integer());
    EXPECT_EQ(optionValuesJson(OptionValues()).dump(), "{}");
}

TEST(OptionJson, ANegativeIntegerIsWrittenAsItself) {
    const OptionsDescriptor d = {integerOption("offset", "", -10, 10, -3, "may be negative")};
    EXPECT_EQ(optionValuesJson(OptionValues(d)).dump(), R"({"offset":-3})");
}

TEST(OptionJson, EveryCullersValuesReadBackAsWritten) {
    for (const CullerRow* culler : cullerRows()) {
        const OptionValues written(culler->options);
        const Json j(optionValuesJson(written));
        OptionValues read(culler->options);
        for (const OptionSpec& spec : culler->options) {
            read.set(
                spec.key,
                readOptionValue(JsonValueReader(j.at(spec.key), "/" + spec.key, "t.json"), spec));
        }
        EXPECT_TRUE(read == written) << culler->name;
    }
}

TEST(OptionJson, AValueOfTheWrongTypeOrRangeFailsAtItsPointer) {
    const OptionSpec spec = integerOption("n", "frames", 1, 8, 1, "a count");
    const Json text = "4";
    const Json big = 9;
    try {
        readOptionValue(JsonValueReader(text, "/culling/x/n", "t.json"), spec);
        FAIL() << "a string was read as an integer";
    } catch (const ScenarioError& e) {
        EXPECT_STREQ(e.what(),
                     "t.json: /culling/x/n: expected an integer in [1, 8] (frames), "
                     "got \"4\" (string)");
    }
    try {
        readOptionValue(JsonValueReader(big, "/culling/x/n", "t.json"), spec);
        FAIL() << "9 was read in [1, 8]";
    } catch (const ScenarioError& e) {
        EXPECT_STREQ(e.what(),
                     "t.json: /culling/x/n: expected an integer in [1, 8] (frames), got 9");
    }
}

}  // namespace
}  // namespace occsim
