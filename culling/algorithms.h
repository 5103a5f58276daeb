// The culling algorithms by name: what each one is, and the factory that makes it. This is the
// one place that says whether an algorithm is conservative, issues queries, or is an oracle; the
// rest of the program asks here instead of comparing names.
#pragma once

#include "culling/culler.h"
#include "culling/culler_options.h"

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace occsim {

// Which options struct of CullerOptions an algorithm reads (sweeps and the tuner use it to know
// which knobs apply).
enum class AlgorithmFamily : uint8_t {
    Vfc,
    StopAndWait,
    Statistical,      // CullerOptions::statistical (the paper as published)
    StatisticalPlus,  // CullerOptions::statistical_plus (the same culler, improvements on)
    Chc,
    Chcpp,
    Async,
    Ideal,
};

struct AlgorithmTraits {
    std::string_view name;
    std::string_view summary;  // one line, for help texts
    AlgorithmFamily family;
    // Never hides a visible pixel by design (with the approximation knobs off): regression runs
    // expect zero error of it unless a scenario says otherwise.
    bool conservative;
    // Decides with occlusion queries: the approximation knobs (pixel threshold, stale results)
    // apply to it.
    bool issues_queries;
    // Decides from ground truth (the Ideal oracle): needs a ground-truth render every frame, and
    // is the bound others are measured against, never a candidate on a time-against-error front.
    bool oracle;
    // The reference that speedups are measured against (frustum culling).
    bool speedup_reference;
};

// Every algorithm, in the order tables list them.
std::span<const AlgorithmTraits> algorithms();
const std::vector<std::string>& algorithmNames();
// nullptr when the name is unknown.
const AlgorithmTraits* findAlgorithm(std::string_view name);
// The algorithm with speedup_reference set (frustum culling).
const AlgorithmTraits& speedupReference();
// "vfc, stop-and-wait, ..." for messages.
std::string algorithmNameList();

// The statistical options an algorithm reads: nullptr for the algorithms that are not statistical.
const StatisticalOptions* statisticalOptionsOf(const AlgorithmTraits& algorithm,
                                               const CullerOptions& options);

std::unique_ptr<Culler> makeCuller(const AlgorithmTraits& algorithm, const CullerOptions& options);

}  // namespace occsim
