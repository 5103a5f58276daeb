#include "sim/regress/junit_reader.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>

#include "sim/regress/result_files.h"

namespace occsim {
namespace {

struct Tag {
    std::string name;
    std::map<std::string, std::string> attributes;
    bool closing = false;       // </name>
    bool self_closing = false;  // <name/>
};

// Walks the text tag by tag; text between tags is skipped (failure details).
class TagReader {
  public:
    TagReader(const std::string& text, const std::string& name) : text_(text), name_(name) {}

    [[noreturn]] void fail(const std::string& message) const {
        const size_t line =
            1 + std::count(text_.begin(), text_.begin() + std::min(pos_, text_.size()), '\n');
        throw ResultFileError(
            name_ + ": line " + std::to_string(line) + ": " + message +
            " (a truncated or corrupt JUnit file; rerun the shard that wrote it)");
    }

    // False at the end of the text.
    bool next(Tag& tag) {
        pos_ = text_.find('<', pos_);
        if (pos_ == std::string::npos) {
            pos_ = text_.size();
            return false;
        }
        const size_t end = text_.find('>', pos_);
        if (end == std::string::npos)
            fail("expected '>' to close the tag, got the end of the file");
        std::string body = text_.substr(pos_ + 1, end - pos_ - 1);
        tag = Tag{};
        if (!body.empty() && (body.front() == '?' || body.front() == '!')) {
            pos_ = end + 1;
            tag.name = body.substr(0, 1);
            tag.self_closing = true;
            return true;
        }
        if (!body.empty() && body.front() == '/') {
            tag.closing = true;
            body.erase(0, 1);
        }
        if (!body.empty() && body.back() == '/') {
            tag.self_closing = true;
            body.pop_back();
        }
        parseBody(body, tag);
        pos_ = end + 1;
        return true;
    }

  private:
    void parseBody(const std::string& body, Tag& tag) {
        size_t i = 0;
        while (i < body.size() && !std::isspace(static_cast<unsigned char>(body[i]))) ++i;
        tag.name = body.substr(0, i);
        if (tag.name.empty()) fail("expected an element name after '<'");
        while (true) {
            while (i < body.size() && std::isspace(static_cast<unsigned char>(body[i]))) ++i;
            if (i == body.size()) return;
            const size_t eq = body.find('=', i);
            if (eq == std::string::npos || eq + 1 >= body.size() || body[eq + 1] != '"') {
                fail("expected name=\"value\" in <" + tag.name + ">");
            }
            const size_t close = body.find('"', eq + 2);
            if (close == std::string::npos) fail("expected a closing quote in <" + tag.name + ">");
            tag.attributes[body.substr(i, eq - i)] = body.substr(eq + 2, close - eq - 2);
            i = close + 1;
        }
    }

    const std::string& text_;
    const std::string& name_;
    size_t pos_ = 0;
};

size_t countAttribute(const Tag& tag, const char* key, TagReader& reader) {
    const auto it = tag.attributes.find(key);
    if (it == tag.attributes.end())
        reader.fail("expected attribute " + std::string(key) + " in <" + tag.name + ">");
    const std::string& v = it->second;
    if (v.empty() || v.size() > 9 || v.find_first_not_of("0123456789") != std::string::npos) {
        reader.fail("expected a count in " + std::string(key) + "=\"...\" of <" + tag.name +
                    ">, got '" + v + "'");
    }
    return std::stoul(v);
}

// The attribute text as written by junitXml(): the five entities and the references to tab,
// newline and carriage return decoded.
std::string unescape(const std::string& s) {
    static const std::pair<const char*, char> entities[] = {
        {"&amp;", '&'},   {"&lt;", '<'},  {"&gt;", '>'},   {"&quot;", '"'},
        {"&apos;", '\''}, {"&#9;", '\t'}, {"&#10;", '\n'}, {"&#13;", '\r'}};
    std::string out;
    for (size_t i = 0; i < s.size();) {
        bool matched = false;
        for (const auto& [entity, c] : entities) {
            if (s.compare(i, std::char_traits<char>::length(entity), entity) == 0) {
                out += c;
                i += std::char_traits<char>::length(entity);
                matched = true;
                break;
            }
        }
        if (!matched) out += s[i++];
    }
    return out;
}

}  // namespace

std::vector<JunitSuite> parseJunit(const std::string& text, const std::string& name) {
    TagReader reader(text, name);
    std::vector<std::string> open;  // element stack
    std::vector<JunitSuite> suites;
    std::vector<size_t> declared_tests;
    size_t total_declared = 0, total_seen = 0;
    bool root_seen = false, root_closed = false;
    Tag tag;
    while (reader.next(tag)) {
        if (tag.name == "?" || tag.name == "!") continue;
        if (root_closed)
            reader.fail("expected nothing after </testsuites>, got <" + tag.name + ">");
        if (tag.closing) {
            if (open.empty() || open.back() != tag.name) {
                reader.fail("expected </" +
                            (open.empty() ? std::string("testsuites") : open.back()) + ">, got </" +
                            tag.name + ">");
            }
            open.pop_back();
            if (tag.name == "testsuite" && suites.back().testcases != declared_tests.back()) {
                reader.fail("testsuite '" + suites.back().name + "' declares tests=\"" +
                            std::to_string(declared_tests.back()) + "\" but has " +
                            std::to_string(suites.back().testcases) + " testcases");
            }
            if (tag.name == "testsuites") root_closed = true;
            continue;
        }
        const std::string parent = open.empty() ? "" : open.back();
        if (tag.name == "testsuites") {
            if (root_seen || !open.empty()) reader.fail("expected one <testsuites> at the top");
            root_seen = true;
            total_declared = countAttribute(tag, "tests", reader);
        } else if (tag.name == "testsuite") {
            if (parent != "testsuites") reader.fail("expected <testsuite> inside <testsuites>");
            const auto n = tag.attributes.find("name");
            if (n == tag.attributes.end()) reader.fail("expected attribute name in <testsuite>");
            suites.push_back({unescape(n->second), 0, 0, 0});
            declared_tests.push_back(countAttribute(tag, "tests", reader));
        } else if (tag.name == "testcase") {
            if (parent != "testsuite") reader.fail("expected <testcase> inside <testsuite>");
            ++suites.back().testcases;
            ++total_seen;
        } else if (tag.name == "failure" || tag.name == "skipped") {
            if (parent != "testcase") reader.fail("expected <" + tag.name + "> inside <testcase>");
            ++(tag.name == "failure" ? suites.back().failures : suites.back().skipped);
        } else {
            reader.fail("unexpected element <" + tag.name + ">");
        }
        if (!tag.self_closing) open.push_back(tag.name);
    }
    if (!root_seen) reader.fail("expected <testsuites>, got none");
    if (!root_closed) reader.fail("expected </" + open.back() + ">, got the end of the file");
    if (total_seen != total_declared) {
        reader.fail("<testsuites> declares tests=\"" + std::to_string(total_declared) +
                    "\" but has " + std::to_string(total_seen) + " testcases");
    }
    return suites;
}

std::vector<JunitSuite> readJunit(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ResultFileError(file.string() + ": cannot open the JUnit file");
    std::ostringstream s;
    s << in.rdbuf();
    return parseJunit(s.str(), file.string());
}

}  // namespace occsim
