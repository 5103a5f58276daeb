// Finds the repository paths a text names, so a test can check that each still exists: in
// Markdown, every word that starts with a top-level folder of the repository (`culling/...`,
// `docs/...`, also inside code blocks) and every link target (relative to the page's folder, with
// its #anchor); in code, the same words inside comments only (a string literal may name a file
// that a test creates on purpose).
//
// Not a repository path, by rule rather than by list: a word with a placeholder or glob in it
// (`<room>`, `*`, `$OUT`, `...`), a file whose name is one letter (`scenarios/X.json`) or starts
// with "my" (`culling/cullers/my_culler.cpp`: the reader's own file), and links to web addresses.
// `a.{h,cpp}` names both files; `occsim/culling/...` (the include path of a public header) names
// `culling/include/occsim/culling/...`, the file it is.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace occsim::testing {

struct NamedPath {
    std::string path;    // relative to the repository root, lexically normal; may end in '/'
    std::string anchor;  // a link's #anchor without '#', else empty
    int line = 0;        // 1-based, in the text scanned
};

inline bool isPathChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '+' ||
           c == '/' || c == '-';
}

// Characters that make a word a placeholder or a pattern when they appear in it.
inline bool isPlaceholderChar(char c) { return c == '<' || c == '>' || c == '*' || c == '$'; }

inline int lineAt(std::string_view text, size_t pos) {
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

// The file names a reader is meant to replace: one letter (X.json), or "my..." (my_culler.cpp).
inline bool isPlaceholderName(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    const std::string stem = std::filesystem::path(path).stem().string();
    return stem.size() == 1 || name.rfind("my_", 0) == 0 || name.rfind("my-", 0) == 0;
}

// The word at `pos` (which starts a path), with one {a,b} group expanded: its spellings.
inline std::vector<std::string> wordAt(std::string_view text, size_t pos, bool* placeholder) {
    std::string before, group, after;
    bool in_group = false, had_group = false;
    size_t i = pos;
    for (; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '{' && !had_group) {
            in_group = had_group = true;
        } else if (in_group) {
            if (c == '}') {
                in_group = false;
            } else {
                group += c;
            }
        } else if (isPathChar(c) || isPlaceholderChar(c)) {
            (had_group ? after : before) += c;
        } else {
            break;
        }
    }
    std::vector<std::string> words;
    if (!had_group || in_group) {
        words.push_back(before);
    } else {
        size_t start = 0;
        while (start <= group.size()) {
            const size_t comma = std::min(group.find(',', start), group.size());
            words.push_back(before + group.substr(start, comma - start) + after);
            start = comma + 1;
        }
    }
    *placeholder = false;
    for (std::string& w : words) {
        while (!w.empty() && std::string_view(".,:;-").find(w.back()) != std::string_view::npos) {
            if (w.size() >= 3 && w.compare(w.size() - 3, 3, "...") == 0) *placeholder = true;
            w.pop_back();
        }
        if (std::any_of(w.begin(), w.end(), isPlaceholderChar) || isPlaceholderName(w) ||
            w.find("...") != std::string::npos) {
            *placeholder = true;
        }
    }
    return words;
}

// Every word of `text` that starts with one of `top_folders` followed by '/' (and is not inside
// a longer path: "./build/release/sim" names no `sim/`).
inline std::vector<NamedPath> repositoryWords(std::string_view text,
                                              const std::set<std::string>& top_folders) {
    std::vector<NamedPath> found;
    constexpr std::string_view kIncludePath = "occsim/culling/";  // a public header's
    const std::string kIncludeRoot = "culling/include/";          // folder of public headers
    for (size_t pos = 0; pos < text.size(); ++pos) {
        if (pos > 0 && (isPathChar(text[pos - 1]) || isPlaceholderChar(text[pos - 1]))) continue;
        const bool include_path = text.substr(pos, kIncludePath.size()) == kIncludePath;
        if (!include_path) {
            const size_t slash = text.find('/', pos);
            if (slash == std::string_view::npos || slash == pos) continue;
            if (!top_folders.count(std::string(text.substr(pos, slash - pos)))) continue;
        }
        bool placeholder = false;
        const std::vector<std::string> words = wordAt(text, pos, &placeholder);
        if (placeholder) continue;
        for (const std::string& w : words) {
            std::string path = include_path ? kIncludeRoot : std::string();
            path.append(w);
            found.push_back({path, "", lineAt(text, pos)});
        }
    }
    return found;
}

