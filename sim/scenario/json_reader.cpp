#include "sim/scenario/json_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

namespace occsim {

namespace {

constexpr std::size_t kMaxSuggestionDistance = 2;
constexpr std::size_t kMaxQuotedLength = 60;  // longer strings are shortened in messages

// 1-based line and column of the byte at `offset`; the column counts UTF-8 characters, not bytes,
// so it matches what an editor shows.
std::pair<std::size_t, std::size_t> lineAndColumn(const std::string& text, std::size_t offset) {
    offset = std::min(offset, text.size());
    std::size_t line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    }
    std::size_t column = 1;
    for (std::size_t i = line_start; i < offset; ++i) {
        const auto byte = static_cast<unsigned char>(text[i]);
        if ((byte & 0xC0u) != 0x80u) ++column;  // skip UTF-8 continuation bytes
    }
    return {line, column};
}

// nlohmann reports how many characters it read; the offending one is the last of them, or, with
// `token_length`, the token of that many characters that ends there.
std::string atLineColumn(const std::string& text, std::size_t chars_read,
                         std::size_t token_length = 1) {
    const std::size_t offset = chars_read >= token_length ? chars_read - token_length : 0;
    const auto [line, column] = lineAndColumn(text, offset);
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's what() is "[json.exception.parse_error.101] parse error at line 3, column 9: <why>";
// keep only <why> because we compute the position ourselves.
std::string parseErrorReason(const char* what) {
    const std::string text = what;
    const auto at = text.find("parse error");
    const auto colon = text.find(": ", at == std::string::npos ? 0 : at);
    return colon == std::string::npos ? text : text.substr(colon + 2);
}

// nlohmann's SAX interface, building the DOM ourselves so that we know where we are: needed to
// reject duplicate keys and to name the value whose number overflowed.
class StrictDomBuilder {
  public:
    StrictDomBuilder(const std::string& text, const std::string& file) : text_(text), file_(file) {}

    Json take() { return std::move(root_); }
    const std::optional<ScenarioError>& error() const { return error_; }

    bool null() { return place(Json(nullptr)) != nullptr; }
    bool boolean(bool value) { return place(Json(value)) != nullptr; }
    bool number_integer(Json::number_integer_t value) { return place(Json(value)) != nullptr; }
    bool number_unsigned(Json::number_unsigned_t value) { return place(Json(value)) != nullptr; }
    bool number_float(Json::number_float_t value, const Json::string_t& /*text*/) {
        return place(Json(value)) != nullptr;
    }
    bool string(Json::string_t& value) { return place(Json(std::move(value))) != nullptr; }
    bool binary(Json::binary_t& value) { return place(Json::binary(std::move(value))) != nullptr; }

    bool start_object(std::size_t /*elements*/) { return open(Json::object()); }
    bool start_array(std::size_t /*elements*/) { return open(Json::array()); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(Json::string_t& key) {
        Frame& top = frames_.back();
        top.key = key;
        if (top.container->contains(key)) {
            error_.emplace(file_, currentPointer(),
                           "duplicate key '" + key +
                               "' (the later value would silently replace "
                               "the earlier one)");
            return false;
        }
        return true;
    }

    bool parse_error(std::size_t chars_read, const std::string& last_token,
                     const Json::exception& ex) {
        constexpr int kNumberOverflow = 406;  // out_of_range.406: the number overflows a double
        if (ex.id == kNumberOverflow) {
            error_.emplace(file_, currentPointer(),
                           "expected a finite number, got " + last_token +
                               ", which overflows a double (at " +
                               atLineColumn(text_, chars_read, last_token.size()) + ")");
        } else {
            error_.emplace(file_, "",
                           "invalid JSON at " + atLineColumn(text_, chars_read) + ": " +
                               parseErrorReason(ex.what()));
        }
        return false;
    }

  private:
    struct Frame {
        Json* container;
        std::string key;  // objects: the key whose value is being read
    };

    // Stores a finished value where the parser is and returns where it went.
    Json* place(Json value) {
        if (frames_.empty()) {
            root_ = std::move(value);
            return &root_;
        }
        Frame& top = frames_.back();
        if (top.container->is_array()) {
            top.container->push_back(std::move(value));
            return &top.container->back();
        }
        Json& slot = (*top.container)[top.key];
        slot = std::move(value);
        return &slot;
    }

    bool open(Json empty_container) {
        frames_.push_back(Frame{place(std::move(empty_container)), {}});
        return true;
    }

    bool close() {
        frames_.pop_back();
        return true;
    }

    // The pointer of the value the parser is reading now.
    std::string currentPointer() const {
        std::string pointer;
        for (std::size_t i = 0; i < frames_.size(); ++i) {
            const Json& container = *frames_[i].container;
            if (container.is_object()) {
                pointer = appendJsonPointer(pointer, frames_[i].key);
                continue;
            }
            // An enclosing array already holds the child being read; the innermost one does not
            // hold the value being read yet.
            const bool innermost = i + 1 == frames_.size();
            const std::size_t index = innermost ? container.size() : container.size() - 1;
            pointer = appendJsonPointer(pointer, std::to_string(index));
        }
        return pointer;
    }

    const std::string& text_;
    const std::string& file_;
    Json root_;
    std::vector<Frame> frames_;
    std::optional<ScenarioError> error_;
};

std::string quoteAll(const std::vector<std::string>& words, const char* quote) {
    std::string out;
    for (const std::string& word : words) {
        if (!out.empty()) out += ", ";
        out += quote + word + quote;
    }
    return out;
}

std::string describeInterval(const NumberRange& r) {
    return std::string("in ") + (r.min_open ? "(" : "[") + formatNumber(r.min) + ", " +
           formatNumber(r.max) + (r.max_open ? ")" : "]");
}

std::string describeUnsignedRange(uint64_t min, uint64_t max) {
    if (max == UINT64_MAX) return "an integer >= " + std::to_string(min);
    return "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
}

// The exact uint64 a JSON number denotes, or nullopt when it is negative, fractional or too big.
std::optional<uint64_t> exactUnsigned(const Json& value) {
    if (value.is_number_unsigned()) return value.get<uint64_t>();
    if (value.is_number_integer()) {
        const auto v = value.get<int64_t>();
        if (v < 0) return std::nullopt;
        return static_cast<uint64_t>(v);
    }
    if (value.is_number_float()) {
        const double d = value.get<double>();
        constexpr double kTwoTo64 = 18446744073709551616.0;
        if (!std::isfinite(d) || d < 0.0 || d >= kTwoTo64 || std::trunc(d) != d) {
            return std::nullopt;
        }
        return static_cast<uint64_t>(d);
    }
    return std::nullopt;
}

}  // namespace

Json parseStrictJson(const std::string& text, const std::string& file) {
    StrictDomBuilder builder(text, file);
    const bool ok = Json::sax_parse(text, &builder, Json::input_format_t::json, /*strict=*/true,
                                    /*ignore_comments=*/false);
    if (builder.error()) throw *builder.error();
    if (!ok) throw ScenarioError(file, "", "invalid JSON");  // defensive: every failure sets error
    return builder.take();
}

std::string appendJsonPointer(const std::string& pointer, std::string_view key) {
    std::string out = pointer + "/";
    for (const char c : key) {
        if (c == '~') {
            out += "~0";
        } else if (c == '/') {
            out += "~1";
        } else {
            out += c;
        }
    }
    return out;
}

std::string formatNumber(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    // Integral values print as integers ("10000000", not "1e+07") while they are exact.
    if (std::trunc(value) == value && std::fabs(value) < 1e15) {
        return std::to_string(static_cast<long long>(value));
    }
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return std::string(buffer, result.ptr);
}

std::string describeJsonValue(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return value.dump() + " (boolean)";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
            return value.dump();
        case Json::value_t::number_float:
            return formatNumber(value.get<double>());
        case Json::value_t::string: {
            std::string text = value.dump();
            if (text.size() > kMaxQuotedLength) text = text.substr(0, kMaxQuotedLength) + "...\"";
            return text + " (string)";
        }
        case Json::value_t::array:
            return "an array of " + std::to_string(value.size()) + " element" +
                   (value.size() == 1 ? "" : "s");
        case Json::value_t::object:
            return "an object";
        case Json::value_t::binary:
        case Json::value_t::discarded:
            break;
    }
    return "a value of type " + std::string(value.type_name());
}

std::size_t editDistance(std::string_view a, std::string_view b) {
    // Three rows of the dynamic-programming table: the transposition case looks two rows back.
    std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
                current[j] = std::min(current[j], before[j - 2] + 1);
            }
        }
        std::swap(before, previous);
        std::swap(previous, current);
    }
    return previous[b.size()];
}

