// One kind of bad input (occsim/culling/contract/input_error.h): every error that bad input causes,
// in whichever module finds it, is an occsim::InputError, the one type occsim and occtune catch for
// exit code 2. A bad-input type that forgets the base fails here (and would end with exit code 1);
// the errors that are no bad input (a failure while running, a run to try again later) stay apart.
#include <gtest/gtest.h>

#include <type_traits>

#include "occsim/culling/contract/input_error.h"
#include "occsim/culling/registry/plugin_loader.h"
#include "occsim/culling/registry/registry.h"
#include "render/glfw_context.h"
#include "render/headless_context.h"
#include "sim/output/run_folder.h"
#include "sim/regress/regress.h"
#include "sim/regress/result_files.h"
#include "sim/scenario/errors.h"
#include "sim/view/view_script.h"
#include "sim/world/world.h"
#include "tune/errors.h"

namespace occsim {
namespace {

template <class E>
constexpr bool isBadInput = std::is_base_of_v<InputError, E>;

TEST(InputError, EveryBadInputErrorIsAnInputError) {
    EXPECT_TRUE(isBadInput<PluginError>) << "a plugin that cannot be loaded";
    EXPECT_TRUE(isBadInput<RegistryError>) << "a culler row refused, a factory that throws";
    EXPECT_TRUE(isBadInput<ScenarioError>) << "a scenario or --culling file";
    EXPECT_TRUE(isBadInput<GltfError>) << "a glTF file";
    EXPECT_TRUE(isBadInput<MocrecError>) << "a recorded MOC frame (masked-replay)";
    EXPECT_TRUE(isBadInput<BackendUnavailable>) << "--backend, --device";
    EXPECT_TRUE(isBadInput<WindowUnavailable>) << "no window for occsim view";
    EXPECT_TRUE(isBadInput<ScriptError>) << "a view script";
    EXPECT_TRUE(isBadInput<RunFolderError>) << "an --out that is not an occsim run";
    EXPECT_TRUE(isBadInput<ResultFileError>) << "a shard result, a history entry";
    EXPECT_TRUE(isBadInput<BaselineError>) << "a baseline file";
    EXPECT_TRUE(isBadInput<tune::TuneInputError>) << "occtune's flags and sample log";
}

TEST(InputError, FailuresWhileRunningAreNoBadInput) {
    EXPECT_FALSE(isBadInput<MotionError>) << "a motion that left finite coordinates: exit 1";
    EXPECT_FALSE(isBadInput<RunFolderBusy>) << "another run holds --out: try again, exit 1";
    EXPECT_FALSE(isBadInput<tune::Interrupted>) << "Ctrl-C: exit 130";
}

TEST(InputError, GivenByNamesTheFlagBeforeTheMessage) {
    const PluginError error("x.so: no such file");
    EXPECT_STREQ(givenBy("--plugin", error).what(), "--plugin x.so: no such file");
}

}  // namespace
}  // namespace occsim
