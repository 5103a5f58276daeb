#include "sim/output/console_colour.h"

#include <unistd.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace occsim {
namespace {

constexpr const char* kReset = "\033[0m";

struct Mark {
    std::string_view prefix;  // a line that starts with it (after its indent)
    const char* colour;
};

constexpr std::array<Mark, 4> kMarks = {{
    {"verdict:", "\033[1m"},
    {"WRONG PIXELS", "\033[1;31m"},
    {"busy machine:", "\033[33m"},
    {"warning:", "\033[33m"},
}};

}  // namespace

bool colourWanted(bool is_terminal, const char* no_color, const char* term) {
    if (!is_terminal) return false;
    if (no_color != nullptr && no_color[0] != '\0') return false;
    return term == nullptr || std::strcmp(term, "dumb") != 0;
}

bool stdoutWantsColour() {
    return colourWanted(::isatty(STDOUT_FILENO) == 1, std::getenv("NO_COLOR"), std::getenv("TERM"));
}

std::string colouredConsoleText(const std::string& text) {
    std::string out;
    out.reserve(text.size() + 64);
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string_view line(text.data() + start, end - start);
        const size_t indent = line.find_first_not_of(' ');
        const std::string_view body =
            indent == std::string_view::npos ? std::string_view() : line.substr(indent);
        const Mark* mark = nullptr;
        for (const Mark& m : kMarks) {
            if (body.substr(0, m.prefix.size()) == m.prefix) mark = &m;
        }
        if (mark) {
            // The first word coloured: the prefix itself.
            out.append(line.substr(0, indent));
            out += mark->colour;
            out.append(mark->prefix);
            out += kReset;
            out.append(body.substr(mark->prefix.size()));
        } else {
            out.append(line);
        }
        if (end < text.size()) out += '\n';
        start = end + 1;
    }
    return out;
}

}  // namespace occsim