// Markdown link targets `[text](target)` and `![alt](target)`, resolved against `page_folder`
// (the page's folder, relative to the repository root). Web and mail links are not paths.
inline std::vector<NamedPath> markdownLinks(std::string_view text,
                                            const std::filesystem::path& page_folder) {
    std::vector<NamedPath> found;
    for (size_t pos = text.find("]("); pos != std::string_view::npos;
         pos = text.find("](", pos + 2)) {
        const size_t end = text.find(')', pos + 2);
        if (end == std::string_view::npos) break;
        std::string target(text.substr(pos + 2, end - pos - 2));
        if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0 ||
            target.find(' ') != std::string::npos) {
            continue;
        }
        std::string anchor;
        if (const size_t hash = target.find('#'); hash != std::string::npos) {
            anchor = target.substr(hash + 1);
            target.erase(hash);
        }
        const std::string path =
            target.empty() ? "" : (page_folder / target).lexically_normal().generic_string();
        found.push_back({path, anchor, lineAt(text, pos)});
    }
    return found;
}

// The text of `source`'s comments, everything else blanked (line breaks kept, so lines still
// count). `hash_comments`: '#' starts a comment (shell, CMake, Python) when it begins a word;
// otherwise C++: // and /* */, outside string, character and raw string literals.
inline std::string commentsOnly(std::string_view source, bool hash_comments) {
    std::string out(source.size(), ' ');
    enum { Code, Line, Block, String, Char, Raw } state = Code;
    std::string raw_end;  // )delimiter" of the raw string being skipped
    for (size_t i = 0; i < source.size(); ++i) {
        const char c = source[i];
        if (c == '\n') out[i] = '\n';
        switch (state) {
            case Code:
                if (hash_comments) {
                    if (c == '#' &&
                        (i == 0 || std::isspace(static_cast<unsigned char>(source[i - 1]))))
                        state = Line;
                } else if (source.substr(i, 2) == "//") {
                    state = Line;
                } else if (source.substr(i, 2) == "/*") {
                    state = Block;
                } else if (c == 'R' && source.substr(i + 1, 1) == "\"" &&
                           (i == 0 || !isPathChar(source[i - 1]))) {
                    const size_t open = source.find('(', i);
                    raw_end = ")" + std::string(source.substr(i + 2, open - i - 2)) + "\"";
                    state = Raw;
                } else if (c == '"') {
                    state = String;
                } else if (c == '\'' && !(i > 0 && std::isxdigit(static_cast<unsigned char>(
                                                       source[i - 1])))) {  // not 1'000'000
                    state = Char;
                }
                break;
            case Line:
                if (c == '\n') {
                    state = Code;
                } else {
                    out[i] = c;
                }
                break;
            case Block:
                if (source.substr(i, 2) == "*/") {
                    state = Code;
                    ++i;
                } else if (c != '\n') {
                    out[i] = c;
                }
                break;
            case String:
            case Char:
                if (c == '\\') {
                    ++i;
                } else if (c == (state == String ? '"' : '\'') || c == '\n') {
                    state = Code;
                }
                break;
            case Raw:
                if (source.substr(i, raw_end.size()) == raw_end) {
                    i += raw_end.size() - 1;
                    state = Code;
                }
                break;
        }
    }
    return out;
}

// GitHub's anchors of a page's headings (outside code blocks): lower case, spaces to '-', other
// punctuation but '-' and '_' dropped, a repeated anchor numbered "-1", "-2", ...
inline std::set<std::string> headingAnchors(std::string_view markdown) {
    std::set<std::string> anchors;
    bool in_code = false;
    size_t start = 0;
    while (start < markdown.size()) {
        const size_t end = std::min(markdown.find('\n', start), markdown.size());
        const std::string_view line = markdown.substr(start, end - start);
        start = end + 1;
        if (line.rfind("```", 0) == 0) in_code = !in_code;
        if (in_code || line.rfind('#', 0) != 0) continue;
        std::string anchor;
        for (const char c : line.substr(line.find_first_not_of('#'))) {
            const auto u = static_cast<unsigned char>(c);
            if (std::isalnum(u) || c == '-' || c == '_' || u >= 0x80) {
                anchor += static_cast<char>(std::tolower(u));
            } else if (c == ' ') {
                anchor += '-';
            }
        }
        if (!anchor.empty() && anchor.front() == '-') anchor.erase(0, 1);
        std::string unique = anchor;
        for (int n = 1; anchors.count(unique); ++n) unique = anchor + "-" + std::to_string(n);
        anchors.insert(unique);
    }
    return anchors;
}

}  // namespace occsim::testing