std::optional<std::string> closestMatch(std::string_view word,
                                        const std::vector<std::string>& candidates) {
    std::optional<std::string> best;
    std::size_t best_distance = kMaxSuggestionDistance + 1;
    for (const std::string& candidate : candidates) {
        const std::size_t distance = editDistance(word, candidate);
        if (distance < best_distance) {
            best_distance = distance;
            best = candidate;
        }
    }
    return best;
}

// --- NumberRange ---------------------------------------------------------------------------

bool NumberRange::contains(double value) const {
    if (!std::isfinite(value)) return false;
    const bool above_min = min_open ? value > min : value >= min;
    const bool below_max = max_open ? value < max : value <= max;
    return above_min && below_max;
}

std::string NumberRange::describe() const {
    const bool has_min = std::isfinite(min);
    const bool has_max = std::isfinite(max);
    if (has_min && has_max) return "a number " + describeInterval(*this);
    if (has_min) return std::string("a number ") + (min_open ? "> " : ">= ") + formatNumber(min);
    if (has_max) return std::string("a number ") + (max_open ? "< " : "<= ") + formatNumber(max);
    return "a finite number";
}

// --- JsonValueReader -----------------------------------------------------------------------

JsonValueReader::JsonValueReader(const Json& value, std::string pointer, std::string file)
    : value_(&value), pointer_(std::move(pointer)), file_(std::move(file)) {}

