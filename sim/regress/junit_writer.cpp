// A regression run as JUnit XML: one test case per scenario, its failed checks as the failure.
#include <cstdio>
#include <sstream>

#include "sim/output/fixed_text.h"
#include "sim/regress/regress.h"

namespace occsim {
namespace {

// Escaped for an attribute or text of XML 1.0. Tab, newline and carriage return become character
// references (an attribute keeps them); the other control characters, which XML 1.0 forbids even
// as references, are written as visible text (junitVisibleText()).
std::string xmlEscape(const std::string& s) {
    std::string out;
    for (char c : junitVisibleText(s)) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            case '\t':
                out += "&#9;";
                break;
            case '\n':
                out += "&#10;";
                break;
            case '\r':
                out += "&#13;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

}  // namespace

std::string junitVisibleText(const std::string& s) {
    std::string out;
    for (char c : s) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (u < 0x20 && c != '\t' && c != '\n' && c != '\r') {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", u);
            out += buf;
        } else {
            out += c;
        }
    }
    return out;
}

std::string junitXml(const RegressReport& report) {
    size_t tests = 0, failures = 0, skipped = 0;
    double seconds = 0;
    for (const ScenarioOutcome& s : report.scenarios) {
        tests += s.skipped ? 1 : s.checks.size();
        skipped += s.skipped;
        for (const CheckResult& c : s.checks) failures += !c.passed;
        seconds += s.seconds;
    }
    std::ostringstream out;
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"occsim regress\" "
           "tests=\""
        << tests << "\" failures=\"" << failures << "\" skipped=\"" << skipped << "\" time=\""
        << fixed(seconds, 3) << "\">\n";
    for (const ScenarioOutcome& s : report.scenarios) {
        size_t f = 0;
        for (const CheckResult& c : s.checks) f += !c.passed;
        out << "  <testsuite name=\"" << xmlEscape(s.name) << "\" file=\"" << xmlEscape(s.scenario)
            << "\" tests=\"" << (s.skipped ? 1 : s.checks.size()) << "\" failures=\"" << f
            << "\" skipped=\"" << (s.skipped ? 1 : 0) << "\" time=\"" << fixed(s.seconds, 3)
            << "\">\n";
        if (s.skipped) {
            out << "    <testcase classname=\"" << xmlEscape(s.name) << "\" name=\"scenario\">"
                << "<skipped message=\"" << xmlEscape(s.note) << "\"/></testcase>\n";
        }
        for (const CheckResult& c : s.checks) {
            out << "    <testcase classname=\"" << xmlEscape(s.name) << "\" name=\""
                << xmlEscape(c.check) << "\"";
            if (c.passed) {
                out << "/>\n";
            } else {
                std::string detail = "expected " + c.expected + ", got " + c.got;
                for (const auto& capture : s.captures) detail += "\ncapture: " + capture;
                out << "><failure message=\""
                    << xmlEscape("expected " + c.expected + ", got " + c.got) << "\">"
                    << xmlEscape(detail) << "</failure></testcase>\n";
            }
        }
        out << "  </testsuite>\n";
    }
    out << "</testsuites>\n";
    return out.str();
}

}  // namespace occsim
