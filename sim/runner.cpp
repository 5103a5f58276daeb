#include "sim/runner.h"

#include "culling/culler_factory.h"
#include "render/gl_context.h"
#include "render/png_writer.h"
#include "sim/atomic_file.h"
#include "sim/simulation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

void printProgress(uint32_t done, uint32_t total, Clock::time_point start) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const double left = done > 0 ? elapsed / done * (total - done) : 0.0;
    std::fprintf(stderr, "\rframe %u/%u  %.0f s elapsed, about %.0f s left   ", done, total, elapsed,
                 left);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
}

nlohmann::json machineJson(const std::string& renderer, const Scenario& scenario) {
    const char* lp_threads = std::getenv("LP_NUM_THREADS");
    return {{"hardware_threads", std::thread::hardware_concurrency()},
            {"llvmpipe_threads", lp_threads ? lp_threads : "default"},
            {"renderer", renderer},
            {"resolution", std::to_string(scenario.width) + "x" + std::to_string(scenario.height)}};
}

void printWarnings(const Scene& scene) {
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

}  // namespace

BenchResult runBenchmark(const Scenario& input, const BenchOptions& options) {
    Scenario scenario = input;
    if (options.frames) scenario.frames = *options.frames;

    const Scene scene = buildScene(scenario);
    printWarnings(scene);
    auto context = createOsMesaContext(scenario.width, scenario.height);
    GlRenderer renderer(scenario.width, scenario.height);
    uploadScene(scene, renderer);

    SimulationOptions sim_options;
    sim_options.measure_error = options.measure_error;
    sim_options.latency = options.latency;
    sim_options.keep_worst_error_frame = options.keep_worst_error_frame && options.measure_error;
    std::vector<std::unique_ptr<Simulation>> sims;
    for (const std::string& name : options.algorithms) {
        auto culler = options.make_culler ? options.make_culler(name, scenario.culler)
                                          : makeCuller(name, scenario.culler);
        if (!culler) throw std::invalid_argument("unknown algorithm '" + name + "'");
        sims.push_back(std::make_unique<Simulation>(scene, scenario, std::move(culler), renderer, sim_options));
    }

    std::filesystem::create_directories(options.out_dir);
    BenchResult result;
    result.renderer = context->rendererName();
    std::vector<std::vector<FrameStats>> frames(sims.size());
    for (auto& f : frames) f.reserve(scenario.frames);
    std::vector<uint8_t> rgba;
    const auto start = Clock::now();
    auto last_progress = start;
    // Interleaved: frame f of every algorithm before frame f + 1 of any.
    // Every simulation runs the same world in lockstep, so one ground-truth render per frame
    // serves them all.
    bool any_needs_truth = false;
    for (const auto& sim : sims) any_needs_truth |= sim->needsGroundTruth();
    for (uint32_t f = 0; f < scenario.frames; ++f) {
        for (auto& sim : sims) sim->advance();
        const GroundTruthFrame* truth =
            any_needs_truth ? &sims.front()->renderGroundTruth(sim_options.keep_worst_error_frame)
                            : nullptr;
        for (size_t a = 0; a < sims.size(); ++a) {
            frames[a].push_back(sims[a]->renderFrame(truth));
            if (std::find(options.capture_frames.begin(), options.capture_frames.end(), f) !=
                options.capture_frames.end()) {
                renderer.readColor(rgba);
                char name[96];
                std::snprintf(name, sizeof name, "frame-%05u-%s.png", f, options.algorithms[a].c_str());
                writeFileAtomically(options.out_dir / name,
                                    encodePngBottomUp(rgba, scenario.width, scenario.height));
            }
        }
        if (options.progress && (Clock::now() - last_progress > std::chrono::milliseconds(250) ||
                                 f + 1 == scenario.frames)) {
            printProgress(f + 1, scenario.frames, start);
            last_progress = Clock::now();
        }
    }

    for (size_t a = 0; a < sims.size(); ++a) {
        result.runs.push_back({summarize(options.algorithms[a], frames[a], scenario.warmup_frames),
                               std::move(frames[a])});
    }
    result.table = formatComparisonTable(result.runs);
    result.width = scenario.width;
    result.height = scenario.height;
    if (sim_options.keep_worst_error_frame) {
        for (const auto& sim : sims) result.worst_error_frames.push_back(sim->worstErrorFrame());
    }

    nlohmann::json summary = summaryJson(result.runs);
    summary["scenario"] = {{"name", scenario.name}, {"file", scenario.file.string()},
                           {"frames", scenario.frames}, {"warmup_frames", scenario.warmup_frames},
                           {"dt_s", scenario.dt_s}, {"seed", scenario.seed},
                           {"objects", scene.objectCount()}, {"triangles", scene.triangle_count},
                           {"movers", scene.initial_movers.size()}};
    summary["machine"] = machineJson(result.renderer, scenario);
    summary["command"] = options.command_line;
    summary["error_measured"] = options.measure_error;
    summary["deterministic_latency"] =
        options.latency.deterministic ? nlohmann::json(options.latency.latency_commands) : nlohmann::json(nullptr);
    writeFileAtomically(options.out_dir / "frames.csv", framesCsv(result.runs));
    writeFileAtomically(options.out_dir / "summary.json", summary.dump(2) + "\n");
    return result;
}

