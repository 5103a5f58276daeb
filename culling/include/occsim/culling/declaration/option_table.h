// A culler's options struct bound to its descriptor: each row is an option's spec (options.h) and
// the struct member it sets, written together, so that an option is spelled once. The table yields
// the descriptor (each default read from a defaults struct) and reads a culler's values into its
// options struct by the rows' setters; no culler copies its options out by hand.
//
//   using O = ChcOptions;
//   const OptionTable<O> table = {
//       integerOption(OCCSIM_OPTION_MEMBER(O, visible_frames_skip), "frames", 0, 1000000, "t_av"),
//       numberOption(OptionMember{&O::base_time_s, "base_time"}, "s", 0.0, inf, "BASE_TIME"),
//   };
//   t.options = table.descriptor(O{});
//   O o = table.read(context.options);
//
// The key is the member's own name (OCCSIM_OPTION_MEMBER); a key that differs from it stands
// beside the member, on one line (OptionMember{&O::member, "key"}). A row's type follows its
// member's: booleanOption binds a bool, integerOption an integer type, numberOption a double.
// Header-only: it builds OptionSpec rows and calls the OptionValues API, so nothing of it
// crosses the plugin boundary and a plugin may use it as the built-ins do.
#pragma once

#include <concepts>
#include <functional>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "occsim/culling/declaration/options.h"

namespace occsim {

// A member of an options struct and the key it is read under.
template <class Options, class T>
struct OptionMember {
    T Options::*member;
    const char* key;
};
// Spelled out for compilers without deduction for aggregates (clang before 17: the fuzz preset).
template <class Options, class T>
OptionMember(T Options::*, const char*) -> OptionMember<Options, T>;

// The member `name` of `Options`, keyed by its own name.
#define OCCSIM_OPTION_MEMBER(Options, name) (::occsim::OptionMember{&Options::name, #name})

// An integer member type (a bool is a boolean option, not an integer one).
template <class T>
concept OptionInteger = std::integral<T> && !std::same_as<T, bool>;

// One option: its spec and the member it stands for. Values cross as doubles (options.h): a
// boolean as 0 or 1, an integer exactly.
template <class Options>
struct OptionRow {
    OptionSpec spec;  // default_value is the defaults struct's, filled in by descriptor()
    std::function<double(const Options&)> get;
    std::function<void(Options&, double)> set;
};

template <class Options>
OptionRow<Options> booleanOption(OptionMember<Options, bool> m, std::string doc) {
    return {booleanOption(m.key, false, std::move(doc)),
            [p = m.member](const Options& o) { return o.*p ? 1.0 : 0.0; },
            [p = m.member](Options& o, double v) { o.*p = v != 0.0; }};
}

template <class Options, OptionInteger T>
OptionRow<Options> integerOption(OptionMember<Options, T> m, std::string unit, double min,
                                 double max, std::string doc) {
    // A value in the range must fit the member, or the setter would wrap it.
    if (min < static_cast<double>(std::numeric_limits<T>::lowest()) ||
        max > static_cast<double>(std::numeric_limits<T>::max())) {
        throw std::logic_error(std::string("option '") + m.key +
                               "': its range does not fit its member's type");
    }
    return {integerOption(m.key, std::move(unit), min, max, min, std::move(doc)),
            [p = m.member](const Options& o) { return static_cast<double>(o.*p); },
            [p = m.member](Options& o, double v) { o.*p = static_cast<T>(v); }};
}

template <class Options>
OptionRow<Options> numberOption(OptionMember<Options, double> m, std::string unit, double min,
                                double max, std::string doc) {
    return {numberOption(m.key, std::move(unit), min, max, min, std::move(doc)),
            [p = m.member](const Options& o) { return o.*p; },
            [p = m.member](Options& o, double v) { o.*p = v; }};
}

// The row, tunable within [lo, hi]; with an off value; as an alternative to another key; acting
// on a scope (the same as options.h's, on a bound row).
template <class Options>
OptionRow<Options> tunable(OptionRow<Options> row, double lo, double hi) {
    row.spec = tunable(std::move(row.spec), lo, hi);
    return row;
}

template <class Options>
OptionRow<Options> switchable(OptionRow<Options> row, double off_value) {
    row.spec = switchable(std::move(row.spec), off_value);
    return row;
}

template <class Options>
OptionRow<Options> alternativeTo(OptionRow<Options> row, std::string other_key) {
    row.spec = alternativeTo(std::move(row.spec), std::move(other_key));
    return row;
}

template <class Options>
OptionRow<Options> actingOn(OptionRow<Options> row, OptionScope scope) {
    row.spec = actingOn(std::move(row.spec), scope);
    return row;
}

// A culler's options, one row each, in the order tables list them.
template <class Options>
class OptionTable {
  public:
    OptionTable(std::initializer_list<OptionRow<Options>> rows) : rows_(rows) {}
    explicit OptionTable(std::vector<OptionRow<Options>> rows) : rows_(std::move(rows)) {}

    const std::vector<OptionRow<Options>>& rows() const { return rows_; }

    // The registry's descriptor, each default read from `defaults`.
    OptionsDescriptor descriptor(const Options& defaults) const {
        OptionsDescriptor out;
        out.reserve(rows_.size());
        for (const OptionRow<Options>& row : rows_) {
            out.push_back(row.spec);
            out.back().default_value = row.get(defaults);
        }
        return out;
    }

    // `values` (of a descriptor with this table's keys) set on a default-constructed Options;
    // std::logic_error when a key is missing from them (options.h: OptionValues::number).
    Options read(const OptionValues& values) const {
        Options o{};
        for (const OptionRow<Options>& row : rows_) row.set(o, values.number(row.spec.key));
        return o;
    }

  private:
    std::vector<OptionRow<Options>> rows_;
};

}  // namespace occsim
