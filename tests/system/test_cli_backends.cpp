// The backend, device and context as occsim meets them: one that cannot serve is one line, exit 2;
// without EGL, auto falls back to OSMesa and says why; the software device listed with its strings;
// the backend, device and driver recorded in every output.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"

using namespace occsim::cli_run;

namespace {

// The headless backend and device: a choice that cannot be served is bad input, one line naming
// what is missing and what was found, and nothing is written.
TEST(Cli, ABackendOrDeviceThatCannotServeIsOneLineWithExitCode2) {
    const auto out = tempPath("bad-backend");
    const struct {
        std::string args, must_contain;
    } cases[] = {
        {"bench " + kSmall + " --backend vulkan",
         "--backend: expected auto, egl or osmesa, got 'vulkan'"},
        {"bench " + kSmall + " --device 64", "--device 64: out of range, EGL lists "},
        {"run " + kSmall + " --backend egl --device 9", "--device 9: out of range"},
        {"run " + kSmall + " --device -1", "--device: expected an integer in [0, 1023], got '-1'"},
        {"run " + kSmall + " --backend osmesa --device 0",
         "--device 0: only the EGL backend has devices"},
        {"regress " + kSmall + " --device 5", "--device 5: out of range"},
        {"regress " + kSmall + " --backend gl",
         "--backend: expected auto, egl or osmesa, got 'gl'"},
    };
    for (const auto& c : cases) {
        const Outcome o = runOccsim(c.args + " --out " + out.string());
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << c.args << ": " << o.output;
        EXPECT_NE(o.output.find(c.must_contain), std::string::npos) << c.args << ": " << o.output;
        EXPECT_FALSE(std::filesystem::exists(out / "summary.json")) << c.args;
    }
}

// Without EGL (here: glvnd told to load no vendor library), `auto` falls back to OSMesa where the
// build has it and says so everywhere; `egl` is bad input; without OSMesa `auto` is bad input too.
TEST(Cli, WithoutEglAutoFallsBackToOsmesaAndSaysWhyAndEglIsBadInput) {
    const std::string no_egl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json ";
    const auto out = tempPath("no-egl");
    const Outcome egl = shell(no_egl + OCCSIM_EXE + " run " + kSmall +
                              " --algo vfc --frames 2 --backend egl --out " + out.string());
    EXPECT_EQ(egl.exit_code, 2) << egl.output;
    EXPECT_EQ(lineCount(egl.output), 1u) << egl.output;
    EXPECT_NE(egl.output.find("--backend egl: EGL: EGL lacks EGL_EXT_device_enumeration"),
              std::string::npos)
        << egl.output;
    const Outcome fallback = shell(no_egl + OCCSIM_EXE + " run " + kSmall +
                                   " --algo vfc --frames 2 --out " + out.string());
    if (!OCCSIM_HAVE_OSMESA) {
        EXPECT_EQ(fallback.exit_code, 2) << fallback.output;
        EXPECT_NE(fallback.output.find("and this build has no OSMesa"), std::string::npos)
            << fallback.output;
        return;
    }
    ASSERT_EQ(fallback.exit_code, 0) << fallback.output;
    EXPECT_NE(fallback.output.find("backend: OSMesa"), std::string::npos) << fallback.output;
    EXPECT_NE(fallback.output.find("backend auto fell back to OSMesa: EGL: EGL lacks"),
              std::string::npos)
        << fallback.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    EXPECT_NE(json.find("\"backend\": \"osmesa\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"backend_fallback\": \"EGL: EGL lacks"), std::string::npos) << json;
}

// A device whose OpenGL is too old (Mesa told to offer 4.3, or to hide the timer queries, which
// takes it below 3.3) is bad input naming what was asked for and what was found.
TEST(Cli, AContextBelowOpenGl45IsOneLineNamingWhatWasFound) {
    const auto out = tempPath("old-gl");
    for (const std::string& env : {std::string("MESA_GL_VERSION_OVERRIDE=4.3"),
                                   std::string("MESA_EXTENSION_OVERRIDE=-GL_ARB_timer_query")}) {
        const Outcome o = shell(env + " " + OCCSIM_EXE + " run " + kSmall +
                                " --algo vfc --frames 2 --backend egl --out " + out.string());
        EXPECT_EQ(o.exit_code, 2) << env << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << env << ": " << o.output;
        EXPECT_NE(o.output.find("EGL device 0: cannot create an OpenGL 4.5 core context"),
                  std::string::npos)
            << o.output;
        EXPECT_NE(o.output.find("found OpenGL \""), std::string::npos) << o.output;
        EXPECT_FALSE(std::filesystem::exists(out / "summary.json"));
    }
}

TEST(Cli, DevicesListsTheSoftwareDeviceWithVendorRendererAndDriver) {
    const Outcome o = runOccsim("devices");
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("EGL devices: "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("(software): vendor Mesa"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("renderer llvmpipe"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("driver Mesa "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("gpu ms not meaningful"), std::string::npos) << o.output;
}

// Where a run rendered is in its console header, summary.json and report.md.
TEST(Cli, TheBackendDeviceAndDriverAreRecordedEverywhere) {
    const auto out = tempPath("backend");
    const Outcome o = runOccsim(
        "run " + kSmall + " --algo vfc --frames 2 --backend egl --device 0 --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("backend: EGL device 0, vendor Mesa"), std::string::npos) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    for (const char* part :
         {"\"backend\": \"egl\"", "\"device\": 0", "\"gl_renderer\": \"llvmpipe",
          "\"driver\": \"Mesa ", "\"gl_vendor\"", "\"gpu_time_meaningful\": false"}) {
        EXPECT_NE(json.find(part), std::string::npos) << part << " in " << json;
    }
    std::ifstream report(out / "report.md");
    const std::string md{std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>()};
    EXPECT_NE(md.find("| backend | EGL device 0: vendor Mesa"), std::string::npos) << md;
}

}  // namespace
