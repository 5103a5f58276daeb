// The GL context and renderer each configuration of a run renders with: the run's own, shared by
// every configuration, or one of its own for a culler that needs conditional rendering. On Mesa's
// llvmpipe a frame of GL_QUERY_NO_WAIT conditional draws flushes a scene per batch of queries,
// and what it leaves slows whatever renders after it in the same context (docs/conditional.md):
// with configurations interleaved frame by frame that would be every other culler in turn. A
// context of its own (its own renderer, the scene uploaded again) keeps that out of the others'
// timings; ground truth and every picture of the run stay in the run's context.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "render/gl_renderer.h"
#include "render/headless_context.h"
#include "sim/run/run_config.h"
#include "sim/world/world.h"

namespace occsim {

// Whether a culler renders in a context of its own: it needs conditional rendering.
bool rendersApart(const CullerRow& algorithm);

class ConfigContexts {
  public:
    // `shared` and `shared_renderer` are the run's (current on the calling thread, the scene
    // uploaded); a configuration that renders apart gets a context on the same backend and
    // device, with a renderer of `shared_renderer`'s size and depth convention and `scene`
    // uploaded to it. `shared` is current again when the constructor returns.
    ConfigContexts(const std::vector<RunConfig>& configs, HeadlessContext& shared,
                   GlRenderer& shared_renderer, const Scene& scene, DepthConvention depth);
    // Each context of its own is destroyed with its renderer while current; `shared` is current
    // afterwards.
    ~ConfigContexts();
    ConfigContexts(const ConfigContexts&) = delete;
    ConfigContexts& operator=(const ConfigContexts&) = delete;

    GlRenderer& renderer(size_t config);
    bool apart(size_t config) const { return own_[config] != nullptr; }
    // The labels of the configurations that render apart, in run order.
    std::vector<std::string> apartLabels(const std::vector<RunConfig>& configs) const;

    // Configuration `config`'s context current for the scope, the run's after it. Nothing happens
    // for a configuration that renders in the run's context.
    class Use {
      public:
        Use(ConfigContexts& contexts, size_t config);
        ~Use();
        Use(const Use&) = delete;
        Use& operator=(const Use&) = delete;

      private:
        ConfigContexts& contexts_;
        bool switched_;
    };

  private:
    struct Own {
        std::unique_ptr<HeadlessContext> context;
        std::unique_ptr<GlRenderer> renderer;
    };
    // Destroys every context of its own (each current while its renderer goes), then makes the
    // run's context current.
    void release();

    HeadlessContext& shared_;
    GlRenderer& shared_renderer_;
    std::vector<std::unique_ptr<Own>> own_;  // per configuration; null: the run's context
};

}  // namespace occsim
