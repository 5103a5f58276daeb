#include "render/window_events.h"

#include <algorithm>
#include <array>

namespace occsim {
namespace {

constexpr std::array<std::string_view, 36 + 12 + 22> kKeyNames = {
    "a",      "b",    "c",   "d",       "e",         "f",     "g",      "h",         "i",
    "j",      "k",    "l",   "m",       "n",         "o",     "p",      "q",         "r",
    "s",      "t",    "u",   "v",       "w",         "x",     "y",      "z",         "0",
    "1",      "2",    "3",   "4",       "5",         "6",     "7",      "8",         "9",
    "f1",     "f2",   "f3",  "f4",      "f5",        "f6",    "f7",     "f8",        "f9",
    "f10",    "f11",  "f12", "space",   "tab",       "enter", "escape", "backspace", "delete",
    "insert", "home", "end", "page_up", "page_down", "up",    "down",   "left",      "right",
    "shift",  "ctrl", "alt", "minus",   "equal",     "comma", "period"};

}  // namespace

std::span<const std::string_view> keyNames() { return kKeyNames; }

std::string_view findKeyName(std::string_view name) {
    const auto it = std::find(kKeyNames.begin(), kKeyNames.end(), name);
    return it == kKeyNames.end() ? std::string_view{} : *it;
}

}  // namespace occsim
