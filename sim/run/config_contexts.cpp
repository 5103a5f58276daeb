#include "sim/run/config_contexts.h"

#include "occsim/culling/contract/render_device.h"
#include "sim/run/simulation.h"

namespace occsim {

bool rendersApart(const CullerRow& algorithm) {
    return (algorithm.device_needs & kConditionalRendering) != 0;
}

ConfigContexts::ConfigContexts(const std::vector<RunConfig>& configs, HeadlessContext& shared,
                               GlRenderer& shared_renderer, const Scene& scene,
                               DepthConvention depth)
    : shared_(shared), shared_renderer_(shared_renderer), own_(configs.size()) {
    // The same backend and device as the run's context, never another one Auto might pick.
    const BackendChoice same{shared.info().backend, shared.info().device};
    try {
        for (size_t c = 0; c < configs.size(); ++c) {
            if (!rendersApart(*configs[c].algorithm)) continue;
            auto own = std::make_unique<Own>();
            own->context =
                createHeadlessContext(same, shared_renderer.width(), shared_renderer.height());
            own->renderer = std::make_unique<GlRenderer>(shared_renderer.width(),
                                                         shared_renderer.height(), depth);
            uploadScene(scene, *own->renderer);
            own_[c] = std::move(own);
        }
    } catch (...) {
        release();
        throw;
    }
    shared_.makeCurrent();
}

ConfigContexts::~ConfigContexts() { release(); }

void ConfigContexts::release() {
    for (std::unique_ptr<Own>& own : own_) {
        if (!own) continue;
        try {
            own->context->makeCurrent();
        } catch (...) {
            // A context that cannot be made current cannot free its objects either; destroying
            // it frees them with it.
        }
        own->renderer.reset();
        own->context.reset();
        own.reset();
    }
    try {
        shared_.makeCurrent();
    } catch (...) {
        // Nothing is left to render with; the caller's next GL call says so.
    }
}

GlRenderer& ConfigContexts::renderer(size_t config) {
    return own_[config] ? *own_[config]->renderer : shared_renderer_;
}

std::vector<std::string> ConfigContexts::apartLabels(const std::vector<RunConfig>& configs) const {
    std::vector<std::string> labels;
    for (size_t c = 0; c < own_.size() && c < configs.size(); ++c) {
        if (own_[c]) labels.push_back(configs[c].label);
    }
    return labels;
}

ConfigContexts::Use::Use(ConfigContexts& contexts, size_t config)
    : contexts_(contexts), switched_(contexts.own_[config] != nullptr) {
    if (switched_) contexts.own_[config]->context->makeCurrent();
}

ConfigContexts::Use::~Use() {
    if (!switched_) return;
    try {
        contexts_.shared_.makeCurrent();
    } catch (...) {
        // As in ~ConfigContexts().
    }
}

}  // namespace occsim