void JsonValueReader::fail(const std::string& message) const {
    throw ScenarioError(file_, pointer_, message);
}

void JsonValueReader::failExpected(const std::string& what) const {
    fail("expected " + what + ", got " + describeJsonValue(*value_));
}

double JsonValueReader::asNumber(const NumberRange& range) const {
    // Non-finite numbers cannot come from JSON text but can from a Json built in code.
    if (!value_->is_number() || !range.contains(value_->get<double>())) {
        failExpected(range.describe());
    }
    return value_->get<double>();
}

uint64_t JsonValueReader::asUnsigned(uint64_t min, uint64_t max) const {
    const std::optional<uint64_t> value = exactUnsigned(*value_);
    if (!value || *value < min || *value > max) failExpected(describeUnsignedRange(min, max));
    return *value;
}

bool JsonValueReader::asBool() const {
    if (!value_->is_boolean()) failExpected("true or false");
    return value_->get<bool>();
}

std::string JsonValueReader::asString() const {
    if (!value_->is_string()) failExpected("a string");
    return value_->get<std::string>();
}

std::string JsonValueReader::asEnum(const std::vector<std::string>& allowed) const {
    if (value_->is_string()) {
        const auto& text = value_->get_ref<const std::string&>();
        if (std::find(allowed.begin(), allowed.end(), text) != allowed.end()) return text;
        if (const auto suggestion = closestMatch(text, allowed)) {
            failExpected("one of " + quoteAll(allowed, "\"") + " (did you mean \"" + *suggestion +
                         "\"?)");
        }
    }
    failExpected("one of " + quoteAll(allowed, "\""));
}

glm::dvec3 JsonValueReader::asVec3() const {
    if (!value_->is_array() || value_->size() != 3) failExpected("an array [x, y, z] of 3 numbers");
    const JsonArrayReader elements(*value_, pointer_, file_);
    // Points end up as 32-bit floats (the world, the camera, the GPU): a coordinate finite as a
    // double but beyond float range would silently become infinite there.
    auto coordinate = [&](size_t i) {
        const JsonValueReader at = elements.at(i);
        const double v = at.asNumber();
        if (!std::isfinite(static_cast<float>(v))) {
            at.failExpected("a coordinate that fits a 32-bit float (|x| < 3.4e38)");
        }
        return v;
    };
    return {coordinate(0), coordinate(1), coordinate(2)};
}

std::pair<double, double> JsonValueReader::asRange(const NumberRange& element) const {
    if (!value_->is_array() || value_->size() != 2) {
        failExpected("an array [min, max] of 2 numbers");
    }
    const JsonArrayReader elements(*value_, pointer_, file_);
    const double lo = elements.at(0).asNumber(element);
    const double hi = elements.at(1).asNumber(element);
    if (lo > hi) failExpected("[min, max] with min <= max");
    return {lo, hi};
}

JsonObjectReader JsonValueReader::asObject() const {
    return JsonObjectReader(*value_, pointer_, file_);
}

JsonArrayReader JsonValueReader::asArray() const {
    return JsonArrayReader(*value_, pointer_, file_);
}

// --- JsonObjectReader ----------------------------------------------------------------------

JsonObjectReader::JsonObjectReader(const Json& value, std::string pointer, std::string file)
    : value_(&value), pointer_(std::move(pointer)), file_(std::move(file)) {
    if (!value.is_object()) JsonValueReader(value, pointer_, file_).failExpected("an object");
}

void JsonObjectReader::allow(std::string_view key) {
    if (std::find(allowed_.begin(), allowed_.end(), key) == allowed_.end()) {
        allowed_.emplace_back(key);
    }
}

bool JsonObjectReader::has(std::string_view key) {
    allow(key);
    return value_->contains(key);
}

std::optional<JsonValueReader> JsonObjectReader::optional(std::string_view key) {
    if (!has(key)) return std::nullopt;
    return JsonValueReader(value_->find(key).value(), pointerOf(key), file_);
}