std::string describeScenario(const Scenario& scenario) {
    const Scene scene = buildScene(scenario);
    printWarnings(scene);
    const WorldState state = initialState(scene);
    BspTree tree;
    tree.build(state.boxes, scenario.bsp);
    uint32_t leaves = 0, objects_in_leaves = 0, max_in_leaf = 0;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const BspNode& node = tree.node(n);
        if (!node.isLeaf()) continue;
        ++leaves;
        objects_in_leaves += node.object_count;
        max_in_leaf = std::max(max_in_leaf, node.object_count);
    }
    // Where objects live by node depth: straddlers of a split stay in inner nodes, and an object
    // high in the tree is drawn whenever its (large) node is visible.
    std::vector<uint32_t> by_depth(tree.maxDepth() + 1, 0);
    for (uint32_t o = 0; o < tree.objectCount(); ++o) ++by_depth[tree.node(tree.nodeOf(o)).depth];
    const Aabb& b = tree.bounds(tree.root());
    std::ostringstream out;
    char line[256];
    out << "scenario      " << scenario.name << " (" << scenario.file.string() << ")\n";
    out << "objects       " << scene.objectCount() << " (" << scene.meshes.size() << " meshes)\n";
    out << "triangles     " << scene.triangle_count << "\n";
    out << "movers        " << scene.initial_movers.size() << "\n";
    out << "frames        " << scenario.frames << " x " << scenario.dt_s << " s, "
        << scenario.width << "x" << scenario.height << " pixels\n";
    out << "bsp           " << tree.nodeCount() << " nodes, " << leaves << " leaves, depth "
        << tree.maxDepth() << "\n";
    std::snprintf(line, sizeof line, "objects/leaf  %.2f mean, %u max; %u objects in inner nodes\n",
                  leaves ? static_cast<double>(objects_in_leaves) / leaves : 0.0, max_in_leaf,
                  scene.objectCount() - objects_in_leaves);
    out << line;
    out << "objects/depth";
    for (size_t d = 0; d < by_depth.size(); ++d) out << ' ' << d << ':' << by_depth[d];
    out << "\n";
    std::snprintf(line, sizeof line, "bounds        (%.2f, %.2f, %.2f) .. (%.2f, %.2f, %.2f)\n", b.min.x,
                  b.min.y, b.min.z, b.max.x, b.max.y, b.max.z);
    out << line;
    out << "algorithm     " << scenario.algorithm << "\n";
    return out.str();
}

}  // namespace occsim
