#include "sim/view/viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <set>
#include <thread>

#include "occsim/culling/registry/registry.h"
#include "render/glfw_context.h"
#include "render/png_writer.h"
#include "sim/output/atomic_file.h"
#include "sim/run/culler_setup.h"
#include "sim/run/simulation.h"
#include "sim/view/fly_camera.h"
#include "sim/view/key_bindings.h"
#include "sim/view/recorded_scenario.h"
#include "sim/view/view_picture.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

// A status message stays on screen for this many composed frames.
constexpr uint32_t kMessageFrames = 90;
// Longest wall-clock step the flying camera takes, so a stall does not throw it across the scene.
constexpr double kMaxFlySeconds = 0.1;
// A paused, idle viewer wakes this often to redraw (an uncovered window) without spinning.
constexpr double kIdleWaitSeconds = 0.1;

// Small scenario viewports (test scenarios are 200 x 150) get an integer zoom to about 800 pixels.
std::pair<uint32_t, uint32_t> initialWindowSize(const Scenario& s, const ViewOptions& o) {
    if (o.width > 0 && o.height > 0) return {o.width, o.height};
    const uint32_t zoom = std::max(1u, 800u / std::max(s.width, s.height));
    return {s.width * zoom, s.height * zoom};
}

size_t algorithmIndex(std::string_view name) {
    const auto& all = cullerRows();
    for (size_t i = 0; i < all.size(); ++i) {
        if (all[i]->name == name) return i;
    }
    return 0;
}

// The first "<prefix>NNN<extension>" in `dir` that does not exist yet, so that a session never
// overwrites the pictures and recordings of an earlier one.
std::filesystem::path nextFreeFile(const std::filesystem::path& dir, const std::string& prefix,
                                   const char* extension) {
    for (unsigned n = 1;; ++n) {
        char name[32];
        std::snprintf(name, sizeof name, "%03u", n);
        std::filesystem::path p = dir / (prefix + name + extension);
        if (!std::filesystem::exists(p)) return p;
    }
}

// A flying speed that crosses the scene in about fifteen seconds.
double initialFlySpeed(const WorldState& state) {
    Aabb all;  // empty
    for (const Aabb& b : state.boxes) {
        if (isFiniteAndOrdered(b)) extend(all, b);
    }
    if (isEmpty(all)) return 5.0;
    return std::clamp(static_cast<double>(glm::length(all.max - all.min)) / 15.0, 0.5, 1000.0);
}

class Viewer {
  public:
    Viewer(const Scenario& scenario, const std::string& scenario_text, const ViewOptions& options)
        : scenario_(scenario),
          scenario_text_(scenario_text),
          options_(options),
          window_(initialWindowSize(scenario, options).first,
                  initialWindowSize(scenario, options).second, "occsim view: " + scenario.name),
          scene_(buildScene(scenario)),
          renderer_(std::max(1u, window_.framebufferWidth()),
                    std::max(1u, window_.framebufferHeight())),
          algorithm_(
              algorithmIndex(options.algorithm.empty() ? scenario.algorithm : options.algorithm)),
          error_(options.error) {
        for (const std::string& w : scene_.warnings)
            std::fprintf(stderr, "warning: %s\n", w.c_str());
        uploadScene(scene_, renderer_);
        world_ = std::make_unique<SharedWorld>(scene_, scenario_);
        sim_ = makeSimulation(*world_);
        fly_ = FlyCamera(initialFlySpeed(world_->state()));
        if (options.script) script_.emplace(*options.script);
        updateTitle();
        std::printf("occsim view: %s, %u objects, %s; press h for the keys\n",
                    scenario.name.c_str(), scene_.objectCount(), window_.rendererName().c_str());
        std::fflush(stdout);
    }

    void run();

  private:
    const CullerRow& algorithm() const { return *cullerRows()[algorithm_]; }
    std::unique_ptr<Simulation> makeSimulation(SharedWorld& world);
    void replaceSimulation(bool keep_world);
    void restart();

    void handle(const WindowEvent& event);
    void onKey(std::string_view key);
    bool held(std::string_view key) const { return held_.count(key) > 0; }
    FlyInput flyInput() const;
    void startFlying();
    CameraPose currentPose(bool play) const;

    void renderFrame(bool play);
    HudState hudState() const;
    void say(const std::string& message);
    void updateTitle();

    void saveScreenshot();
    void startRecording();
    void stopRecording();

    const Scenario& scenario_;
    const std::string& scenario_text_;
    const ViewOptions& options_;
    GlfwWindow window_;
    const Scene scene_;
    GlRenderer renderer_;
    // The world goes on while the algorithm or the error setting changes: only the
    // configuration on it (sim_) is replaced; a restart replaces the world.
    std::unique_ptr<SharedWorld> world_;
    GroundTruth truth_{renderer_};
    std::unique_ptr<Simulation> sim_;
    std::optional<ScriptPlayer> script_;

