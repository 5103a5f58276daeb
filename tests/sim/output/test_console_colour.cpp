// Colour on the console (sim/output/console_colour.h): only on a terminal, never with NO_COLOR or
// TERM=dumb; only a marked line's first word, so that a line read without its escape codes is the
// line as it was.
#include <gtest/gtest.h>

#include <string>

#include "sim/output/console_colour.h"

namespace occsim {
namespace {

// The text as a terminal shows it: every escape sequence (ESC [ ... m) taken out.
std::string withoutEscapes(const std::string& text) {
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\033') {
            while (i < text.size() && text[i] != 'm') ++i;
            continue;
        }
        out += text[i];
    }
    return out;
}

TEST(ConsoleColour, OnlyATerminalWithoutNoColorAndNotDumbGetsColour) {
    EXPECT_TRUE(colourWanted(true, nullptr, "xterm-256color"));
    EXPECT_TRUE(colourWanted(true, nullptr, nullptr));
    EXPECT_TRUE(colourWanted(true, "", "xterm"));         // NO_COLOR set but empty: no request
    EXPECT_FALSE(colourWanted(false, nullptr, "xterm"));  // a file or a pipe
    EXPECT_FALSE(colourWanted(true, "1", "xterm"));
    EXPECT_FALSE(colourWanted(true, "anything", "xterm"));
    EXPECT_FALSE(colourWanted(true, nullptr, "dumb"));
}

TEST(ConsoleColour, MarksTheVerdictWrongPixelsAndWarningsAndNothingElse) {
    const std::string text =
        "configuration  kind    mean ms\n"
        "verdict: fastest conservative culler chc, 1.2x faster than statistical+\n"
        "  faster on 80 of 110 frames\n"
        "WRONG PIXELS from conservative cullers (a bug): chc 12 px, 1 missed\n"
        "busy machine: other work ran beside this run\n"
        "warning: the camera sees no object\n"
        "\n"
        "the verdict: is not at the start of this line\n";
    const std::string coloured = colouredConsoleText(text);
    EXPECT_EQ(withoutEscapes(coloured), text);
    EXPECT_NE(coloured.find("\033[1mverdict:\033[0m fastest"), std::string::npos) << coloured;
    EXPECT_NE(coloured.find("\033[1;31mWRONG PIXELS\033[0m from"), std::string::npos);
    EXPECT_NE(coloured.find("\033[33mbusy machine:\033[0m other"), std::string::npos);
    EXPECT_NE(coloured.find("\033[33mwarning:\033[0m the camera"), std::string::npos);
    EXPECT_NE(coloured.find("\nthe verdict: is not at the start of this line\n"),
              std::string::npos);
    EXPECT_NE(coloured.find("\n  faster on 80 of 110 frames\n"), std::string::npos);
    // An indented marked line keeps its indent before the colour.
    EXPECT_EQ(colouredConsoleText("  warning: x\n"), "  \033[33mwarning:\033[0m x\n");
}

TEST(ConsoleColour, PlainTextAndTheEmptyTextStayAsTheyAre) {
    EXPECT_EQ(colouredConsoleText(""), "");
    EXPECT_EQ(colouredConsoleText("a\nb"), "a\nb");
    EXPECT_EQ(colouredConsoleText("\n\n"), "\n\n");
    EXPECT_EQ(colouredConsoleText("wrong pixels: none from a conservative culler\n"),
              "wrong pixels: none from a conservative culler\n");
}

}  // namespace
}  // namespace occsim
