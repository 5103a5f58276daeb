// The fixture of the viewer's headless tests: the small teapot scenario built and uploaded on the
// backend of the parameter, and simulations of it with any culler.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "headless_backends.h"
#include "occsim/culling/registry/registry.h"
#include "render/gl_renderer.h"
#include "render/headless_context.h"
#include "sim/output/raster_canvas.h"
#include "sim/run/culler_setup.h"
#include "sim/run/simulation.h"
#include "sim/scenario/scenario.h"

namespace occsim {

inline const std::filesystem::path kSmall =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

class ViewGl : public ::testing::TestWithParam<Backend> {
  protected:
    void SetUp() override {
        scenario_ = parseScenarioFile(kSmall);
        context_ = createHeadlessContext({GetParam(), {}}, scenario_.width, scenario_.height);
        scene_ = std::make_unique<Scene>(buildScene(scenario_));
        renderer_ = std::make_unique<GlRenderer>(scenario_.width, scenario_.height);
        uploadScene(*scene_, *renderer_);
    }
    std::unique_ptr<Simulation> simulation(const std::string& algorithm, bool error = false) {
        const CullerRow& a = *findCuller(algorithm);
        SimulationOptions options;
        options.measure_error = error;
        return std::make_unique<Simulation>(*scene_, scenario_, a, makeCuller(a, scenario_.culler),
                                            scenario_.culler, *renderer_, options);
    }
    std::vector<uint32_t> ids() {
        std::vector<uint32_t> out;
        renderer_->readObjectIds(out);
        return out;
    }

    Scenario scenario_;
    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<Scene> scene_;
    std::unique_ptr<GlRenderer> renderer_;
};

inline size_t countColour(const RasterCanvas& canvas, Rgb colour) {
    size_t n = 0;
    for (uint32_t y = 0; y < canvas.height(); ++y) {
        for (uint32_t x = 0; x < canvas.width(); ++x) n += canvas.at(int(x), int(y)) == colour;
    }
    return n;
}

}  // namespace occsim
