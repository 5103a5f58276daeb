#include "occsim/culling/registry/registry.h"

#include <utility>

#include "occsim/culling/registry/culler_options.h"

namespace occsim {

// builtin_cullers.cpp: the built-in rows, one registration line each.
void registerBuiltinCullers(CullerRegistry& registry);

namespace {

bool validName(const std::string& name) {
    if (name.empty() || name.size() > 64) return false;
    for (char c : name) {
        const bool ok =
            (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '+';
        if (!ok) return false;
    }
    return true;
}

}  // namespace

std::string deviceFeatureNames(uint32_t features) {
    static constexpr std::pair<uint32_t, const char*> kNames[] = {
        {kConditionalRendering, "conditional rendering"},
        {kDepthPyramid, "a depth pyramid (compute shaders)"},
        {kGpuDrivenDraws, "GPU-driven draws (multi-draw indirect and storage buffers)"},
        {kBoxRaster, "box rasterisation (storage buffers written by fragment shaders)"},
    };
    // "a", "a and b", "a, b and c".
    std::vector<const char*> names;
    for (const auto& [bit, name] : kNames) {
        if (features & bit) names.push_back(name);
    }
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) {
        if (i > 0) out += i + 1 == names.size() ? " and " : ", ";
        out += names[i];
    }
    return out;
}

void requireDeviceFeatures(const CullerRow& culler, uint32_t available) {
    const uint32_t missing = culler.device_needs & ~available;
    if (missing == 0) return;
    throw RegistryError("culler '" + culler.name + "' needs " + deviceFeatureNames(missing) +
                        ", which this device does not offer");
}

std::string checkOptionValues(const CullerRow& culler, const OptionValues& values) {
    const OptionsDescriptor& d = culler.options;
    if (values.values().size() != d.size()) {
        return culler.name + ": option values do not match its descriptor";
    }
    for (size_t i = 0; i < d.size(); ++i) {
        if (const std::string why = checkOptionValue(d[i], values.values()[i]); !why.empty()) {
            return d[i].key + ": " + why;
        }
    }
    if (culler.validate) return culler.validate(values);
    return {};
}

void CullerRegistry::check(const CullerRow& traits) const {
    const std::string who = "culler '" + traits.name + "'";
    if (!validName(traits.name)) {
        throw RegistryError(who + ": a name is 1 to 64 characters of a-z 0-9 _ + -");
    }
    if (find(traits.name)) {
        const CullerRow& taken = *find(traits.name);
        throw RegistryError(who + ": the name is already taken (by " +
                            (taken.source.empty() ? std::string("a built-in culler")
                                                  : "the plugin " + taken.source) +
                            ")");
    }
    if (traits.summary.empty()) throw RegistryError(who + ": no summary line");
    if (!traits.factory) throw RegistryError(who + ": no factory");
    if (traits.oracle && traits.issues_queries) {
        throw RegistryError(who + ": an oracle decides from ground truth and issues no queries");
    }
    if (traits.speedup_reference) {
        for (const CullerRow* a : order_) {
            if (a->speedup_reference) {
                throw RegistryError(who + ": '" + a->name + "' is already the speedup reference");
            }
        }
    }
    if (const std::string why = checkDescriptor(traits.options); !why.empty()) {
        throw RegistryError(who + ": invalid options descriptor: " + why);
    }
    // Its defaults must pass its own rules, or no run could use it.
    if (const std::string why = checkOptionValues(traits, OptionValues(traits.options));
        !why.empty()) {
        throw RegistryError(who + ": its default options are invalid: " + why);
    }
}

const CullerRow& CullerRegistry::add(CullerRow traits) {
    check(traits);
    rows_.push_back(std::move(traits));
    order_.push_back(&rows_.back());
    return rows_.back();
}

const CullerRow* CullerRegistry::find(std::string_view name) const {
    for (const CullerRow* a : order_) {
        if (a->name == name) return a;
    }
    return nullptr;
}

CullerRegistry& cullerRegistry() {
    static CullerRegistry* registry = [] {
        auto* r = new CullerRegistry;  // never destroyed: plugins' rows point into it until exit
        registerBuiltinCullers(*r);
        return r;
    }();
    return *registry;
}

const std::vector<const CullerRow*>& cullerRows() { return cullerRegistry().all(); }

std::vector<std::string> cullerNames() {
    std::vector<std::string> out;
    for (const CullerRow* a : cullerRows()) out.push_back(a->name);
    return out;
}

const CullerRow* findCuller(std::string_view name) { return cullerRegistry().find(name); }

const CullerRow& speedupReference() {
    for (const CullerRow* a : cullerRows()) {
        if (a->speedup_reference) return *a;
    }
    return *cullerRows().front();
}

std::string cullerNameList() {
    std::string out;
    for (const CullerRow* a : cullerRows()) out += (out.empty() ? "" : ", ") + a->name;
    return out;
}

std::unique_ptr<Culler> makeCheckedCuller(const CullerRow& algorithm, const OptionValues& values,
                                          const CostModel& costs) {
    const std::string who = "culler '" + algorithm.name + "': its factory";
    std::unique_ptr<Culler> culler;
    try {
        culler = algorithm.factory(CullerContext{algorithm.name, values, costs});
    } catch (const std::exception& e) {
        throw RegistryError(who + " threw: " + e.what());
    } catch (...) {
        throw RegistryError(who + " threw a non-standard exception");
    }
    if (!culler) throw RegistryError(who + " made no culler");
    return culler;
}

std::unique_ptr<Culler> makeCuller(const CullerRow& algorithm, const CullerOptions& options) {
    const OptionValues values = options.of(algorithm);
    if (algorithm.source.empty()) {
        return algorithm.factory(CullerContext{algorithm.name, values, options.cost_model});
    }
    try {
        return makeCheckedCuller(algorithm, values, options.cost_model);
    } catch (const RegistryError& e) {
        throw RegistryError(algorithm.source + ": " + e.what());
    }
}

}  // namespace occsim
