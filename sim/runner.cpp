#include "sim/runner.h"

#include "culling/culler_factory.h"
#include "sim/bench_config.h"
#include "render/gl_context.h"
#include "render/png_writer.h"
#include "sim/atomic_file.h"
#include "sim/birds_eye.h"
#include "sim/camera_path.h"
#include "sim/markdown_report.h"
#include "sim/plots.h"
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

std::string fileSafe(std::string s) {
    for (char& c : s) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.' && c != '_') c = '_';
    }
    return s;
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

// The bird's-eye picture of the frame `sim` just rendered with tracing on; returns its file name.
std::string writeBirdsEye(const Simulation& sim, const Scenario& scenario, const RunConfig& config,
                          const std::filesystem::path& dir) {
    const FrameTrace& trace = *sim.lastTrace();
    const std::vector<NodeClass> classes = classifyNodes(sim.tree(), sim.view().cull, trace);
    const CameraPose pose = sampleCameraPath(scenario.camera, trace.frame * scenario.dt_s);
    BirdsEyeInput in;
    in.tree = &sim.tree();
    in.object_boxes = sim.state().boxes;
    in.drawn_objects = trace.drawn_objects;
    in.node_classes = classes;
    in.view = sim.view().cull;
    in.forward = glm::vec3(glm::normalize(pose.target - pose.position));
    in.fov_y_rad = static_cast<float>(glm::radians(scenario.camera.fov_y_deg));
    in.aspect = static_cast<float>(scenario.width) / static_cast<float>(scenario.height);
    in.near_m = static_cast<float>(scenario.camera.near_m);
    in.far_m = static_cast<float>(scenario.camera.far_m);
    in.title = "frame " + std::to_string(trace.frame) + "  " + config.label;
    const PictureSize size = birdsEyeSize(in, 1000);
    char name[200];
    std::snprintf(name, sizeof name, "birds-eye-%s-frame-%05u.png", fileSafe(config.label).c_str(),
                  static_cast<unsigned>(trace.frame));
    writeFileAtomically(dir / name, encodePngBottomUp(renderBirdsEye(in, size.width, size.height),
                                                      size.width, size.height));
    return name;
}

ReportContext reportContext(const Scenario& scenario, const BenchOptions& options,
                            const BenchResult& result, uint32_t repetitions) {
    ReportContext c;
    // "occsim run ..." or "occsim bench ...": the command is the word after the executable.
    std::istringstream words(options.command_line);
    std::string executable, command;
    words >> executable >> command;
    if (command == "run" || command == "bench") c.command_name = command;
    c.scenario_name = scenario.name;
    c.scenario_file = scenario.file.string();
    c.frames = scenario.frames;
    c.warmup_frames = std::min(scenario.warmup_frames, scenario.frames);
    c.repetitions = repetitions;
    c.error_measured = options.measure_error;
    if (options.latency.deterministic) c.deterministic_latency = options.latency.latency_commands;
    c.hardware_threads = std::thread::hardware_concurrency();
    const char* lp_threads = std::getenv("LP_NUM_THREADS");
    if (lp_threads) c.lp_num_threads = lp_threads;
    c.renderer = result.renderer;
    c.width = scenario.width;
    c.height = scenario.height;
    c.command_line = options.command_line;
    c.sweep = options.sweep;
    return c;
}

}  // namespace

