#include "sim/run/runner.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "render/headless_context.h"
#include "sim/run/calibration.h"
#include "sim/run/config_contexts.h"
#include "sim/run/crash_note.h"
#include "sim/run/culler_setup.h"
#include "sim/run/ground_truth.h"
#include "sim/run/heap_policy.h"
#include "sim/run/light_limits.h"
#include "sim/run/segment_summaries.h"
#include "sim/run/shared_world.h"
#include "sim/run/stop_request.h"
#include "sim/world/occluder_roles.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

// The 1, 5 and 15-minute load averages, or -1 where the system does not say.
std::array<double, 3> loadAverage() {
    std::array<double, 3> load{-1.0, -1.0, -1.0};
    double values[3];
    const int n = ::getloadavg(values, 3);
    for (int i = 0; i < n && i < 3; ++i) load[static_cast<size_t>(i)] = values[i];
    return load;
}

void printWarnings(const Scene& scene, std::set<std::string>* shown) {
    for (const std::string& w : scene.warnings) {
        if (shown && !shown->insert(w).second) continue;
        std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
}

// A note for the person running it, once a session (BenchOptions::warnings_shown).
void printNote(const BenchOptions& options, const std::string& line) {
    if (options.warnings_shown && !options.warnings_shown->insert(line).second) return;
    if (options.on_note) {
        options.on_note(line);
    } else {
        std::fprintf(stderr, "note: %s\n", line.c_str());
    }
}

// What a run renders of the views a scene names (docs/views.md), said once, so that nobody reads
// its figures as those of a frame with every view culled: the first shadow-casting directional
// light's shadow pass is rendered, its casters culled by the light's box, by the camera's
// receivers, or by each configuration's culler; other lights and a second eye are read and
// checked but not rendered yet.
void noteViews(const Scenario& scenario, const Scene& scene, const BenchOptions& options) {
    std::vector<std::string> parts;
    const int shadow_light = firstShadowLight(scene.lights);
    if (shadow_light >= 0) {
        const ShadowCasterCulling mode = options.shadow_casters;
        parts.push_back(
            "light " + std::to_string(shadow_light) +
            (mode == ShadowCasterCulling::ReceiverMask
                 ? " renders a shadow pass after the camera's, drawing the casters that may "
                   "shadow what the camera's pass drew (receiver-masked), then a shading pass: "
                   "the cullers cull the camera's view alone"
             : mode == ShadowCasterCulling::Culler
                 ? " renders a shadow pass whose casters each configuration's culler culls in "
                   "the light's view, with state of its own"
             : mode == ShadowCasterCulling::CullerWithReceiverMask
                 ? " renders a shadow pass after the camera's, whose casters each "
                   "configuration's culler culls in the light's view, with state of its own, "
                   "leaving out those that may shadow nothing the camera's pass drew, then a "
                   "shading pass"
                 : " renders a shadow pass drawing every object in its box (light-frustum "
                   "culling): the cullers cull the camera's view alone"));
    }
    const auto casting = std::count_if(scene.lights.begin(), scene.lights.end(),
                                       [](const LightSpec& l) { return l.casts_shadows; });
    const bool other_lights = casting > (shadow_light >= 0 ? 1 : 0);
    if (other_lights) {
        parts.push_back(
            "spot lights and further shadow-casting lights are read and checked but "
            "not rendered yet");
    }
    if (scenario.stereo) {
        const bool per_eye = scenario.stereo->culling == StereoCulling::PerEye;
        parts.push_back("stereo renders two eyes of " + std::to_string(scenario.width) + "x" +
                        std::to_string(scenario.height) + " each, one above the other, " +
                        (per_eye
                             ? "each culled by an instance of the configuration's culler of its own"
                             : "culled by one pass over a frustum enclosing both"));
    }
    if (parts.empty()) return;
    std::string line = scenario.file.string() + ": ";
    for (size_t i = 0; i < parts.size(); ++i) line += (i > 0 ? "; " : "") + parts[i];
    printNote(options, line + " (docs/views.md)");
}

RunMetadata metadataOf(const Scenario& scenario, const Scene& scene, const BenchOptions& options,
                       uint32_t repetitions, const HeadlessContext& context) {
    RunMetadata m;
    m.command = options.command;
    m.command_line = options.command_line;
    m.scenario_name = scenario.name;
    m.scenario_file = scenario.file.string();
    m.scenario_id = options.scenario_id;
    m.frames = scenario.frames;
    m.warmup_frames = std::min(scenario.warmup_frames, scenario.frames);
    m.dt_s = scenario.dt_s;
    m.seed = scenario.seed;
    m.objects = scene.objectCount();
    m.triangles = scene.triangle_count;
    m.movers = static_cast<uint32_t>(scene.initial_movers.size());
    m.repetitions = repetitions;
    m.frame_order = std::string(frameOrderName(options.frame_order));
    m.error_measured = options.measure_error;
    if (options.latency.deterministic) m.deterministic_latency = options.latency.latency_commands;
    m.sweep = options.sweep;
    m.hardware_threads = std::thread::hardware_concurrency();
    if (const char* lp_threads = std::getenv("LP_NUM_THREADS")) m.lp_num_threads = lp_threads;
    m.renderer = context.rendererName();
    const ContextInfo& gl = context.info();
    m.backend = backendName(gl.backend);
    m.device = gl.device;
    m.gl_vendor = gl.vendor;
    m.gl_renderer = gl.renderer;
    m.gl_version = gl.version;
    m.driver = gl.driver;
    m.gpu_time_meaningful = gl.gpu_time_meaningful;
    m.backend_fallback = gl.fallback;
    m.width = scenario.width;
    m.height = scenario.height;
    m.segments = options.segments;
    m.stereo = scenario.stereo;
    m.depth_format = depthConventionOf(scenario) == DepthConvention::ReverseFloat
                         ? "reverse-Z, 32-bit float"
                         : "conventional, 24-bit fixed point";
    return m;
}

// The start-up measurement of drawing and querying, when one was made.
void printCalibratedCosts(const std::optional<CostModelChoice>& costs) {
    if (costs && costs->source == CostModelSource::Calibrated) {
        std::fprintf(stderr,
                     "cost model (calibrated): %.5f ms/query box, %.3g ms/triangle, %.5f ms/draw "
                     "call\n",
                     costs->costs.query_box_ms, costs->costs.triangle_ms,
                     costs->costs.draw_call_ms);
    }
}

// One record per configuration, with what it ran with, before any frame.
void prepareRecords(BenchResult& result, const std::vector<RunConfig>& configs) {
    result.runs.resize(configs.size());
    for (size_t c = 0; c < configs.size(); ++c) {
        result.runs[c].algorithm = configs[c].algorithm;
        result.runs[c].options = configs[c].culler.of(*configs[c].algorithm);
        result.runs[c].approximation = configs[c].culler.approximation;
        result.runs[c].culling_file = configs[c].culling_file;
        const CullerRow& a = *configs[c].algorithm;
        if (a.cost_model_use && a.cost_model_use(result.runs[c].options).wanted) {
            result.runs[c].cost_model = configs[c].culler.cost_model;
        }
    }
}

// What one repetition runs on: the world, ground truth and the renderer all configurations share.
struct Stage {
    const Scenario& scenario;
    const std::vector<RunConfig>& configs;
    const BenchOptions& options;
    const HeadlessContext& context;
    GlRenderer& renderer;  // the run's: ground truth, and every configuration not apart
    ConfigContexts& contexts;
    // Per configuration, its verdicts of the first repetition for the worst windows' pictures;
    // empty when none are wanted (no on_window_frame, or error not measured).
    std::vector<VerdictLog>& verdicts;
};

// Every configuration's simulation of one repetition, each made and destroyed with its own
// context current (its GL objects live there: sim/run/config_contexts.h).
struct Simulations {
    ConfigContexts& contexts;
    std::vector<std::unique_ptr<Simulation>> all;

    ~Simulations() {
        for (size_t c = 0; c < all.size(); ++c) {
            try {
                const ConfigContexts::Use use(contexts, c);
                all[c].reset();
            } catch (...) {
                // Its context cannot be made current: freeing its GL names now would free the
                // run's objects of the same names, so the simulation is left as it is.
                (void)all[c].release();
            }
        }
    }
};

void makeSimulations(const Stage& stage, SharedWorld& world, GroundTruth& truth, uint32_t rep,
                     Simulations& sims) {
    const BenchOptions& options = stage.options;
    for (size_t c = 0; c < stage.configs.size(); ++c) {
        const RunConfig& config = stage.configs[c];
        const ConfigContexts::Use use(stage.contexts, c);
        SimulationOptions sim_options;
        sim_options.measure_error = options.measure_error;
        sim_options.shadow_casters = options.shadow_casters;
        sim_options.latency = options.latency;
        sim_options.keep_worst_error_frame =
            options.keep_worst_error_frame && options.measure_error && rep == 0;
        if (rep == 0) sim_options.trace_frame = options.trace_frame;
        sim_options.record_objects = options.record_objects && options.measure_error && rep == 0;
        sim_options.measure_gpu_time = stage.context.info().gpu_time_meaningful;
        sim_options.segments = options.segments;
        sim_options.frame_clock_ms = options.frame_clock_ms;
        auto culler = options.make_culler ? options.make_culler(*config.algorithm, config.culler)
                                          : makeConfiguredCuller(config);
        sims.all.push_back(std::make_unique<Simulation>(world, truth, *config.algorithm,
                                                        std::move(culler), config.culler,
                                                        stage.contexts.renderer(c), sim_options));
        if (cullsLightView(options.shadow_casters)) {
            // The light's view culled by an instance of its own (its state apart).
            sims.all.back()->cullLightViewWith(
                options.make_culler ? options.make_culler(*config.algorithm, config.culler)
                                    : makeConfiguredCuller(config));
        }
        if (world.cullsEachEye()) {
            // Stereo per eye: the right eye culled by an instance of its own.
            sims.all.back()->cullRightEyeWith(
                options.make_culler ? options.make_culler(*config.algorithm, config.culler)
                                    : makeConfiguredCuller(config));
        }
    }
}

// The run's progress (sim/run/progress.h), timed from the first frame.
struct ProgressClock {
    Clock::time_point start = Clock::now();
    RunProgress progress;

    void frameDone(uint32_t done) {
        progress.frameDone(done, std::chrono::duration<double>(Clock::now() - start).count());
    }
};

// A configuration's frame that failed (its culler threw): what the partial result says.
PartialRun failedFrame(const RunConfig& config, uint32_t rep, uint32_t frame,
                       const std::string& what) {
    return PartialRun{"configuration '" + config.label + "' failed at frame " +
                          std::to_string(frame) + ": " + what,
                      0, rep, frame};
}

// Frame `frame` rendered by some configurations only: dropped, so that every configuration
// reports the same frames.
void dropUnevenFrame(std::vector<std::vector<FrameStats>>& frames, uint32_t frame,
                     RunCosts& spent) {
    for (auto& f : frames) {
        if (f.size() > frame) {
            spent.frame_ms_total -= f.back().frame_ms;
            f.pop_back();
        }
    }
}

// Every frame of one repetition, or those before a stop (`stop` set): after a signal the frame
// in hand is finished, after a failed frame the frames before it are kept. Interleaved: frame f
// of every configuration before frame f + 1 of any, so that drift on a shared machine hits all
// alike. Ground truth, when some configuration needs it, is rendered once per frame before the
// first configuration renders (outside every timing); a run in which none needs it renders none.
std::vector<std::vector<FrameStats>> runFrames(const Stage& stage, SharedWorld& world,
                                               GroundTruth& truth,
                                               std::vector<std::unique_ptr<Simulation>>& sims,
                                               uint32_t rep, ProgressClock& progress,
                                               RunCosts& spent, std::optional<PartialRun>& stop) {
    const Scenario& scenario = stage.scenario;
    const BenchOptions& options = stage.options;
    std::vector<std::vector<FrameStats>> frames(sims.size());
    for (auto& f : frames) f.reserve(scenario.frames);
    bool any_needs_truth = false;
    for (const auto& sim : sims) any_needs_truth |= sim->needsGroundTruth();
    const bool truth_colour = options.keep_worst_error_frame && options.measure_error && rep == 0;
    for (uint32_t f = 0; f < scenario.frames; ++f) {
        try {
            world.advance();
        } catch (const MotionError& e) {
            // A world that cannot go on (an object left finite coordinates): the frames before it
            // stand, and the partial run names the object, its position and scale.
            stop = PartialRun{
                std::string("the world stopped at frame ") + std::to_string(f) + ": " + e.what(), 0,
                rep, f};
            return frames;
        }
        if (any_needs_truth) truth.of(world, truth_colour);
        for (size_t k = 0; k < sims.size(); ++k) {
            const size_t c = configurationAt(options.frame_order, sims.size(), f, k);
            noteRendering(stage.configs[c].label.c_str(), f);
            const ConfigContexts::Use use(stage.contexts, c);
            try {
                frames[c].push_back(sims[c]->renderFrame());
            } catch (const std::exception& e) {
                stop = failedFrame(stage.configs[c], rep, f, e.what());
            } catch (...) {
                stop = failedFrame(stage.configs[c], rep, f, "threw a non-standard exception");
            }
            clearCrashNote();
            if (stop) {
                dropUnevenFrame(frames, f, spent);
                return frames;
            }
            spent.frame_ms_total += frames[c].back().frame_ms;
            if (rep == 0 && !stage.verdicts.empty())
                stage.verdicts[c].record(f, sims[c]->objectVerdicts());
            if (options.on_frame) {
                options.on_frame(FrameEvent{rep, f, stage.configs[c], *sims[c], scenario,
                                            stage.contexts.renderer(c)});
            }
        }
        progress.frameDone(rep * scenario.frames + f + 1);
        // A signal after the run's last frame loses nothing: the run is whole, not partial.
        const bool frames_left =
            f + 1 < scenario.frames || rep + 1 < std::max(1u, options.repetitions);
        if (const int signal = stopSignal(); signal && frames_left) {
            stop =
                PartialRun{std::string("interrupted by ") + signalName(signal), signal, rep, f + 1};
            break;
        }
    }
    return frames;
}

void addWorldCosts(RunCosts& spent, const SharedWorld& world, const GroundTruth& truth) {
    spent.world_advances += world.advances();
    spent.world_steps += world.steps();
    spent.world_update_ms_total += world.updateMsTotal();
    spent.ground_truth_renders += truth.renders();
    spent.ground_truth_ms_total += truth.msTotal();
    const SharedWorld::OccluderMeshCost& occluders = world.occluderMeshCost();
    spent.occluder_meshes_tried += occluders.tried;
    spent.occluder_meshes_made += occluders.made;
    spent.occluder_meshes_ms += occluders.ms;
}

// Each configuration's summary of the repetition; the first repetition keeps its frames whole.
void recordRepetition(BenchResult& result, const Stage& stage,
                      const std::vector<std::unique_ptr<Simulation>>& sims,
                      std::vector<std::vector<FrameStats>>& frames, uint32_t rep) {
    for (size_t c = 0; c < sims.size(); ++c) {
        result.costs.error_read_backs += sims[c]->errorReadBacks();
        RunRecord& record = result.runs[c];
        RunSummary summary =
            summarize(stage.configs[c].label, frames[c], stage.scenario.warmup_frames);
        if (stage.options.measure_error) addPopping(summary, sims[c]->poppingRuns());
        addAnswerLatencies(summary, sims[c]->answerLatencies());
        record.repetitions.push_back(summary);
        const std::vector<Segment>& segments = stage.options.segments;
        record.segment_repetitions.resize(segments.size());
        for (size_t k = 0; k < segments.size(); ++k) {
            record.segment_repetitions[k].push_back(summarizeSegment(
                stage.configs[c].label, frames[c], segments[k], stage.scenario.warmup_frames,
                &sims[c]->segmentTallies(), k, stage.options.measure_error));
        }
        if (rep == 0) {
            record.frames = std::move(frames[c]);
            if (sims[c]->keepsWorstErrorFrame())
                result.worst_error_frames.push_back(sims[c]->worstErrorFrame());
        } else {
            record.later_repetitions.push_back(std::move(frames[c]));
        }
    }
}

// A fresh world for every repetition: each one replays the same frames. One world for all
// configurations: the movers step and the tree is refit once per frame, and each culler keeps its
// own per-node state beside the shared tree.
// A repetition stopped early is recorded only when it is the first: a later one's share would
// mix unequal frame counts into the medians, and the whole repetitions before it stand.
void runRepetition(BenchResult& result, const Stage& stage, const Scene& scene, uint32_t rep,
                   ProgressClock& progress) {
    SharedWorld world(scene, stage.scenario);
    GroundTruth truth(stage.renderer);
    Simulations sims{stage.contexts, {}};
    makeSimulations(stage, world, truth, rep, sims);
    const auto loop_start = Clock::now();
    std::vector<std::vector<FrameStats>> frames =
        runFrames(stage, world, truth, sims.all, rep, progress, result.costs, result.partial);
    result.costs.wall_ms +=
        std::chrono::duration<double, std::milli>(Clock::now() - loop_start).count();
    addWorldCosts(result.costs, world, truth);
    if (rep == 0) {
        for (const std::string& line : world.occluderMeshCost().refusals) {
            printNote(stage.options, line);
        }
    }
    if (!result.partial || rep == 0) recordRepetition(result, stage, sims.all, frames, rep);
}

// The worst windows' worst frames, each rendered again on a fresh world replayed to it (the same
// frames every repetition rendered) and handed to the hook, outside every timing.
void replayWindowFrames(BenchResult& result, const Scene& scene, const Scenario& scenario,
                        GlRenderer& renderer, const BenchOptions& options,
                        const std::vector<VerdictLog>& verdicts) {
    std::vector<uint32_t> wanted;
    for (const RunRecord& r : result.runs) {
        for (const WorstWindow& w : r.worst_windows) wanted.push_back(w.worst_frame);
    }
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    if (wanted.empty()) return;
    const auto start = Clock::now();
    SharedWorld world(scene, scenario);
    GroundTruth truth(renderer);
    size_t next = 0;
    while (next < wanted.size() && !world.done()) {
        world.advance();
        if (world.frame() != wanted[next]) continue;
        const GroundTruthFrame& frame = truth.of(world, true);
        ReplayedFrame replayed{world.frame(),
                               world.frame() * scenario.dt_s,
                               frame.rgba,
                               renderer.width(),
                               renderer.height(),
                               frame.ids,
                               world.state().boxes,
                               world.view().render,
                               scenario.camera.near_m,
                               {}};
        for (size_t c = 0; c < result.runs.size(); ++c) {
            const RunRecord& run = result.runs[c];
            for (const WorstWindow& w : run.worst_windows) {
                if (w.worst_frame != world.frame()) continue;
                replayed.windows.push_back(
                    WindowVerdicts{run.summary.label,
                                   c < verdicts.size() ? verdicts[c].at(w.worst_frame) : nullptr,
                                   options.measure_error});
                break;
            }
        }
        options.on_window_frame(replayed);
        ++next;
    }
    result.costs.window_frames_replayed = static_cast<uint32_t>(next);
    result.costs.window_replay_ms =
        std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

BenchResult runBenchmark(const Scenario& input, const BenchOptions& options) {
    const std::array<double, 3> load_before = loadAverage();
    const std::string heap = keepFreedMemory();
    Scenario scenario = input;
    if (options.frames) scenario.frames = *options.frames;
    std::vector<RunConfig> configs =
        options.configs.empty()
            ? planConfigs(options.algorithms, scenario.culler, options.sweep, options.ablate)
            : options.configs;
    const uint32_t repetitions = std::max(1u, options.repetitions);

    // Before the scene is built: what the views cannot take yet is one line, and nothing else.
    for (const RunConfig& config : configs) {
        requireViewSupport(*config.algorithm, scenario, options.shadow_casters);
    }
    const Scene scene = buildScene(scenario);
    printWarnings(scene, options.warnings_shown);
    noteViews(scenario, scene, options);
    auto context = createHeadlessContext(options.backend, scenario.width, scenario.height);
    checkShadowMapsFit(scenario, context->info().max_texture_size);
    // Stereo: the two eyes one above the other (GlRenderer, docs/views.md).
    GlRenderer renderer(scenario.width, scenario.stereo ? 2 * scenario.height : scenario.height,
                        depthConventionOf(scenario));
    uploadScene(scene, renderer);

    const std::optional<CostModelChoice> costs =
        chooseCostModel(configs, scene, scenario, renderer, options.latency);
    printCalibratedCosts(costs);

    BenchResult result;
    result.metadata = metadataOf(scenario, scene, options, repetitions, *context);
    // The roles a culler with an occluder pass reads: said, so that a user can check what the
    // scene file gave (all explicit roles leave an occluder option nothing to act on).
    if (std::any_of(configs.begin(), configs.end(),
                    [](const RunConfig& c) { return c.algorithm->needs_meshes; }))
        result.metadata.occluder_roles = occluderRolesText(countOccluderRoles(scene));
    result.metadata.heap = heap;
    if (costs) {
        result.metadata.cost_model = costs->costs;
        result.metadata.cost_model_source = costModelSourceName(costs->source);
    }
    prepareRecords(result, configs);

    // The verdicts of every frame, kept for the worst windows' pictures (found after the run).
    std::vector<VerdictLog> verdicts;
    if (options.on_window_frame && options.measure_error)
        verdicts.assign(configs.size(), VerdictLog(kVerdictLogBudgetBytes / configs.size()));
    ConfigContexts contexts(configs, *context, renderer, scene, depthConventionOf(scenario));
    result.metadata.contexts_apart = contexts.apartLabels(configs);
    const Stage stage{scenario, configs, options, *context, renderer, contexts, verdicts};
    ProgressClock progress{
        Clock::now(), RunProgress(options.progress,
                                  scenario.name + ", " + std::to_string(configs.size()) +
                                      (configs.size() == 1 ? " configuration" : " configurations"),
                                  repetitions * scenario.frames, scenario.frames)};
    for (uint32_t rep = 0; rep < repetitions && !result.partial; ++rep)
        runRepetition(result, stage, scene, rep, progress);
    progress.progress.finish();  // ends a bar a stopped run left open

    result.metadata.load_before = load_before;
    result.metadata.load_after = loadAverage();
    for (RunRecord& record : result.runs) {
        record.summary = aggregateRepetitions(record.repetitions);
        for (const std::vector<RunSummary>& reps : record.segment_repetitions)
            record.segments.push_back(aggregateRepetitions(reps));
    }
    if (options.measure_error) markParetoFront(result.runs);
    const int reference = markWorstWindows(result.runs, scenario.warmup_frames);
    if (reference >= 0) result.window_reference = result.runs[size_t(reference)].summary.label;
    if (options.on_window_frame && !(result.partial && result.partial->signal != 0))
        replayWindowFrames(result, scene, scenario, renderer, options, verdicts);
    return result;
}

}  // namespace occsim
