// A long run's progress on stderr (sim/run/progress.h): a bar on a terminal, a line every few
// seconds otherwise, nothing when quiet; driven here with given times, never the clock.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "sim/run/progress.h"

namespace occsim {
namespace {

// What a RunProgress wrote, through a memory stream.
class Captured {
  public:
    Captured() : file_(::open_memstream(&buffer_, &size_)) {}
    ~Captured() {
        std::fclose(file_);
        std::free(buffer_);
    }
    std::FILE* file() { return file_; }
    std::string text() {
        std::fflush(file_);
        return std::string(buffer_, size_);
    }

  private:
    char* buffer_ = nullptr;
    size_t size_ = 0;
    std::FILE* file_;
};

TEST(RunProgress, OffATerminalALineEveryIntervalAndNoneForAShortRun) {
    Captured out;
    RunProgress p(ProgressStyle::Lines, "teapots, 8 configurations", 120, 120, out.file(), 10.0);
    p.frameDone(1, 0.4);
    p.frameDone(30, 9.9);
    EXPECT_EQ(out.text(), "") << "nothing before the first interval";
    p.frameDone(50, 10.0);
    EXPECT_EQ(out.text(),
              "progress: frame 50/120, teapots, 8 configurations, 10 s elapsed, about 14 s "
              "left\n");
    p.frameDone(60, 19.0);
    p.frameDone(100, 20.4);
    p.frameDone(120, 24.0);  // the end: the table follows, no line
    p.finish();
    const std::string text = out.text();
    EXPECT_EQ(text.find("progress: frame 60/"), std::string::npos) << text;
    EXPECT_NE(text.find("progress: frame 100/120, teapots, 8 configurations, 20 s elapsed, about "
                        "4 s left\n"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find('\r'), std::string::npos) << "no bar off a terminal";
}

TEST(RunProgress, OnATerminalABarRedrawnInPlaceAndEndedAtTheLastFrame) {
    Captured out;
    RunProgress p(ProgressStyle::Bar, "teapots, 2 configurations", 40, 40, out.file());
    p.frameDone(1, 0.01);
    EXPECT_EQ(out.text().rfind("\r[--------------------] frame 1/40, teapots, 2 configurations", 0),
              0u)
        << out.text();
    p.frameDone(2, 0.1);  // within a quarter second: not redrawn
    EXPECT_EQ(out.text().find("frame 2/40"), std::string::npos);
    p.frameDone(20, 0.5);
    EXPECT_NE(out.text().find("\r[##########----------] frame 20/40"), std::string::npos);
    p.frameDone(40, 0.6);  // the last frame is always drawn, and ends the line
    const std::string text = out.text();
    EXPECT_NE(text.find("\r[####################] frame 40/40"), std::string::npos) << text;
    EXPECT_EQ(text.back(), '\n');
    EXPECT_EQ(text.find('\n'), text.size() - 1) << "one line, redrawn";
}

TEST(RunProgress, AStoppedRunEndsItsBarAndQuietPrintsNothing) {
    Captured bar;
    RunProgress stopped(ProgressStyle::Bar, "s, 1 configuration", 40, 40, bar.file());
    stopped.frameDone(3, 1.0);
    stopped.finish();
    EXPECT_EQ(bar.text().back(), '\n');
    Captured quiet;
    RunProgress none(ProgressStyle::None, "s, 1 configuration", 40, 40, quiet.file());
    for (uint32_t f = 1; f <= 40; ++f) none.frameDone(f, 5.0 * f);
    none.finish();
    EXPECT_EQ(quiet.text(), "");
    EXPECT_EQ(stderrProgressStyle(true), ProgressStyle::None);
}

TEST(RunProgress, SaysTheRepetitionOfARepeatedRun) {
    const RunProgress p(ProgressStyle::Lines, "s, 3 configurations", 240, 120, stderr);
    EXPECT_EQ(p.status(120, 60.0),
              "frame 120/240 (repetition 1/2), s, 3 configurations, 60 s elapsed, about 60 s "
              "left");
    EXPECT_NE(p.status(121, 60.0).find("(repetition 2/2)"), std::string::npos);
}

}  // namespace
}  // namespace occsim
