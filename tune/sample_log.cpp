#include "tune/sample_log.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sim/output/atomic_file.h"
#include "tune/errors.h"

namespace occsim::tune {
namespace {

using Json = nlohmann::json;
constexpr int kLogVersion = 1;

Json settingsJson(const LogSettings& s) {
    Json bounds = Json::array();
    for (const Bounds& b : s.bounds) bounds.push_back({b.lo, b.hi});
    return {{"occtune_sample_log", kLogVersion},
            {"scenario", s.scenario_file},
            {"scenario_name", s.scenario_name},
            {"scenario_hash", s.scenario_hash},
            {"algorithm", s.algorithm},
            {"parameters", s.parameters},
            {"bounds", bounds},
            {"frames", s.frames},
            {"warmup_frames", s.warmup_frames},
            {"seed", s.seed},
            {"initial_samples", s.initial_samples}};
}

LogSettings settingsOf(const Json& j) {
    LogSettings s;
    if (j.at("occtune_sample_log").get<int>() != kLogVersion)
        throw std::runtime_error("unknown log version");
    s.scenario_file = j.at("scenario").get<std::string>();
    s.scenario_name = j.at("scenario_name").get<std::string>();
    s.scenario_hash = j.at("scenario_hash").get<uint64_t>();
    // Logs from before occtune --algo tuned the statistical culler.
    s.algorithm = j.contains("algorithm") ? j.at("algorithm").get<std::string>() : "statistical";
    s.parameters = j.at("parameters").get<std::vector<std::string>>();
    for (const Json& b : j.at("bounds"))
        s.bounds.push_back({b.at(0).get<double>(), b.at(1).get<double>()});
    s.frames = j.at("frames").get<uint32_t>();
    s.warmup_frames = j.at("warmup_frames").get<uint32_t>();
    s.seed = j.at("seed").get<uint64_t>();
    s.initial_samples = j.at("initial_samples").get<uint32_t>();
    if (s.bounds.size() != s.parameters.size())
        throw std::runtime_error("bounds and parameters differ in number");
    return s;
}

Json runJson(const LoggedRun& r) {
    Json frames = Json::array();
    for (const FrameCounts& f : r.frames)
        frames.push_back({f.frame_ms, f.queries, f.triangles, f.objects_drawn, f.wait_ms});
    return {{"batch", r.batch},   {"kind", r.reference ? "reference" : "sample"},
            {"values", r.values}, {"mean_ms", r.mean_ms},
            {"p95_ms", r.p95_ms}, {"error_pixels", r.error_pixels},
            {"frames", frames}};
}

LoggedRun runOf(const Json& j, size_t parameters) {
    LoggedRun r;
    r.batch = j.at("batch").get<uint32_t>();
    const std::string kind = j.at("kind").get<std::string>();
    if (kind != "reference" && kind != "sample")
        throw std::runtime_error("kind must be reference or sample");
    r.reference = kind == "reference";
    r.values = j.at("values").get<std::vector<double>>();
    if (r.values.size() != parameters)
        throw std::runtime_error("values do not match the parameters");
    r.mean_ms = j.at("mean_ms").get<double>();
    r.p95_ms = j.at("p95_ms").get<double>();
    r.error_pixels = j.at("error_pixels").get<int64_t>();
    for (const Json& f : j.at("frames")) {
        r.frames.push_back({f.at(0).get<double>(), f.at(1).get<double>(), f.at(2).get<double>(),
                            f.at(3).get<double>(), f.at(4).get<double>()});
    }
    return r;
}

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ",") + x;
    return s;
}

}  // namespace

uint64_t textHash(const std::string& text) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : text) {
        h ^= c;
        h *= 0x100000001b3ull;
    }
    return h;
}

SampleLog::SampleLog(std::filesystem::path file, LogSettings settings)
    : file_(std::move(file)),
      settings_(std::move(settings)),
      text_(settingsJson(settings_).dump() + "\n") {}

SampleLog SampleLog::read(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw TuneInputError("--resume: cannot read the sample log " + file.string());
    std::string line;
    size_t number = 0;
    SampleLog log(file, {});
    log.text_.clear();
    try {
        while (std::getline(in, line)) {
            ++number;
            const Json j = Json::parse(line);
            if (number == 1) {
                log.settings_ = settingsOf(j);
            } else {
                log.runs_.push_back(runOf(j, log.settings_.parameters.size()));
            }
            log.text_ += line + "\n";
        }
    } catch (const std::exception& e) {
        throw TuneInputError("--resume: " + file.string() + ":" + std::to_string(number) +
                             ": not an occtune sample log line (" + e.what() + ")");
    }
    if (number == 0) throw TuneInputError("--resume: " + file.string() + " is empty");
    // Every batch needs a reference: the samples are ratios to it.
    std::map<uint32_t, int> references;
    for (const LoggedRun& r : log.runs_) references[r.batch] += r.reference;
    for (const auto& [batch, count] : references) {
        if (count < 1) {
            throw TuneInputError("--resume: " + file.string() + ": batch " + std::to_string(batch) +
                                 " has no reference run");
        }
    }
    return log;
}

