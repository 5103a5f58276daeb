// The gnuplot charts (sim/output/plots.h): written whole or not at all, and a word when gnuplot
// is not on PATH.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "sample_runs.h"
#include "sim/output/plots.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using testing::sampleRuns;

fs::path freshDir(const std::string& name) {
    const fs::path p = fs::temp_directory_path() /
                       ("occsim-report-outputs-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    return p;
}

// Sets PATH for the scope of a test and puts the old value back.
class ScopedPath {
  public:
    explicit ScopedPath(const std::string& value) {
        if (const char* old = std::getenv("PATH")) old_ = old;
        ::setenv("PATH", value.c_str(), 1);
    }
    ~ScopedPath() {
        if (old_)
            ::setenv("PATH", old_->c_str(), 1);
        else
            ::unsetenv("PATH");
    }
    ScopedPath(const ScopedPath&) = delete;
    ScopedPath& operator=(const ScopedPath&) = delete;

  private:
    std::optional<std::string> old_;
};

void writeExecutable(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
    ::chmod(path.c_str(), 0755);
}

std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> out;
    if (!fs::exists(dir)) return out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

TEST(Plots, WithoutGnuplotOnPathSaysSoAndWritesNothing) {
    const fs::path empty_bin = freshDir("empty-bin");
    fs::create_directories(empty_bin);
    const fs::path out = freshDir("no-gnuplot");
    PlotResult r;
    {
        ScopedPath path(empty_bin.string());
        r = writePlots(sampleRuns(), out);
    }
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.message,
              "plots skipped: gnuplot not found; install the Debian package gnuplot-nox");
    EXPECT_TRUE(r.files.empty());
    EXPECT_FALSE(fs::exists(out)) << "nothing written, not even the folder";
}

TEST(Plots, AFailingGnuplotLeavesNoPictureNotEvenAHalfWrittenOne) {
    const fs::path bin = freshDir("failing-bin");
    fs::create_directories(bin);
    // Writes a partial file under every temporary name the script asks for, then fails.
    writeExecutable(bin / "gnuplot",
                    "#!/bin/sh\n"
                    "for f in $(grep -o '\\.plot-[a-z-]*\\.[a-z]*\\.tmp-[0-9]*' \"$1\"); do\n"
                    "  printf partial > \"$f\"\n"
                    "done\n"
                    "echo '\"plots.gp\" line 9: something broke' >&2\n"
                    "exit 1\n");
    const fs::path out = freshDir("failing");
    PlotResult r;
    {
        ScopedPath path(bin.string() + ":/usr/bin:/bin");
        r = writePlots(sampleRuns(), out);
    }
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.message.find("plots failed"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("something broke"), std::string::npos) << r.message;
    EXPECT_TRUE(r.files.empty());
    for (const std::string& f : filesIn(out)) {
        EXPECT_TRUE(f.ends_with(".dat") || f == "plots.gp") << "left behind: " << f;
    }
}

TEST(Plots, WithGnuplotWritesNonEmptyPngAndSvgOfEveryChart) {
    if (!findOnPath("gnuplot"))
        GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
    const fs::path out = freshDir("real");
    const PlotResult r = writePlots(sampleRuns(), out);
    ASSERT_TRUE(r.ok) << r.message;
    const std::vector<std::string> want = {
        "plot-frame-time.png",    "plot-frame-time.svg",        "plot-time-vs-error.png",
        "plot-time-vs-error.svg", "plot-queries-triangles.png", "plot-queries-triangles.svg"};
    EXPECT_EQ(r.files, want);
    for (const std::string& f : want) {
        ASSERT_TRUE(fs::exists(out / f)) << f;
        EXPECT_GT(fs::file_size(out / f), 1000u) << f;
        std::ifstream in(out / f, std::ios::binary);
        std::string head(8, '\0');
        in.read(head.data(), 8);
        if (f.ends_with(".png"))
            EXPECT_EQ(head.substr(1, 3), "PNG") << f;
        else
            EXPECT_TRUE(head.starts_with("<?xml") || head.starts_with("<svg")) << f;
    }
    for (const std::string& f : filesIn(out)) EXPECT_EQ(f.find(".tmp-"), std::string::npos) << f;
}

}  // namespace
}  // namespace occsim