BenchResult runBenchmark(const Scenario& input, const BenchOptions& options) {
    Scenario scenario = input;
    if (options.frames) scenario.frames = *options.frames;
    const std::vector<RunConfig> configs = planConfigs(options.algorithms, scenario.culler, options.sweep);
    const uint32_t repetitions = std::max(1u, options.repetitions);

    const Scene scene = buildScene(scenario);
    printWarnings(scene);
    auto context = createOsMesaContext(scenario.width, scenario.height);
    GlRenderer renderer(scenario.width, scenario.height);
    uploadScene(scene, renderer);
    std::filesystem::create_directories(options.out_dir);

    BenchResult result;
    result.renderer = context->rendererName();
    result.width = scenario.width;
    result.height = scenario.height;
    result.runs.resize(configs.size());
    for (size_t c = 0; c < configs.size(); ++c) result.runs[c].algorithm = configs[c].algorithm;

    std::vector<uint8_t> rgba;
    const auto start = Clock::now();
    auto last_progress = start;
    const uint32_t total_frames = repetitions * scenario.frames;
    for (uint32_t rep = 0; rep < repetitions; ++rep) {
        // Fresh worlds for every repetition: each one replays the same frames.
        std::vector<std::unique_ptr<Simulation>> sims;
        for (const RunConfig& config : configs) {
            SimulationOptions sim_options;
            sim_options.measure_error = options.measure_error;
            sim_options.latency = options.latency;
            sim_options.keep_worst_error_frame =
                options.keep_worst_error_frame && options.measure_error && rep == 0;
            sim_options.approximation = config.approximation;
            if (rep == 0) sim_options.trace_frame = options.birds_eye_frame;
            auto culler = options.make_culler ? options.make_culler(config.algorithm, config.culler)
                                              : makeCuller(config.algorithm, config.culler);
            if (!culler) throw std::invalid_argument("unknown algorithm '" + config.algorithm + "'");
            sims.push_back(std::make_unique<Simulation>(scene, scenario, std::move(culler), renderer,
                                                        sim_options));
        }
        std::vector<std::vector<FrameStats>> frames(sims.size());
        for (auto& f : frames) f.reserve(scenario.frames);
        // Interleaved: frame f of every configuration before frame f + 1 of any, so that drift
        // on a shared machine hits all alike. Every simulation runs the same world in lockstep,
        // so one ground-truth render per frame serves them all (outside every timing).
        bool any_needs_truth = false;
        for (const auto& sim : sims) any_needs_truth |= sim->needsGroundTruth();
        const bool truth_colour = options.keep_worst_error_frame && options.measure_error && rep == 0;
        for (uint32_t f = 0; f < scenario.frames; ++f) {
            for (auto& sim : sims) sim->advance();
            const GroundTruthFrame* truth =
                any_needs_truth ? &sims.front()->renderGroundTruth(truth_colour) : nullptr;
            for (size_t c = 0; c < sims.size(); ++c) {
                frames[c].push_back(sims[c]->renderFrame(truth));
                // Pictures are drawn between frames, outside every timing.
                if (rep == 0 && options.birds_eye_frame == f) {
                    result.outputs.push_back(writeBirdsEye(*sims[c], scenario, configs[c], options.out_dir));
                }
                const bool capture = rep == 0 && std::find(options.capture_frames.begin(),
                                                           options.capture_frames.end(),
                                                           f) != options.capture_frames.end();
                if (capture) {
                    renderer.readColor(rgba);
                    char name[160];
                    std::snprintf(name, sizeof name, "frame-%05u-%s.png", f,
                                  fileSafe(configs[c].label).c_str());
                    writeFileAtomically(options.out_dir / name,
                                        encodePngBottomUp(rgba, scenario.width, scenario.height));
                }
            }
            const uint32_t done = rep * scenario.frames + f + 1;
            if (options.progress && (Clock::now() - last_progress > std::chrono::milliseconds(250) ||
                                     done == total_frames)) {
                printProgress(done, total_frames, start);
                last_progress = Clock::now();
            }
        }
        for (size_t c = 0; c < sims.size(); ++c) {
            RunRecord& record = result.runs[c];
            RunSummary summary = summarize(configs[c].label, frames[c], scenario.warmup_frames);
            if (options.measure_error) addPopping(summary, sims[c]->poppingRuns());
            record.repetitions.push_back(summary);
            if (rep == 0) {
                record.frames = std::move(frames[c]);
                if (sims[c]->keepsWorstErrorFrame()) result.worst_error_frames.push_back(sims[c]->worstErrorFrame());
            } else {
                record.later_repetitions.push_back(std::move(frames[c]));
            }
        }
    }

    std::vector<double> time, error;
    for (RunRecord& record : result.runs) {
        record.summary = aggregateRepetitions(record.repetitions);
        time.push_back(record.summary.frame_ms.mean);
        error.push_back(record.summary.error_pixels_mean);
    }
    if (options.measure_error) {
        // The Ideal oracle is the bound, not a candidate: the front is over real cullers.
        std::vector<size_t> candidates;
        std::vector<double> t, e;
        for (size_t c = 0; c < result.runs.size(); ++c) {
            if (result.runs[c].algorithm == "ideal") continue;
            candidates.push_back(c);
            t.push_back(time[c]);
            e.push_back(error[c]);
        }
        const std::vector<bool> front = paretoFront(t, e);
        for (size_t i = 0; i < candidates.size(); ++i) result.runs[candidates[i]].pareto = front[i];
    }
    result.table = formatComparisonTable(result.runs);

    nlohmann::json summary = summaryJson(result.runs);
    summary["scenario"] = {{"name", scenario.name}, {"file", scenario.file.string()},
                           {"frames", scenario.frames}, {"warmup_frames", scenario.warmup_frames},
                           {"dt_s", scenario.dt_s}, {"seed", scenario.seed},
                           {"objects", scene.objectCount()}, {"triangles", scene.triangle_count},
                           {"movers", scene.initial_movers.size()}};
    summary["machine"] = machineJson(result.renderer, scenario);
    summary["command"] = options.command_line;
    summary["repetitions"] = repetitions;
    summary["error_measured"] = options.measure_error;
    summary["deterministic_latency"] =
        options.latency.deterministic ? nlohmann::json(options.latency.latency_commands) : nlohmann::json(nullptr);
    if (options.sweep) summary["sweep"] = {{"parameter", options.sweep->parameter}, {"values", options.sweep->values}};
    writeFileAtomically(options.out_dir / "frames.csv", framesCsv(result.runs));
    writeFileAtomically(options.out_dir / "summary.json", summary.dump(2) + "\n");

    ReportContext report = reportContext(scenario, options, result, repetitions);
    for (const std::string& f : result.outputs) report.birds_eye_files.push_back(f);
    if (options.plots) {
        const PlotResult plots = writePlots(result.runs, options.out_dir);
        report.plot_files = plots.files;
        report.plots_note = plots.message;
        result.plots_message = plots.message;
        result.outputs.insert(result.outputs.end(), plots.files.begin(), plots.files.end());
    }
    writeFileAtomically(options.out_dir / "report.md", markdownReport(result, report));
    result.outputs.push_back("report.md");
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
