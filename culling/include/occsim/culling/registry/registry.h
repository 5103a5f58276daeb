// The open registry of cullers, the host's side: the program's registry of rows
// (declaration/culler_row.h: what a culler, built-in or plugin, fills in), lookups by name,
// making a culler from its row and a run's options, and the checks of a row. Built-in cullers
// register the same way as a plugin's (builtin_cullers.cpp: one line each), so everything that
// lists, builds, sweeps or tunes cullers (the scenario parser, `occsim bench`, the viewer, occtune,
// the docs' tables) reads this registry and nothing else. A plugin never includes this header.
#pragma once

#include <deque>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "occsim/culling/contract/cost_model.h"
#include "occsim/culling/contract/culler.h"
#include "occsim/culling/declaration/culler_row.h"
#include "occsim/culling/declaration/options.h"
#include "occsim/culling/registry/culler_options.h"

namespace occsim {

// Empty when `values` (of `culler`'s descriptor) are valid: each in its range, then the validate
// hook. Else "<key>: expected ..., got ..." or the hook's line.
std::string checkOptionValues(const CullerRow& culler, const OptionValues& values);

// The names of the DeviceFeature bits in `features`, comma separated ("conditional rendering").
std::string deviceFeatureNames(uint32_t features);
// Throws RegistryError when `culler` needs a capability (device_needs) that a device with
// `available` features lacks: "culler 'NAME' needs FEATURE, which this device does not offer".
void requireDeviceFeatures(const CullerRow& culler, uint32_t available);

class CullerRegistry {
  public:
    // Checks the row (name, traits, descriptor, factory) and adds it after the others. Throws
    // RegistryError: a name already taken, an invalid name or descriptor, no factory, a second
    // speedup reference, an oracle that claims to issue queries.
    const CullerRow& add(CullerRow traits);
    // The checks of add(), without adding: throws what add() would.
    void check(const CullerRow& traits) const;

    // In registration order: built-ins first, in the order tables list them, then plugins'.
    const std::vector<const CullerRow*>& all() const { return order_; }
    const CullerRow* find(std::string_view name) const;

  private:
    std::deque<CullerRow> rows_;  // a deque: pointers stay valid as rows are added
    std::vector<const CullerRow*> order_;
};

// The program's registry, with the built-in cullers registered on first use.
CullerRegistry& cullerRegistry();

// Shorthands over cullerRegistry().
const std::vector<const CullerRow*>& cullerRows();
std::vector<std::string> cullerNames();
const CullerRow* findCuller(std::string_view name);  // nullptr when unknown
const CullerRow& speedupReference();                 // frustum culling
std::string cullerNameList();                        // "vfc, stop-and-wait, ..."

// The culler, made by its factory from its own values in `options`. A plugin's factory that
// throws is reported as a RegistryError naming the plugin's file and the culler.
std::unique_ptr<Culler> makeCuller(const CullerRow& algorithm, const CullerOptions& options);
// The factory called with every failure (an exception, no culler) turned into a RegistryError
// "culler 'NAME': its factory ...": what makeCuller reports for a plugin, and what the plugin
// loader checks each row's defaults with.
std::unique_ptr<Culler> makeCheckedCuller(const CullerRow& algorithm, const OptionValues& values,
                                          const CostModel& costs);

}  // namespace occsim
