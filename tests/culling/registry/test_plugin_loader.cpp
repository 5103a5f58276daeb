// The plugin loader (occsim/culling/registry/plugin_loader.h) on each kind of plugin file, built
// from tests/plugins/test_plugin.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "occsim/culling/registry/plugin_loader.h"
#include "occsim/culling/registry/registry.h"
#include "plugin_files.h"

namespace occsim {
namespace {

using testing::lineCount;
using testing::pluginFile;
using testing::tempDir;

namespace fs = std::filesystem;

std::string loadError(const fs::path& file, CullerRegistry& registry) {
    try {
        loadPlugin(file, registry);
    } catch (const PluginError& e) {
        return e.what();
    }
    return "";
}

TEST(PluginLoader, AGoodPluginRegistersItsCullersOnceWithItsFileAsTheSource) {
    CullerRegistry registry;
    const std::vector<std::string> names = loadPlugin(pluginFile("good"), registry);
    ASSERT_EQ(names, std::vector<std::string>{"test-frustum"});
    const CullerRow* a = registry.find("test-frustum");
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->source, pluginFile("good").string());
    EXPECT_TRUE(a->conservative);
    ASSERT_EQ(a->options.size(), 2u);
    EXPECT_EQ(a->options[1].key, "margin");
    EXPECT_TRUE(a->options[1].tunable);
    EXPECT_TRUE(loadPlugin(pluginFile("good"), registry).empty())
        << "a file already loaded is not loaded again";
    EXPECT_EQ(registry.all().size(), 1u);
}

TEST(PluginLoader, EachBadFileIsOneLineNamingTheFileAndWhatWasExpected) {
    const fs::path dir = tempDir("bad");
    const fs::path text_file = dir / "libnotes.so";
    std::ofstream(text_file) << "not a shared object\n";
    const struct {
        fs::path file;
        std::string expected;
    } cases[] = {
        {dir / "libmissing.so", "no such file; expected a plugin culler"},
        {text_file, "not a loadable shared object"},
        {pluginFile("no_entry"), "no entry point 'occsim_plugin'"},
        {pluginFile("other_abi"), "built for plugin ABI version 9; this occsim loads version 8"},
        {pluginFile("taken_name"),
         "culler 'chc': the name is already taken (by a built-in culler)"},
        {pluginFile("bad_descriptor"),
         "invalid options descriptor: option 0 ('budget'): the range must be ordered"},
        {pluginFile("throwing"), "its factory threw: no GPU budget configured"},
    };
    for (const auto& c : cases) {
        CullerRegistry registry;
        registry.add(*findCuller("chc"));  // the name a plugin must not take
        const std::string why = loadError(c.file, registry);
        EXPECT_EQ(why.rfind(c.file.string() + ": ", 0), 0u) << why;
        EXPECT_NE(why.find(c.expected), std::string::npos) << why;
        EXPECT_EQ(why.find('\n'), std::string::npos) << why;
        EXPECT_EQ(registry.all().size(), 1u) << "a refused plugin registers nothing: " << c.file;
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace occsim
