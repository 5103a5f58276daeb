// Plugins for the loader's tests (test_plugin_loader.cpp, test_plugins.cpp), one shared object per
// define:
//   PLUGIN_GOOD            a conservative culler "test-frustum" (frustum culling) with options
//   PLUGIN_NO_ENTRY        no entry point at all
//   PLUGIN_OTHER_ABI       an entry point that carries another ABI version
//   PLUGIN_TAKEN_NAME      registers "chc", a built-in's name
//   PLUGIN_BAD_DESCRIPTOR  an option whose range is inverted
//   PLUGIN_THROWING        a factory that throws
//   PLUGIN_PICKY           a factory that throws for a margin other than the default: it loads
//                          (made once with its defaults) and fails when a run asks for another
//   PLUGIN_FAILING         "test-frustum" throws in its frame 3 (the stopping tests)
//   PLUGIN_CRASHING        "test-frustum" raises SIGSEGV in its frame 3 (the stopping tests)
//   PLUGIN_NEEDS_CONDITIONAL  "test-frustum" claims to issue queries and to need conditional
//                          rendering, which an approximating device withholds (the refusal)
#include <csignal>
#include <stdexcept>

#include "occsim/culling/plugin.h"

namespace {

class FrustumOnly final : public occsim::Culler {
  public:
    void reset(const occsim::BspTree&) override {}
    void cullAndRender(const occsim::BspTree& tree, const occsim::CullFrame& frame,
                       occsim::RenderDevice& device) override {
#if defined(PLUGIN_FAILING)
        if (frames_++ == 3) throw std::runtime_error("out of budget");
#elif defined(PLUGIN_CRASHING)
        if (frames_++ == 3) std::raise(SIGSEGV);
#endif
        const occsim::PreparedView view = occsim::prepareView(frame.view);
        occsim::traverseFrontToBack(tree, view, stack_, [&](const occsim::NodeVisit& v) {
            occsim::drawNodeObjects(tree, v.node, view.frustum, v.inside_frustum, device);
            return true;
        });
    }

  private:
    std::vector<occsim::NodeVisit> stack_;
    [[maybe_unused]] unsigned frames_ = 0;
};

[[maybe_unused]] std::unique_ptr<occsim::Culler> make(const occsim::CullerContext&) {
    return std::make_unique<FrustumOnly>();
}

[[maybe_unused]] std::unique_ptr<occsim::Culler> makeThrowing(const occsim::CullerContext&) {
    throw std::runtime_error("no GPU budget configured");
}

[[maybe_unused]] std::unique_ptr<occsim::Culler> makePicky(const occsim::CullerContext& context) {
    if (context.options.number("margin") != 1.0) throw std::runtime_error("margin is not 1");
    return std::make_unique<FrustumOnly>();
}

[[maybe_unused]] void registerCullers(occsim::PluginRegistrar& registrar) {
    occsim::CullerRow t;
    t.name = "test-frustum";
    t.summary = "frustum culling, from a plugin (tests)";
    t.options = {
        occsim::integerOption("budget", "objects", 1, 1000, 10, "a budget nobody reads"),
        occsim::tunable(occsim::numberOption("margin", "m", 0.0, 5.0, 1.0, "a margin nobody reads"),
                        0.0, 2.0)};
    t.factory = make;
#if defined(PLUGIN_TAKEN_NAME)
    t.name = "chc";
#elif defined(PLUGIN_BAD_DESCRIPTOR)
    t.options[0].min = 10;
    t.options[0].max = 1;
#elif defined(PLUGIN_THROWING)
    t.factory = makeThrowing;
#elif defined(PLUGIN_PICKY)
    t.factory = makePicky;
#elif defined(PLUGIN_NEEDS_CONDITIONAL)
    t.issues_queries = true;
    t.device_needs = occsim::kConditionalRendering;
#endif
    registrar.add(std::move(t));
}

}  // namespace

#if defined(PLUGIN_OTHER_ABI)
extern "C" __attribute__((visibility("default"))) const OccsimPlugin* occsim_plugin() {
    static const OccsimPlugin plugin{OCCSIM_PLUGIN_ABI_VERSION + 1, "old", registerCullers};
    return &plugin;
}
#elif !defined(PLUGIN_NO_ENTRY)
OCCSIM_PLUGIN("test plugin", registerCullers)
#endif
