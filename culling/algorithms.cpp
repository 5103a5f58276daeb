#include "culling/algorithms.h"

#include "culling/async_culler.h"
#include "culling/basic_cullers.h"
#include "culling/chc_culler.h"
#include "culling/chcpp_culler.h"
#include "culling/statistical_culler.h"

#include <array>

namespace occsim {
namespace {

using F = AlgorithmFamily;

// name, summary, family, conservative, issues_queries, oracle, speedup_reference
constexpr std::array kAlgorithms = {
    AlgorithmTraits{"vfc", "view-frustum culling only (the reference)", F::Vfc, true, false, false,
                    true},
    AlgorithmTraits{"stop-and-wait", "hierarchical queries, each result awaited",
                    F::StopAndWait, true, true, false, false},
    AlgorithmTraits{"statistical", "Kovalcik & Sochor 2005, as published", F::Statistical, true,
                    true, false, false},
    AlgorithmTraits{"statistical+",
                    "Kovalcik & Sochor with ready answers, virtual leaves, a cost model, "
                    "re-query by distance and a frustum fallback",
                    F::StatisticalPlus, true, true, false, false},
    AlgorithmTraits{"chc", "coherent hierarchical culling (Bittner et al. 2004)", F::Chc, true,
                    true, false, false},
    AlgorithmTraits{"chc++", "CHC++ (Mattausch et al. 2008)", F::Chcpp, true, true, false, false},
    AlgorithmTraits{"async", "one asynchronous query per object (not conservative)", F::Async,
                    false, true, false, false},
    AlgorithmTraits{"ideal", "draws what ground truth saw (the oracle)", F::Ideal, true, false,
                    true, false},
};

}  // namespace

std::span<const AlgorithmTraits> algorithms() { return kAlgorithms; }

const std::vector<std::string>& algorithmNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const AlgorithmTraits& a : kAlgorithms) out.emplace_back(a.name);
        return out;
    }();
    return names;
}

const AlgorithmTraits* findAlgorithm(std::string_view name) {
    for (const AlgorithmTraits& a : kAlgorithms) {
        if (a.name == name) return &a;
    }
    return nullptr;
}

const AlgorithmTraits& speedupReference() {
    for (const AlgorithmTraits& a : kAlgorithms) {
        if (a.speedup_reference) return a;
    }
    return kAlgorithms.front();
}

std::string algorithmNameList() {
    std::string out;
    for (const AlgorithmTraits& a : kAlgorithms) out += (out.empty() ? "" : ", ") + std::string(a.name);
    return out;
}

const StatisticalOptions* statisticalOptionsOf(const AlgorithmTraits& algorithm,
                                               const CullerOptions& options) {
    switch (algorithm.family) {
        case F::Statistical: return &options.statistical;
        case F::StatisticalPlus: return &options.statistical_plus;
        default: return nullptr;
    }
}

std::unique_ptr<Culler> makeCuller(const AlgorithmTraits& algorithm, const CullerOptions& options) {
    switch (algorithm.family) {
        case F::Vfc: return std::make_unique<VfcCuller>();
        case F::StopAndWait: return std::make_unique<StopAndWaitCuller>();
        case F::Statistical:
        case F::StatisticalPlus:
            return std::make_unique<StatisticalCuller>(*statisticalOptionsOf(algorithm, options),
                                                       options.cost_model, algorithm.name);
        case F::Chc: return std::make_unique<ChcCuller>(options.chc);
        case F::Chcpp: return std::make_unique<ChcppCuller>(options.chcpp);
        case F::Async: return std::make_unique<AsyncCuller>(options.async);
        case F::Ideal: return std::make_unique<IdealCuller>();
    }
    return nullptr;
}

}  // namespace occsim