uint32_t SampleLog::batches() const {
    uint32_t n = 0;
    for (const LoggedRun& r : runs_) n = std::max(n, r.batch + 1);
    return n;
}

namespace {

struct ReferenceFigures {
    double mean_ms = 0.0, p95_ms = 0.0;
    std::vector<const LoggedRun*> runs;
};

std::map<uint32_t, ReferenceFigures> referencesOf(const std::vector<LoggedRun>& runs) {
    std::map<uint32_t, ReferenceFigures> references;
    for (const LoggedRun& r : runs) {
        if (r.reference) references[r.batch].runs.push_back(&r);
    }
    for (auto& [batch, ref] : references) {
        for (const LoggedRun* r : ref.runs) {
            ref.mean_ms += r->mean_ms / static_cast<double>(ref.runs.size());
            ref.p95_ms += r->p95_ms / static_cast<double>(ref.runs.size());
        }
    }
    return references;
}

}  // namespace

std::vector<Sample> SampleLog::samples() const {
    const std::map<uint32_t, ReferenceFigures> references = referencesOf(runs_);
    std::vector<Sample> out;
    for (const LoggedRun& r : runs_) {
        if (r.reference) continue;
        const ReferenceFigures& ref = references.at(r.batch);
        out.push_back({&r, r.mean_ms / ref.mean_ms, r.p95_ms / ref.p95_ms});
    }
    return out;
}

std::vector<Sample> SampleLog::referenceSamples() const {
    const std::map<uint32_t, ReferenceFigures> references = referencesOf(runs_);
    std::vector<Sample> out;
    for (const LoggedRun& r : runs_) {
        if (!r.reference) continue;
        const ReferenceFigures& ref = references.at(r.batch);
        out.push_back({&r, r.mean_ms / ref.mean_ms, r.p95_ms / ref.p95_ms});
    }
    return out;
}

double SampleLog::referenceNoise() const {
    double squared = 0.0;
    size_t pairs = 0;
    for (const auto& [batch, ref] : referencesOf(runs_)) {
        if (ref.runs.size() < 2) continue;
        const double l = std::log(ref.runs[1]->mean_ms / ref.runs[0]->mean_ms);
        squared += l * l;
        ++pairs;
    }
    // log(B / A) of two runs with independent noise s has spread s * sqrt(2).
    return pairs > 0 ? std::sqrt(squared / static_cast<double>(pairs) / 2.0) : 0.0;
}

void SampleLog::appendBatch(const std::vector<LoggedRun>& batch) {
    std::string text = text_;
    for (const LoggedRun& r : batch) text += runJson(r).dump() + "\n";
    writeFileAtomically(file_, text);
    text_ = std::move(text);
    runs_.insert(runs_.end(), batch.begin(), batch.end());
}

std::string SampleLog::mismatch(const LogSettings& o) const {
    const LogSettings& s = settings_;
    if (s.scenario_hash != o.scenario_hash || s.scenario_name != o.scenario_name) {
        return "the log was written for another scenario (or the file changed since): " +
               s.scenario_file;
    }
    if (s.algorithm != o.algorithm) return "the log was written with --algo " + s.algorithm;
    if (s.parameters != o.parameters)
        return "the log was written with --params " + join(s.parameters);
    for (size_t j = 0; j < s.bounds.size(); ++j) {
        if (s.bounds[j].lo != o.bounds[j].lo || s.bounds[j].hi != o.bounds[j].hi) {
            std::ostringstream why;
            why << "the log was written with --bounds " << s.parameters[j] << "=" << s.bounds[j].lo
                << ":" << s.bounds[j].hi;
            return why.str();
        }
    }
    if (s.frames != o.frames)
        return "the log was written with --frames " + std::to_string(s.frames);
    if (s.warmup_frames != o.warmup_frames)
        return "the log was written with " + std::to_string(s.warmup_frames) + " warm-up frames";
    if (s.seed != o.seed) return "the log was written with --seed " + std::to_string(s.seed);
    return "";
}

}  // namespace occsim::tune
