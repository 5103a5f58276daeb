#include "tune/input.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "occsim/culling/registry/plugin_loader.h"
#include "sim/output/atomic_file.h"
#include "sim/world/world.h"
#include "tune/errors.h"
#include "tune/response_model.h"

namespace occsim::tune {
namespace {

namespace fs = std::filesystem;

// The space-filling start: 60 % of the budget, never fewer samples than the model needs.
uint32_t initialSamples(uint32_t budget, size_t dims) {
    const auto share = static_cast<uint32_t>(std::lround(0.6 * budget));
    return std::min(budget, std::max(static_cast<uint32_t>(minimumSamples(dims)), share));
}

std::string fileText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

std::vector<std::string> leaveOutInertParameters(ParameterSpace& space,
                                                 const OccluderRoleCounts& roles) {
    std::vector<std::string> left_out;
    for (size_t j = space.size(); j-- > 0;) {
        const TunableParameter& p = space.parameters[j];
        if (p.scope != OptionScope::OccludersBySize || roles.by_size > 0) continue;
        left_out.insert(left_out.begin(), p.name +
                                              ": no object's occluder role is chosen by size (" +
                                              occluderRolesText(roles) + "), so it cannot act");
        space.remove(j);
    }
    // Tuning nothing would fit noise.
    if (space.size() == 0 && !left_out.empty()) {
        throw TuneInputError("--params: nothing left to tune on this scene: " + left_out.front() +
                             "; expected a scene with objects whose occluder role is by_size");
    }
    return left_out;
}

CheckedInput checkInput(const TuneOptions& o) {
    CheckedInput c;
    for (const fs::path& plugin : o.plugins) {
        try {
            loadPlugin(plugin);
        } catch (const PluginError& e) {
            throw TuneInputError(std::string("--plugin ") + e.what());
        }
    }
    // The scenario first: it may load plugins of its own ("plugins"), whose cullers --algo names.
    c.scenario = parseScenarioFile(o.scenario);
    const CullerRow* algorithm = findCuller(o.algorithm);
    if (!algorithm) {
        throw TuneInputError("--algo: unknown algorithm '" + o.algorithm +
                             "'; expected one of: " + cullerNameList());
    }
    c.space = parseParameterSpace(*algorithm, o.params, o.bounds);
    if (o.frames) c.scenario.frames = *o.frames;
    // Builds the scene once so that a scene that cannot be built (a glTF file, a mover's object)
    // fails here, before any run, rather than in the first batch; and so that an option it gives
    // nothing to act on is left out of the fit before the budget is checked against the rest.
    const Scene scene = buildScene(c.scenario);
    c.left_out = leaveOutInertParameters(c.space, countOccluderRoles(scene));
    const size_t needed = minimumSamples(c.space.size());
    if (o.budget < needed) {
        throw TuneInputError("--budget " + std::to_string(o.budget) +
                             ": too small for the model: a quadratic in " +
                             std::to_string(c.space.size()) + " parameters has " +
                             std::to_string(ResponseModel::termCount(c.space.size())) +
                             " terms and needs at least " + std::to_string(needed) +
                             " samples (or tune fewer --params)");
    }
    if (o.batch < 1) throw TuneInputError("--batch: expected at least 1 sample per run");
    if (o.repetitions < 1) throw TuneInputError("--repetitions: expected at least 1");
    if (c.scenario.frames <= c.scenario.warmup_frames) {
        throw TuneInputError("--frames " + std::to_string(c.scenario.frames) +
                             ": the scenario has " + std::to_string(c.scenario.warmup_frames) +
                             " warm-up frames; expected more frames than that");
    }
    c.objects = scene.objectCount();
    c.triangles = scene.triangle_count;
    Scenario held_out = c.scenario;
    held_out.seed = o.holdout_seed.value_or(c.scenario.seed + 1);
    c.held_out_seed = held_out.seed;
    // The first frames show whether the movers move otherwise: a seed acts when the scene is
    // built (placements, picks, speeds, directions, phases), never later.
    c.held_out_effect =
        seedEffect(scene, buildScene(held_out), c.scenario.dt_s, std::min(c.scenario.frames, 30u));

    c.out_dir = o.out.empty() ? fs::path("out") / safeFileName(c.scenario.name) / "tune" : o.out;
    c.log_file = c.out_dir / "samples.jsonl";
    LogSettings& s = c.settings;
    s.scenario_file = o.scenario.string();
    s.scenario_name = c.scenario.name;
    s.scenario_hash = textHash(fileText(o.scenario));
    s.algorithm = algorithm->name;
    for (size_t j = 0; j < c.space.size(); ++j) {
        s.parameters.push_back(c.space.parameters[j].name);
        s.bounds.push_back(c.space.bounds[j]);
    }
    s.frames = c.scenario.frames;
    s.warmup_frames = c.scenario.warmup_frames;
    s.seed = o.seed;
    s.initial_samples = initialSamples(o.budget, c.space.size());
    return c;
}

SampleLog openLog(const TuneOptions& o, const CheckedInput& c) {
    std::error_code ec;
    const bool exists = fs::exists(c.log_file, ec);
    if (!o.resume) {
        if (exists) {
            throw TuneInputError(
                c.log_file.string() +
                " exists: continue that session with --resume, or choose another --out");
        }
        return SampleLog(c.log_file, c.settings);
    }
    if (!exists) throw TuneInputError("--resume: no sample log at " + c.log_file.string());
    SampleLog log = SampleLog::read(c.log_file);
    if (const std::string why = log.mismatch(c.settings); !why.empty())
        throw TuneInputError("--resume: " + why);
    return log;
}

}  // namespace occsim::tune
