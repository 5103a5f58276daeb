// A small strict reader over nlohmann::json for configuration files (scenarios).
//
// Every value is read through a reader that knows its JSON pointer (RFC 6901) and the file it
// came from, so every complaint is a ScenarioError "<file>: <pointer>: <expected ..., got ...>".
// Object readers remember which keys were asked for; finish() rejects any other key, with a
// "did you mean" suggestion when an allowed key is a small edit away. That is the point of the
// strictness: a typo in a regression scenario must fail loudly, never fall back to a default.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sim/scenario/errors.h"

namespace occsim {

using Json = nlohmann::json;

// Parses JSON text. Unlike nlohmann::json::parse it rejects duplicate keys (the second one would
// silently win) and reports syntax errors and numbers that overflow a double with a line and
// column computed from the text. Throws ScenarioError.
Json parseStrictJson(const std::string& text, const std::string& file);

// "pointer/key" with '~' and '/' escaped as RFC 6901 requires.
std::string appendJsonPointer(const std::string& pointer, std::string_view key);

// How a value reads in an error message: `-1`, `2.5`, `"ten" (string)`, `an object`, ...
std::string describeJsonValue(const Json& value);

// Shortest round-trip text of a double; integral values print without exponent or ".0".
std::string formatNumber(double value);

// Optimal-string-alignment distance: insertions, deletions, substitutions and adjacent
// transpositions ("frmaes" -> "frames" is 1) each cost 1.
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate closest to `word` within edit distance 2 (the first on ties), or nullopt.
std::optional<std::string> closestMatch(std::string_view word,
                                        const std::vector<std::string>& candidates);

// An interval on the real line; each end may be open, closed or absent (infinite).
struct NumberRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false;
    bool max_open = false;

    static NumberRange any() { return {}; }
    static NumberRange atLeast(double lo) { return {lo, kInf, false, false}; }
    static NumberRange greaterThan(double lo) { return {lo, kInf, true, false}; }
    static NumberRange closed(double lo, double hi) { return {lo, hi, false, false}; }
    static NumberRange open(double lo, double hi) { return {lo, hi, true, true}; }
    static NumberRange openClosed(double lo, double hi) { return {lo, hi, true, false}; }

    // False for NaN and infinities, whatever the bounds.
    bool contains(double value) const;
    // "a number > 0", "a number in (0, 180)", "a finite number", ...
    std::string describe() const;

  private:
    static constexpr double kInf = std::numeric_limits<double>::infinity();
};

class JsonObjectReader;
class JsonArrayReader;

// One value at a known pointer, converted to a C++ type on request.
class JsonValueReader {
  public:
    JsonValueReader(const Json& value, std::string pointer, std::string file);

    const Json& json() const { return *value_; }
    const std::string& pointer() const { return pointer_; }
    const std::string& file() const { return file_; }

    double asNumber(const NumberRange& range = {}) const;
    // Accepts integral numbers only (2.5 is an error, 3.0 and 1e6 are fine: JSON itself does not
    // distinguish them from 3 and 1000000).
    uint64_t asUnsigned(uint64_t min = 0, uint64_t max = UINT64_MAX) const;
    bool asBool() const;
    std::string asString() const;
    // One of `allowed`, with a suggestion when the text is close to one of them.
    std::string asEnum(const std::vector<std::string>& allowed) const;
    // [x, y, z], three finite numbers.
    glm::dvec3 asVec3() const;
    // [min, max]: two numbers in `element`, min <= max.
    std::pair<double, double> asRange(const NumberRange& element = {}) const;
    JsonObjectReader asObject() const;
    JsonArrayReader asArray() const;

    [[noreturn]] void fail(const std::string& message) const;
    // "expected <what>, got <this value>".
    [[noreturn]] void failExpected(const std::string& what) const;

  private:
    const Json* value_;
    std::string pointer_;
    std::string file_;
};

// An object whose keys are read by name; call finish() after the last read.
class JsonObjectReader {
  public:
    // Throws unless `value` is an object.
    JsonObjectReader(const Json& value, std::string pointer, std::string file);

    const std::string& pointer() const { return pointer_; }
    const std::string& file() const { return file_; }
    std::string pointerOf(std::string_view key) const { return appendJsonPointer(pointer_, key); }

    // Each accessor marks `key` as allowed, whether or not it is present.
    bool has(std::string_view key);
    std::optional<JsonValueReader> optional(std::string_view key);
    // Throws "missing required key" when absent (hinting at a present key that looks like a typo).
    JsonValueReader required(std::string_view key);

    double number(std::string_view key, double fallback, const NumberRange& range = {});
    double requiredNumber(std::string_view key, const NumberRange& range = {});
    uint64_t unsignedInteger(std::string_view key, uint64_t fallback, uint64_t min = 0,
                             uint64_t max = UINT64_MAX);
    uint64_t requiredUnsignedInteger(std::string_view key, uint64_t min = 0,
                                     uint64_t max = UINT64_MAX);
    bool boolean(std::string_view key, bool fallback);
    std::string string(std::string_view key, const std::string& fallback);
    std::string enumeration(std::string_view key, const std::vector<std::string>& allowed,
                            const std::string& fallback);
    std::string requiredEnumeration(std::string_view key, const std::vector<std::string>& allowed);
    glm::dvec3 vec3(std::string_view key, const glm::dvec3& fallback);
    glm::dvec3 requiredVec3(std::string_view key);
    std::pair<double, double> range(std::string_view key, std::pair<double, double> fallback,
                                    const NumberRange& element = {});
    JsonObjectReader object(std::string_view key);
    std::optional<JsonObjectReader> optionalObject(std::string_view key);
    JsonArrayReader array(std::string_view key);
    std::optional<JsonArrayReader> optionalArray(std::string_view key);

    // An error about `key` (present or not), at its pointer.
    [[noreturn]] void fail(std::string_view key, const std::string& message) const;
    // An error about the object as a whole, at its own pointer.
    [[noreturn]] void failHere(const std::string& message) const;

    // Throws on the first key that no accessor asked for.
    void finish() const;

  private:
    void allow(std::string_view key);

    const Json* value_;
    std::string pointer_;
    std::string file_;
    std::vector<std::string> allowed_;  // in the order asked, for the "allowed keys" list
};

class JsonArrayReader {
  public:
    // Throws unless `value` is an array.
    JsonArrayReader(const Json& value, std::string pointer, std::string file);

    const std::string& pointer() const { return pointer_; }
    std::size_t size() const { return value_->size(); }
    JsonValueReader at(std::size_t index) const;
    // Throws "expected an array of at least N <what>" when shorter.
    void requireAtLeast(std::size_t count, const std::string& what) const;

  private:
    const Json* value_;
    std::string pointer_;
    std::string file_;
};

}  // namespace occsim
