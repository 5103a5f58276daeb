// What each executable links, as the project promises (docs/architecture.md, docs/performance.md):
// the headless commands never load GLFW (only `occsim view` opens it, with dlopen, at run time),
// only the tuner links Ceres, and no executable links a windowing GL library (libGL, GLX, EGL):
// the window takes its GL entry points from GLFW, and the EGL backend opens libEGL with dlopen, so
// an occsim built with OSMesa starts (and falls back to it) where EGL is missing. OSMesa is
// linked exactly when the build has it (OCCSIM_WITH_OSMESA). Checked with ldd, which lists the
// libraries the loader would map at start-up, direct and indirect; Ceres also by its symbols (the
// Debian package's CMake configuration links libceres.a, so occtune carries Ceres inside and ldd
// names only its dependencies, glog and SuiteSparse); and once at run time, with the loader's own
// log (LD_DEBUG=files), that a headless bench loads EGL (the default backend) and no GLFW.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "shell_command.h"

namespace {

using occsim::testing::Outcome;
using occsim::testing::shell;

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

// The library names ldd lists for an executable ("libOSMesa.so.8", ...), lower-cased.
std::vector<std::string> linkedLibraries(const std::string& executable) {
    const Outcome o = shell("ldd '" + executable + "'");
    EXPECT_EQ(o.exit_code, 0) << o.output;
    std::vector<std::string> names;
    std::istringstream lines(o.output);
    std::string line;
    while (std::getline(lines, line)) {
        std::istringstream words(line);
        std::string first;
        if (words >> first)
            names.push_back(lower(std::filesystem::path(first).filename().string()));
    }
    return names;
}

// The number of Ceres functions defined in the executable itself (a static link).
int ceresSymbols(const std::string& executable) {
    const Outcome o = shell("nm -C --defined-only '" + executable + "' | grep -c 'ceres::'");
    return std::atoi(o.output.c_str());
}

bool anyStartsWith(const std::vector<std::string>& names, const std::string& prefix) {
    return std::any_of(names.begin(), names.end(),
                       [&](const std::string& n) { return n.rfind(prefix, 0) == 0; });
}

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += n + " ";
    return s;
}

const std::string kOccsim = OCCSIM_EXE;
const std::string kOcctune = OCCTUNE_EXE;
// The windowing GL libraries no executable links (EGL is opened at run time).
const std::array<const char*, 4> kWindowingGl = {"libgl.so", "libglx", "libegl", "libglfw"};

TEST(LinkedLibraries, OccsimLinksOsmesaOnlyWhenBuiltWithItAndNeitherGlfwNorCeres) {
    const std::vector<std::string> libs = linkedLibraries(kOccsim);
    ASSERT_TRUE(anyStartsWith(libs, "libc.so")) << "ldd listed nothing: " << joined(libs);
    EXPECT_EQ(anyStartsWith(libs, "libosmesa"), OCCSIM_HAVE_OSMESA != 0) << joined(libs);
    EXPECT_FALSE(anyStartsWith(libs, "libglfw")) << joined(libs);
    EXPECT_FALSE(anyStartsWith(libs, "libceres")) << joined(libs);
    EXPECT_FALSE(anyStartsWith(libs, "libglog")) << "Ceres' logging library: " << joined(libs);
    EXPECT_EQ(ceresSymbols(kOccsim), 0);
}

TEST(LinkedLibraries, OnlyTheTunerLinksCeres) {
    const std::vector<std::string> libs = linkedLibraries(kOcctune);
    ASSERT_TRUE(anyStartsWith(libs, "libc.so")) << "ldd listed nothing: " << joined(libs);
    EXPECT_TRUE(anyStartsWith(libs, "libceres") || ceresSymbols(kOcctune) > 0) << joined(libs);
    EXPECT_FALSE(anyStartsWith(libs, "libglfw")) << joined(libs);
}

TEST(LinkedLibraries, NoExecutableLinksAWindowingGl) {
    for (const std::string& exe : {kOccsim, kOcctune}) {
        const std::vector<std::string> libs = linkedLibraries(exe);
        ASSERT_TRUE(anyStartsWith(libs, "libc.so")) << exe << ": " << joined(libs);
        for (const char* gl : kWindowingGl) {
            EXPECT_FALSE(anyStartsWith(libs, gl)) << exe << " links " << gl << ": " << joined(libs);
        }
    }
}

// At run time, not only at link time: a library opened with dlopen appears in the loader's log
// and nowhere in ldd, so a headless command that opened GLFW would show only here.
TEST(LinkedLibraries, AHeadlessBenchLoadsEglAndNoGlfw) {
    const auto out = std::filesystem::temp_directory_path() /
                     ("occsim-linked-libraries-" + std::to_string(::getpid()));
    std::filesystem::remove_all(out);
    const Outcome o = shell("LD_DEBUG=files '" + kOccsim + "' bench '" + OCCSIM_SOURCE_DIR +
                            "/scenarios/small/teapots-small.json' --frames 2 --algos vfc chc "
                            "--out '" +
                            out.string() + "'");
    std::filesystem::remove_all(out);
    ASSERT_EQ(o.exit_code, 0) << o.output.substr(0, 4000);
    const std::string log = lower(o.output);
    // The log is really there: it names the libraries the loader mapped.
    ASSERT_NE(log.find("file=libc.so"), std::string::npos) << o.output.substr(0, 4000);
    EXPECT_NE(log.find("file=libegl.so.1"), std::string::npos) << "the default backend is EGL";
    EXPECT_EQ(log.find("glfw"), std::string::npos) << "a headless bench loaded GLFW";
}

}  // namespace
