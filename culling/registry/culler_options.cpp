#include "occsim/culling/registry/culler_options.h"

#include "occsim/culling/registry/registry.h"

namespace occsim {

OptionValues CullerOptions::of(const CullerRow& culler) const {
    if (auto it = given.find(culler.name); it != given.end()) return it->second;
    return OptionValues(culler.options);
}

OptionValues& CullerOptions::edit(const CullerRow& culler) {
    auto it = given.find(culler.name);
    if (it == given.end()) it = given.emplace(culler.name, OptionValues(culler.options)).first;
    return it->second;
}

bool CullerOptions::isValid(std::string* error) const {
    if (!cost_model.isValid(error)) return false;
    for (const auto& [name, model] : cost_model_of) {
        if (!model.isValid(error)) return false;
    }
    for (const auto& [name, values] : given) {
        const CullerRow* culler = findCuller(name);
        const std::string why = culler ? checkOptionValues(*culler, values)
                                       : std::string("no culler of this name is registered");
        if (!why.empty()) {
            if (error) *error = name + ": " + why;
            return false;
        }
    }
    return true;
}

}  // namespace occsim
