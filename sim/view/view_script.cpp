#include "sim/view/view_script.h"

#include <fstream>
#include <sstream>

#include "sim/scenario/number_text.h"

namespace occsim {
namespace {

constexpr const char* kCommands = "wait, press, down, up, hold, drag, wheel, resize, quit";

class LineParser {
  public:
    LineParser(const std::filesystem::path& file, size_t line, std::vector<std::string> words)
        : file_(file), line_(line), words_(std::move(words)) {}

    [[noreturn]] void fail(const std::string& message) const {
        throw ScriptError(file_.string() + ":" + std::to_string(line_) + ": " + message);
    }

    const std::string& command() const { return words_[0]; }

    void expectArguments(size_t count, const char* usage) const {
        if (words_.size() != count + 1) {
            fail("'" + command() + "' takes " + std::to_string(count) + " argument" +
                 (count == 1 ? "" : "s") + " (" + usage + "), got " +
                 std::to_string(words_.size() - 1));
        }
    }

    int64_t integer(size_t argument, int64_t lo, int64_t hi, const char* what) const {
        const std::string& word = words_[argument];
        int64_t value = 0;
        if (!parseInteger(word, value) || value < lo || value > hi) {
            fail(std::string(what) + ": expected an integer in [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "], got '" + word + "'");
        }
        return value;
    }

    std::string_view key(const std::string& word) const {
        const std::string_view name = findKeyName(word);
        if (name.empty()) {
            fail("unknown key '" + word +
                 "'; expected a letter, a digit, f1-f12 or one of: space, tab, enter, escape, "
                 "backspace, delete, insert, home, end, page_up, page_down, up, down, left, right, "
                 "shift, ctrl, alt, minus, equal, comma, period");
        }
        return name;
    }

    const std::string& word(size_t i) const { return words_[i]; }

  private:
    const std::filesystem::path& file_;
    size_t line_;
    std::vector<std::string> words_;
};

ScriptStep eventStep(WindowEvent::Type type, std::string_view key = {}, double x = 0,
                     double y = 0) {
    ScriptStep s;
    s.kind = ScriptStep::Kind::Event;
    s.event.type = type;
    s.event.key = key;
    s.event.x = x;
    s.event.y = y;
    return s;
}

ScriptStep waitStep(uint32_t frames) {
    ScriptStep s;
    s.kind = ScriptStep::Kind::Wait;
    s.frames = frames;
    return s;
}

std::vector<std::string_view> splitKeys(const LineParser& p, const std::string& combo) {
    std::vector<std::string_view> keys;
    size_t start = 0;
    while (true) {
        const size_t plus = combo.find('+', start);
        keys.push_back(p.key(
            combo.substr(start, plus == std::string::npos ? std::string::npos : plus - start)));
        if (plus == std::string::npos) break;
        start = plus + 1;
    }
    return keys;
}

}  // namespace

ViewScript parseViewScript(const std::string& text, const std::filesystem::path& file) {
    ViewScript script;
    script.file = file;
    // The cursor of drags, so that every drag starts where the last one ended (as a hand would).
    double cursor_x = 100.0, cursor_y = 100.0;
    std::istringstream lines(text);
    std::string line;
    for (size_t number = 1; std::getline(lines, line); ++number) {
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream in(line);
        std::vector<std::string> words;
        for (std::string w; in >> w;) words.push_back(w);
        if (words.empty()) continue;
        const LineParser p(file, number, words);
        const std::string& c = p.command();
        auto& steps = script.steps;
        if (c == "wait") {
            p.expectArguments(1, "wait FRAMES");
            steps.push_back(
                waitStep(static_cast<uint32_t>(p.integer(1, 1, 1000000, "wait FRAMES"))));
        } else if (c == "press") {
            p.expectArguments(1, "press KEY[+KEY...]");
            const auto keys = splitKeys(p, p.word(1));
            for (auto k : keys) steps.push_back(eventStep(WindowEvent::Type::KeyDown, k));
            for (auto k = keys.rbegin(); k != keys.rend(); ++k) {
                steps.push_back(eventStep(WindowEvent::Type::KeyUp, *k));
            }
        } else if (c == "down" || c == "up") {
            p.expectArguments(1, (c + " KEY").c_str());
            steps.push_back(
                eventStep(c == "down" ? WindowEvent::Type::KeyDown : WindowEvent::Type::KeyUp,
                          p.key(p.word(1))));
        } else if (c == "hold") {
            p.expectArguments(2, "hold KEY FRAMES");
            const std::string_view k = p.key(p.word(1));
            const auto frames = static_cast<uint32_t>(p.integer(2, 1, 1000000, "hold KEY FRAMES"));
            steps.push_back(eventStep(WindowEvent::Type::KeyDown, k));
            steps.push_back(waitStep(frames));
            steps.push_back(eventStep(WindowEvent::Type::KeyUp, k));
        } else if (c == "drag") {
            p.expectArguments(2, "drag DX DY");
            const auto dx = static_cast<double>(p.integer(1, -100000, 100000, "drag DX"));
            const auto dy = static_cast<double>(p.integer(2, -100000, 100000, "drag DY"));
            steps.push_back(eventStep(WindowEvent::Type::CursorMove, {}, cursor_x, cursor_y));
            steps.push_back(eventStep(WindowEvent::Type::MouseDown));
            cursor_x += dx;
            cursor_y += dy;
            steps.push_back(eventStep(WindowEvent::Type::CursorMove, {}, cursor_x, cursor_y));
            steps.push_back(eventStep(WindowEvent::Type::MouseUp));
        } else if (c == "wheel") {
            p.expectArguments(1, "wheel NOTCHES");
            const auto notches = static_cast<double>(p.integer(1, -100, 100, "wheel NOTCHES"));
            steps.push_back(eventStep(WindowEvent::Type::Scroll, {}, 0.0, notches));
        } else if (c == "resize") {
            p.expectArguments(2, "resize WIDTH HEIGHT");
            ScriptStep s;
            s.kind = ScriptStep::Kind::Resize;
            s.width = static_cast<uint32_t>(p.integer(1, 16, 8192, "resize WIDTH"));
            s.height = static_cast<uint32_t>(p.integer(2, 16, 8192, "resize HEIGHT"));
            steps.push_back(s);
        } else if (c == "quit") {
            p.expectArguments(0, "quit");
            ScriptStep s;
            s.kind = ScriptStep::Kind::Quit;
            steps.push_back(s);
        } else {
            p.fail("unknown command '" + c + "'; expected one of: " + kCommands);
        }
    }
    return script;
}

ViewScript readViewScript(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ScriptError(file.string() + ": cannot open the script file");
    std::ostringstream text;
    text << in.rdbuf();
    return parseViewScript(text.str(), file);
}

ScriptPlayer::FrameInput ScriptPlayer::next() {
    FrameInput in;
    if (waiting_ > 0) {
        --waiting_;
        return in;
    }
    while (position_ < script_.steps.size()) {
        const ScriptStep& step = script_.steps[position_++];
        switch (step.kind) {
            case ScriptStep::Kind::Event:
                in.events.push_back(step.event);
                break;
            case ScriptStep::Kind::Resize:
                in.resize = std::make_pair(step.width, step.height);
                break;
            case ScriptStep::Kind::Quit:
                in.quit = true;
                return in;
            case ScriptStep::Kind::Wait:
                waiting_ = step.frames - 1;  // this frame is the first of the wait
                return in;
        }
    }
    in.quit = true;  // the script is over: what it asked for last still gets its frame
    return in;
}

}  // namespace occsim
