// An example culler for occsim's plugin interface: hierarchical stop-and-wait occlusion queries
// that trust what they saw. A node a query found visible is drawn without a query for `trust`
// seconds of simulation time; every other node in the frustum is queried, front to back, and its
// answer awaited before the traversal goes on. Conservative: an answer is always awaited, and a
// trusted node only draws more than a query would.
#pragma once

#include <occsim/culling/plugin.h>

#include <limits>
#include <vector>

namespace example {

class TrustVisibleCuller final : public occsim::Culler {
  public:
    explicit TrustVisibleCuller(double trust_s) : trust_s_(trust_s) {}
    void reset(const occsim::BspTree& tree) override { last_visible_s_.reset(tree); }
    void cullAndRender(const occsim::BspTree& tree, const occsim::CullFrame& frame,
                       occsim::RenderDevice& device) override;

  private:
    // When a query last found the node visible; -infinity: never.
    struct Seen {
        double time_s = -std::numeric_limits<double>::infinity();
    };
    double trust_s_;
    occsim::NodeStateArray<Seen> last_visible_s_;
    std::vector<occsim::NodeVisit> stack_;
};

}  // namespace example
