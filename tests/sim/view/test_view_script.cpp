// The viewer's scripted input (sim/view/view_script.h): mistakes name the file, the line and what
// was expected; input applies before the next frame, waits and holds count frames, quit ends it.
#include <gtest/gtest.h>

#include "sim/view/view_script.h"

namespace occsim {
namespace {

std::string scriptError(const std::string& text) {
    try {
        parseViewScript(text, "drive.txt");
    } catch (const ScriptError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(ViewScript, MistakesNameTheFileTheLineAndWhatWasExpected) {
    EXPECT_EQ(scriptError("wait 2\n\n  prss b\n"),
              "drive.txt:3: unknown command 'prss'; expected one of: wait, press, down, up, hold, "
              "drag, wheel, resize, quit");
    const std::string bad_key = scriptError("press shift+tabb");
    EXPECT_EQ(bad_key.rfind("drive.txt:1: unknown key 'tabb'; expected a letter, a digit", 0), 0u)
        << bad_key;
    EXPECT_EQ(scriptError("# set-up\nwait 0"),
              "drive.txt:2: wait FRAMES: expected an integer in [1, 1000000], got '0'");
    EXPECT_EQ(scriptError("hold w"),
              "drive.txt:1: 'hold' takes 2 arguments (hold KEY FRAMES), got 1");
    EXPECT_EQ(scriptError("resize 800 x"),
              "drive.txt:1: resize HEIGHT: expected an integer in [16, 8192], got 'x'");
    EXPECT_EQ(scriptError("wheel 2.5"),
              "drive.txt:1: wheel NOTCHES: expected an integer in [-100, 100], got '2.5'");
    EXPECT_EQ(scriptError("quit now"), "drive.txt:1: 'quit' takes 0 arguments (quit), got 1");
}

TEST(ViewScript, AMissingFileIsNamed) {
    try {
        readViewScript("/no/such/script.txt");
        FAIL() << "no error";
    } catch (const ScriptError& e) {
        EXPECT_EQ(std::string(e.what()), "/no/such/script.txt: cannot open the script file");
    }
}

// What each frame of a played script delivers.
std::vector<std::string> playAll(const std::string& text) {
    ScriptPlayer player(parseViewScript(text, "s.txt"));
    std::vector<std::string> frames;
    for (int guard = 0; guard < 1000; ++guard) {
        const ScriptPlayer::FrameInput in = player.next();
        std::string f;
        for (const WindowEvent& e : in.events) {
            switch (e.type) {
                case WindowEvent::Type::KeyDown:
                    f += "+" + std::string(e.key) + " ";
                    break;
                case WindowEvent::Type::KeyUp:
                    f += "-" + std::string(e.key) + " ";
                    break;
                case WindowEvent::Type::MouseDown:
                    f += "mouse+ ";
                    break;
                case WindowEvent::Type::MouseUp:
                    f += "mouse- ";
                    break;
                case WindowEvent::Type::CursorMove:
                    f += "at(" + std::to_string(int(e.x)) + "," + std::to_string(int(e.y)) + ") ";
                    break;
                case WindowEvent::Type::Scroll:
                    f += "wheel(" + std::to_string(int(e.y)) + ") ";
                    break;
                default:
                    f += "? ";
                    break;
            }
        }
        if (in.resize)
            f += "resize(" + std::to_string(in.resize->first) + "x" +
                 std::to_string(in.resize->second) + ") ";
        if (in.quit) f += "quit";
        frames.push_back(f);
        if (in.quit) break;
    }
    return frames;
}

TEST(ViewScript, InputAppliesBeforeTheNextFrameAndWaitsAndHoldsCountFrames) {
    const std::vector<std::string> frames = playAll(
        "press b   # boxes\nwait 2\nhold w 3\npress shift+tab\ndrag 10 -5\nwheel -2\nresize 320 "
        "200\n");
    const std::vector<std::string> expected = {
        "+b -b ",  // press, then the first of the two waited frames
        "",
        "+w ",  // held for three frames
        "",
        "",
        "-w +shift +tab -tab -shift at(100,100) mouse+ at(110,95) mouse- wheel(-2) resize(320x200) "
        "quit",
    };
    EXPECT_EQ(frames, expected);
}

TEST(ViewScript, QuitEndsThePlayEvenWithLinesLeft) {
    EXPECT_EQ(playAll("wait 1\nquit\npress b\n"), (std::vector<std::string>{"", "quit"}));
    EXPECT_EQ(playAll(""), (std::vector<std::string>{"quit"}));
}

}  // namespace
}  // namespace occsim