    size_t algorithm_;
    CullerOptions culler_options_ = scenario_.culler;  // with the cost model once measured
    bool error_;
    bool paused_ = false, step_ = false, dirty_ = true, quit_ = false;
    bool boxes_ = false, birds_eye_ = false, help_ = false, panel_ = true;
    bool validation_ = false;  // the overlay; it turns ground truth on
    bool screenshot_ = false;

    // The camera: the path, or flown by hand.
    bool flying_ = false;
    FlyCamera fly_;
    std::set<std::string_view> held_;
    bool dragging_ = false, have_cursor_ = false;
    double cursor_x_ = 0.0, cursor_y_ = 0.0;

    // Played frames since the (re)start: the path's clock and the recording's.
    uint32_t next_played_ = 0;
    double shown_time_ = 0.0;
    bool recording_ = false;
    std::vector<CameraKeyframe> recorded_;

    bool has_stats_ = false;
    FrameStats stats_;
    std::string message_;
    uint32_t message_frames_ = 0;
    std::vector<uint8_t> rgba_;
    std::vector<uint8_t> picture_;
    uint32_t picture_width_ = 0, picture_height_ = 0;
};

// The culler is made as runs make it (sim/run/culler_setup.h): a culler that weighs costs gets
// the cost model measured on this renderer, once; later switches reuse it.
std::unique_ptr<Simulation> Viewer::makeSimulation(SharedWorld& world) {
    SimulationOptions options;
    options.measure_error = error_;
    std::vector<RunConfig> configs{RunConfig{algorithm().name, &algorithm(), culler_options_}};
    if (chooseCostModel(configs, scene_, scenario_, renderer_, options.latency)) {
        culler_options_.cost_model = configs.front().culler.cost_model;
    }
    return std::make_unique<Simulation>(world, truth_, algorithm(),
                                        makeConfiguredCuller(configs.front()),
                                        configs.front().culler, renderer_, options);
}

// A new configuration for a new algorithm or error setting, with fresh culler state; kept, the
// world goes on where it was, otherwise it starts again from frame 0.
void Viewer::replaceSimulation(bool keep_world) {
    if (keep_world) {
        sim_ = makeSimulation(*world_);
    } else {
        auto world = std::make_unique<SharedWorld>(scene_, scenario_);
        world->setLiveControls(world_->liveControls());
        sim_ = makeSimulation(*world);  // the old configuration goes before the world it used
        world_ = std::move(world);
    }
    dirty_ = true;
}

void Viewer::restart() {
    replaceSimulation(false);
    next_played_ = 0;
    shown_time_ = 0.0;
    recorded_.clear();  // a recording always starts at the world's frame 0, as its replay will
}

void Viewer::run() {
    auto last = Clock::now();
    while (true) {
        const auto frame_start = Clock::now();
        const bool idle = paused_ && !dirty_ && !step_ && !flyInput().moving() && !script_;
        std::vector<WindowEvent> events = window_.takeEvents(idle ? kIdleWaitSeconds : 0.0);
        bool script_done = false;
        if (script_) {
            ScriptPlayer::FrameInput in = script_->next();
            events.insert(events.end(), in.events.begin(), in.events.end());
            if (in.resize) {
                window_.setSize(in.resize->first, in.resize->second);
                // A script's next frames assume the new size: wait for the window system to
                // apply it (a window manager may refuse; then go on after a while).
                const auto give_up = Clock::now() + std::chrono::seconds(5);
                while ((window_.framebufferWidth() != in.resize->first ||
                        window_.framebufferHeight() != in.resize->second) &&
                       Clock::now() < give_up) {
                    const std::vector<WindowEvent> more = window_.takeEvents(0.05);
                    events.insert(events.end(), more.begin(), more.end());
                }
            }
            script_done = in.quit;
        }
        for (const WindowEvent& e : events) handle(e);
        if (quit_ || window_.closeRequested()) break;

        // Scripts fly in simulation time (reproducible); people in wall-clock time.
        const auto now = Clock::now();
        const double seconds =
            script_ ? scenario_.dt_s
                    : std::min(kMaxFlySeconds, std::chrono::duration<double>(now - last).count());
        last = now;
        const FlyInput input = flyInput();
        if (input.moving()) {
            startFlying();
            fly_.fly(input, seconds);
            dirty_ = true;
        }

        const bool play = !paused_ || step_;
        const bool visible = window_.framebufferWidth() > 0 && window_.framebufferHeight() > 0;
        if (visible && (play || dirty_)) renderFrame(play);
        step_ = false;
        dirty_ = false;
        if (screenshot_) saveScreenshot();
        if (visible && !picture_.empty())
            window_.present(picture_, picture_width_, picture_height_);
        if (script_done) break;
        // Played frames keep the scenario's pace: one time step per frame, no faster.
        if (!script_ && play) {
            std::this_thread::sleep_until(frame_start +
                                          std::chrono::duration_cast<Clock::duration>(
                                              std::chrono::duration<double>(scenario_.dt_s)));
        }
    }
    if (recording_) stopRecording();  // closing the window must not lose a flight
}

