#include "culling/culler_factory.h"

#include "culling/basic_cullers.h"

namespace occsim {

const std::vector<std::string>& cullerNames() {
    static const std::vector<std::string> names = {"vfc",   "stop-and-wait", "statistical", "chc",
                                                   "chc++", "async",         "ideal"};
    return names;
}

std::unique_ptr<Culler> makeCuller(std::string_view name, const CullerOptions& options) {
    if (name == "vfc") return std::make_unique<VfcCuller>();
    if (name == "stop-and-wait") return std::make_unique<StopAndWaitCuller>();
    if (name == "statistical") return std::make_unique<StatisticalCuller>(options.statistical);
    if (name == "chc") return std::make_unique<ChcCuller>(options.chc);
    if (name == "chc++") return std::make_unique<ChcppCuller>(options.chcpp);
    if (name == "async") return std::make_unique<AsyncCuller>(options.async);
    if (name == "ideal") return std::make_unique<IdealCuller>();
    return nullptr;
}

}  // namespace occsim
