// A culler's options, described once: for each option its JSON key, type, unit, range, default,
// one line of documentation, and whether (and within which bounds) the tuner may tune it. The
// scenario parser, `--culling` files, `occsim bench --sweep`, occtune, the help texts and the
// options tables of docs/cullers.md all read this descriptor, so an option is spelled in one place.
//
// Values are held as doubles in descriptor order: booleans as 0 or 1, integers exactly (ranges of
// integer options stay within 2^53, where a double holds every integer).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace occsim {

enum class OptionType : uint8_t { Boolean, Integer, Number };

// What an option acts on: every frame's culling, or only the objects whose occluder role is
// chosen by size (an object the scene marks `always` or `never` an occluder ignores it). The tuner
// leaves out of its fit an option that nothing of the scene lets act.
enum class OptionScope : uint8_t { EveryObject, OccludersBySize };

// The largest integer a double holds exactly, the upper end of every integer option's range.
inline constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53

struct OptionSpec {
    std::string key;  // JSON key in the culler's options object, sweep and tuner name
    OptionType type = OptionType::Number;
    std::string unit;  // "s", "m", "frames", ... ("" for a plain number or a boolean)
    double min = 0.0;  // valid range, closed at both ends (booleans: [0, 1])
    double max = 0.0;
    double default_value = 0.0;
    std::string doc;  // one line: what the option does
    // The tuner may tune it, by default within [tune_min, tune_max] (inside [min, max]).
    bool tunable = false;
    double tune_min = 0.0;
    double tune_max = 0.0;
    // For an option that switches a mechanism of the culler on: the value that turns it off.
    // `occsim bench --ablate ALGO` runs the culler once with each such option at this value.
    std::optional<double> off_value;
    // Another option this one is an alternative to: a sweep or the tuner that sets this option to
    // a value other than its off value sets that one to its off value.
    std::string alternative_to;
    OptionScope scope = OptionScope::EveryObject;
};

using OptionsDescriptor = std::vector<OptionSpec>;

// Builders for descriptor rows, so that registrations read as a table.
OptionSpec booleanOption(std::string key, bool default_value, std::string doc);
OptionSpec integerOption(std::string key, std::string unit, double min, double max,
                         double default_value, std::string doc);
OptionSpec numberOption(std::string key, std::string unit, double min, double max,
                        double default_value, std::string doc);
// The same row, tunable within [lo, hi]; with an off value; as an alternative to another key.
OptionSpec tunable(OptionSpec spec, double lo, double hi);
OptionSpec switchable(OptionSpec spec, double off_value);
OptionSpec alternativeTo(OptionSpec spec, std::string other_key);
// The same row, acting only on `scope`.
OptionSpec actingOn(OptionSpec spec, OptionScope scope);

const char* optionTypeName(OptionType type);  // "boolean", "integer", "number"

// "an integer in [1, 32] (frames)", "a number in [0, 1]", "true or false": what a value must be.
std::string describeOptionRange(const OptionSpec& spec);

// Empty when `value` is valid for `spec` (finite, in range, integral where it must be); else
// "expected <range>, got <value>".
std::string checkOptionValue(const OptionSpec& spec, double value);

// Empty when the descriptor itself is sound: keys non-empty, unique and made of [a-z0-9_+-];
// ranges ordered and within the type's; defaults valid; tuning bounds inside the range and
// ordered; off values valid; alternatives naming another option. Else what is wrong.
std::string checkDescriptor(const OptionsDescriptor& descriptor);

// One culler's option values, in its descriptor's order.
class OptionValues {
  public:
    OptionValues() = default;
    // Every option at its default. The descriptor must outlive the values (registrations live
    // as long as the program).
    explicit OptionValues(const OptionsDescriptor& descriptor);

    const OptionsDescriptor& descriptor() const;
    std::span<const double> values() const { return values_; }

    // nullptr when the culler has no option of that key.
    const OptionSpec* find(std::string_view key) const;
    // The value of `key`; std::logic_error when there is no such option (a culler asking for an
    // option it did not declare is a programming error).
    double number(std::string_view key) const;
    bool flag(std::string_view key) const { return number(key) != 0.0; }
    uint32_t count(std::string_view key) const { return static_cast<uint32_t>(number(key)); }
    uint64_t integer(std::string_view key) const { return static_cast<uint64_t>(number(key)); }

    // Sets `key` without checks beyond its existence (std::logic_error otherwise); callers check
    // the value with checkOptionValue() first.
    void set(std::string_view key, double value);
    // set(), and an alternative of `key` goes to its off value when `value` is not `key`'s own.
    void setWithAlternatives(std::string_view key, double value);

    bool operator==(const OptionValues& other) const { return values_ == other.values_; }

  private:
    size_t indexOf(std::string_view key) const;

    const OptionsDescriptor* descriptor_ = nullptr;
    std::vector<double> values_;
};

// "%g"-style text of an option value as JSON writes it: true/false for booleans.
std::string formatOptionValue(const OptionSpec& spec, double value);

}  // namespace occsim