void Viewer::handle(const WindowEvent& e) {
    switch (e.type) {
        case WindowEvent::Type::KeyDown:
            held_.insert(e.key);
            onKey(e.key);
            break;
        case WindowEvent::Type::KeyUp:
            held_.erase(e.key);
            break;
        case WindowEvent::Type::MouseDown:
            dragging_ = true;
            break;
        case WindowEvent::Type::MouseUp:
            dragging_ = false;
            break;
        case WindowEvent::Type::CursorMove:
            if (dragging_ && have_cursor_ && (e.x != cursor_x_ || e.y != cursor_y_)) {
                startFlying();
                fly_.look(e.x - cursor_x_, e.y - cursor_y_);
                dirty_ = true;
            }
            cursor_x_ = e.x;
            cursor_y_ = e.y;
            have_cursor_ = true;
            break;
        case WindowEvent::Type::Scroll:
            fly_.changeSpeed(e.y);
            dirty_ = true;
            break;
        case WindowEvent::Type::Resize:
            dirty_ = true;
            break;
        case WindowEvent::Type::Close:
            quit_ = true;
            break;
    }
}

void Viewer::onKey(std::string_view key) {
    uint32_t index = 0;
    const size_t count = cullerRows().size();
    switch (actionForKey(key, &index)) {
        case ViewAction::None:
            return;
        case ViewAction::Quit:
            quit_ = true;
            break;
        case ViewAction::TogglePause:
            paused_ = !paused_;
            break;
        case ViewAction::Step:
            if (paused_)
                step_ = true;
            else
                say("n steps one frame while paused (space)");
            break;
        case ViewAction::Restart:
            restart();
            say(recording_ ? "restarted: the recording starts over" : "restarted at frame 0");
            break;
        case ViewAction::NextAlgorithm:
            algorithm_ =
                held("shift") ? (algorithm_ + count - 1) % count : (algorithm_ + 1) % count;
            replaceSimulation(true);
            updateTitle();
            break;
        case ViewAction::SelectAlgorithm:
            if (index >= count) {
                say("there are " + std::to_string(count) + " algorithms");
                break;
            }
            algorithm_ = index;
            replaceSimulation(true);
            updateTitle();
            break;
        case ViewAction::ToggleBoxes:
            boxes_ = !boxes_;
            break;
        case ViewAction::ToggleBirdsEye:
            birds_eye_ = !birds_eye_;
            break;
        case ViewAction::ToggleError:
            error_ = !error_;
            if (!error_) validation_ = false;  // the overlay needs ground truth
            replaceSimulation(true);
            break;
        case ViewAction::ToggleValidation:
            validation_ = !validation_;
            if (validation_ && !error_) {
                error_ = true;
                replaceSimulation(true);
                say("validation needs ground truth: turned on (g)");
            }
            break;
        case ViewAction::ToggleCameraMode:
            if (flying_) {
                if (recording_) stopRecording();  // a recording is a flight
                flying_ = false;
            } else {
                startFlying();
            }
            break;
        case ViewAction::ToggleRecording:
            if (recording_)
                stopRecording();
            else
                startRecording();
            break;
        case ViewAction::Screenshot:
            screenshot_ = true;
            break;
        case ViewAction::ToggleHelp:
            help_ = !help_;
            break;
        case ViewAction::TogglePanel:
            panel_ = !panel_;
            break;
    }
    dirty_ = true;
}

FlyInput Viewer::flyInput() const {
    FlyInput in;
    in.forward = int(held("w")) - int(held("s"));
    in.right = int(held("d")) - int(held("a"));
    in.up = int(held("e")) - int(held("q"));
    in.turn_right = int(held("right")) - int(held("left"));
    in.turn_up = int(held("up")) - int(held("down"));
    in.fast = held("shift");
    return in;
}

// Flying starts from wherever the path has the camera now.
void Viewer::startFlying() {
    if (flying_) return;
    fly_.setPose(currentPose(false));
    flying_ = true;
}

CameraPose Viewer::currentPose(bool play) const {
    if (flying_) return fly_.pose();
    // Playing shows the next frame's pose; paused holds the last one shown.
    const uint32_t frame = play ? next_played_ : (next_played_ > 0 ? next_played_ - 1 : 0);
    return sampleCameraPath(scenario_.camera, frame * scenario_.dt_s);
}