JsonValueReader JsonObjectReader::required(std::string_view key) {
    if (auto value = optional(key)) return *value;
    // A missing required key is most often a misspelt one; name it here, because finish() (which
    // would) only runs after every required key was found.
    std::string message = "missing required key '" + std::string(key) + "'";
    for (const auto& item : value_->items()) {
        if (item.key() != key && editDistance(item.key(), key) <= kMaxSuggestionDistance) {
            message += " (is '" + item.key() + "' a misspelling of it?)";
            break;
        }
    }
    fail(key, message);
}

double JsonObjectReader::number(std::string_view key, double fallback, const NumberRange& range) {
    const auto value = optional(key);
    return value ? value->asNumber(range) : fallback;
}

double JsonObjectReader::requiredNumber(std::string_view key, const NumberRange& range) {
    return required(key).asNumber(range);
}

uint64_t JsonObjectReader::unsignedInteger(std::string_view key, uint64_t fallback, uint64_t min,
                                           uint64_t max) {
    const auto value = optional(key);
    return value ? value->asUnsigned(min, max) : fallback;
}

uint64_t JsonObjectReader::requiredUnsignedInteger(std::string_view key, uint64_t min,
                                                   uint64_t max) {
    return required(key).asUnsigned(min, max);
}

bool JsonObjectReader::boolean(std::string_view key, bool fallback) {
    const auto value = optional(key);
    return value ? value->asBool() : fallback;
}

std::string JsonObjectReader::string(std::string_view key, const std::string& fallback) {
    const auto value = optional(key);
    return value ? value->asString() : fallback;
}

std::string JsonObjectReader::enumeration(std::string_view key,
                                          const std::vector<std::string>& allowed,
                                          const std::string& fallback) {
    const auto value = optional(key);
    return value ? value->asEnum(allowed) : fallback;
}

std::string JsonObjectReader::requiredEnumeration(std::string_view key,
                                                  const std::vector<std::string>& allowed) {
    return required(key).asEnum(allowed);
}

glm::dvec3 JsonObjectReader::vec3(std::string_view key, const glm::dvec3& fallback) {
    const auto value = optional(key);
    return value ? value->asVec3() : fallback;
}

glm::dvec3 JsonObjectReader::requiredVec3(std::string_view key) { return required(key).asVec3(); }

std::pair<double, double> JsonObjectReader::range(std::string_view key,
                                                  std::pair<double, double> fallback,
                                                  const NumberRange& element) {
    const auto value = optional(key);
    return value ? value->asRange(element) : fallback;
}

JsonObjectReader JsonObjectReader::object(std::string_view key) { return required(key).asObject(); }

std::optional<JsonObjectReader> JsonObjectReader::optionalObject(std::string_view key) {
    const auto value = optional(key);
    if (!value) return std::nullopt;
    return value->asObject();
}

JsonArrayReader JsonObjectReader::array(std::string_view key) { return required(key).asArray(); }

std::optional<JsonArrayReader> JsonObjectReader::optionalArray(std::string_view key) {
    const auto value = optional(key);
    if (!value) return std::nullopt;
    return value->asArray();
}

void JsonObjectReader::fail(std::string_view key, const std::string& message) const {
    throw ScenarioError(file_, pointerOf(key), message);
}

void JsonObjectReader::failHere(const std::string& message) const {
    throw ScenarioError(file_, pointer_, message);
}

void JsonObjectReader::finish() const {
    for (const auto& item : value_->items()) {
        const std::string& key = item.key();
        if (std::find(allowed_.begin(), allowed_.end(), key) != allowed_.end()) continue;
        std::string message = "unknown key '" + key + "'";
        if (const auto suggestion = closestMatch(key, allowed_)) {
            message += "; did you mean '" + *suggestion + "'?";
        } else if (allowed_.empty()) {
            message += "; this object takes no keys";
        } else {
            message += "; allowed keys here: " + quoteAll(allowed_, "'");
        }
        fail(key, message);
    }
}

// --- JsonArrayReader -----------------------------------------------------------------------

JsonArrayReader::JsonArrayReader(const Json& value, std::string pointer, std::string file)
    : value_(&value), pointer_(std::move(pointer)), file_(std::move(file)) {
    if (!value.is_array()) JsonValueReader(value, pointer_, file_).failExpected("an array");
}

JsonValueReader JsonArrayReader::at(std::size_t index) const {
    return JsonValueReader((*value_)[index], appendJsonPointer(pointer_, std::to_string(index)),
                           file_);
}

void JsonArrayReader::requireAtLeast(std::size_t count, const std::string& what) const {
    if (value_->size() >= count) return;
    JsonValueReader(*value_, pointer_, file_)
        .failExpected("an array of at least " + std::to_string(count) + " " + what);
}

}  // namespace occsim