void Viewer::renderFrame(bool play) {
    // Following the path, the scenario plays in a loop; a flight goes on as long as you fly.
    if (play && !flying_ && next_played_ >= scenario_.frames) restart();
    renderer_.resize(window_.framebufferWidth(), window_.framebufferHeight());

    const CameraPose pose = currentPose(play);
    LiveControls live;
    live.camera = pose;
    live.width = renderer_.width();
    live.height = renderer_.height();
    // Played frame 0 shows the initial world, as frame 0 of a run does; paused frames hold it.
    live.hold_world = !play || next_played_ == 0;
    live.trace_every_frame = boxes_ || birds_eye_;
    world_->setLiveControls(live);
    world_->advance();
    stats_ = sim_->renderFrame();
    has_stats_ = true;
    if (play) {
        shown_time_ = next_played_ * scenario_.dt_s;
        if (recording_) recorded_.push_back({shown_time_, pose.position, pose.target});
        ++next_played_;
    }

    renderer_.readColor(rgba_);
    ViewLayers layers;
    layers.boxes = boxes_;
    layers.birds_eye = birds_eye_;
    layers.hud = panel_;
    layers.validation = validation_;
    // Ground truth of this frame, already rendered for its error (kept, not rendered again).
    if (validation_ && error_) layers.truth_ids = truth_.of(*world_).ids;
    const RasterCanvas picture = composeViewPicture(rgba_, renderer_.width(), renderer_.height(),
                                                    *sim_, scenario_.camera, layers, hudState());
    picture_ = picture.rgbaBottomUp();
    picture_width_ = picture.width();
    picture_height_ = picture.height();
    if (message_frames_ > 0 && --message_frames_ == 0) message_.clear();
}

HudState Viewer::hudState() const {
    HudState h;
    h.scenario = scenario_.name;
    h.algorithm = std::string(algorithm().name);
    h.algorithm_place = static_cast<uint32_t>(algorithm_ + 1);
    h.algorithm_count = static_cast<uint32_t>(cullerRows().size());
    h.frame = next_played_ > 0 ? next_played_ - 1 : 0;
    h.time_s = shown_time_;
    h.paused = paused_;
    h.flying = flying_;
    h.fly_speed_mps = fly_.speed();
    h.recording = recording_;
    h.recorded_frames = static_cast<uint32_t>(recorded_.size());
    h.error_on = error_;
    h.has_stats = has_stats_;
    h.stats = stats_;
    h.legend = boxes_;
    h.validation_legend = validation_;
    h.help = help_;
    h.message = message_;
    return h;
}

void Viewer::say(const std::string& message) {
    message_ = message;
    message_frames_ = kMessageFrames;
}

void Viewer::updateTitle() {
    window_.setTitle("occsim view: " + scenario_.name + " - " + std::string(algorithm().name));
}

void Viewer::saveScreenshot() {
    screenshot_ = false;
    if (picture_.empty()) return;
    try {
        std::filesystem::create_directories(options_.out_dir);
        const std::filesystem::path file = nextFreeFile(options_.out_dir, "screenshot-", ".png");
        writeFileAtomically(file, encodePngBottomUp(picture_, picture_width_, picture_height_));
        std::printf("screenshot: %s\n", file.string().c_str());
        std::fflush(stdout);
        say("saved " + file.string());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "occsim view: screenshot not saved: %s\n", e.what());
        say("screenshot not saved");
    }
}

void Viewer::startRecording() {
    startFlying();
    restart();
    recording_ = true;
    say("recording from frame 0, r stops and saves");
}

void Viewer::stopRecording() {
    recording_ = false;
    if (recorded_.empty()) {
        say("nothing recorded (no frame was played)");
        return;
    }
    try {
        std::filesystem::create_directories(options_.out_dir);
        const std::filesystem::path file =
            nextFreeFile(options_.out_dir, safeFileName(scenario_.name) + "-recorded-", ".json");
        writeRecordedScenario(scenario_text_, scenario_, recorded_, file);
        std::printf("recorded: %s (%zu frames); replay it with: occsim run %s\n",
                    file.string().c_str(), recorded_.size(), file.string().c_str());
        std::fflush(stdout);
        say("saved " + file.string());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "occsim view: recording not saved: %s\n", e.what());
        say("recording not saved");
    }
    recorded_.clear();
}

}  // namespace

int runViewer(const Scenario& scenario, const std::string& scenario_text,
              const ViewOptions& options) {
    Viewer viewer(scenario, scenario_text, options);
    viewer.run();
    return 0;
}

}  // namespace occsim
