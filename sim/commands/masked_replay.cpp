#include "sim/commands/masked_replay.h"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "render/png_writer.h"
#include "sim/commands/exit_codes.h"
#include "sim/output/atomic_file.h"
#include "sim/output/run_folder.h"
#include "sim/run/masked_replay.h"
#include "sim/scene/mocrec.h"

namespace occsim_cli {

CLI::App* addMaskedReplay(CLI::App& app, MaskedReplayFlags& flags) {
    CLI::App* replay = app.add_subcommand(
        "masked-replay",
        "Replay an occluder frame recorded by Intel's Masked Occlusion Culling (.mocrec) into "
        "masked's buffer and an exact one, and compare what they hide");
    replay->add_option("file", flags.file, "The recorded frame (.mocrec)")->required();
    replay->add_option("--out", flags.out,
                       "Folder for depth.png and summary.json (out/masked-replay/<file stem>)");
    replay->add_option("--seed", flags.seed, "Places the object-sized rectangles (1)");
    return replay;
}

namespace {

nlohmann::json tallyJson(const occsim::ReplayTally& t) {
    return {{"exact_hidden", t.exact_hidden},
            {"masked_hidden_too", t.both_hidden},
            {"share", t.share()},
            {"area_share", t.areaShare()},
            {"tests", t.tests},
            {"wrongly_hidden", t.wrongly_hidden},
            {"exact_hidden_pixels", t.exact_hidden_area}};
}

}  // namespace

int maskedReplayCommand(const MaskedReplayFlags& flags) {
    const std::filesystem::path file(flags.file);
    const std::string out =
        flags.out.empty() ? (std::filesystem::path("out/masked-replay") / file.stem()).string()
                          : flags.out;
    const occsim::FolderLock lock(out, false);
    occsim::checkRunFolder(occsim::resolvedFolder(out));
    const occsim::MocFrame frame = occsim::readMocrec(file);
    const std::vector<occsim::ReplayLayout> layouts = occsim::replayLayouts();
    const occsim::MaskedReplay replay = occsim::replayMaskedFrame(frame, layouts, flags.seed);

    std::printf("%s: %ux%u, near %g, %zu occluder batches, %llu triangles\n", flags.file.c_str(),
                frame.width, frame.height, frame.near_clip, frame.occluders.size(),
                static_cast<unsigned long long>(frame.triangles()));
    std::printf("%-6s %-13s %14s %12s %12s %16s %10s\n", "layout", "rectangles", "exact hides",
                "masked too", "by area", "masked wrongly", "raster ms");
    nlohmann::json summary = {{"file", flags.file},
                              {"width", frame.width},
                              {"height", frame.height},
                              {"near", frame.near_clip},
                              {"triangles", frame.triangles()},
                              {"layouts", nlohmann::json::array()}};
    uint64_t wrong = 0;
    for (const occsim::LayoutReplay& l : replay.layouts) {
        nlohmann::json sets = nlohmann::json::object();
        for (const occsim::ReplaySet& s : l.sets) {
            std::printf("%-6s %-13s %14llu %11.2f%% %11.2f%% %16llu %10.1f\n", l.layout.c_str(),
                        s.name.c_str(), static_cast<unsigned long long>(s.tally.exact_hidden),
                        100.0 * s.tally.share(), 100.0 * s.tally.areaShare(),
                        static_cast<unsigned long long>(s.tally.wrongly_hidden), l.raster_ms);
            sets[s.name] = tallyJson(s.tally);
        }
        std::printf("%-6s %-13s %14llu %11.2f%% %11.2f%% %16llu\n", l.layout.c_str(), "all",
                    static_cast<unsigned long long>(l.total.exact_hidden), 100.0 * l.total.share(),
                    100.0 * l.total.areaShare(),
                    static_cast<unsigned long long>(l.total.wrongly_hidden));
        wrong += l.total.wrongly_hidden;
        summary["layouts"].push_back({{"layout", l.layout},
                                      {"raster_ms", l.raster_ms},
                                      {"all", tallyJson(l.total)},
                                      {"sets", sets}});
    }

    uint32_t w = 0, h = 0;
    const std::vector<uint8_t> picture =
        occsim::replayDepthPicture(replay, frame.near_clip, &w, &h);
    occsim::StagedRunFolder folder(out);
    occsim::writeFileAtomically(folder.staging() / "depth.png",
                                occsim::encodePngBottomUp(picture, w, h));
    occsim::writeFileAtomically(folder.staging() / "summary.json", summary.dump(2) + "\n");
    folder.publish();
    std::printf("written: %s/{depth.png,summary.json} (depth: exact | masked %s)\n", out.c_str(),
                layouts.front().name.c_str());
    if (wrong > 0) {
        std::fprintf(stderr,
                     "masked-replay: %llu rectangle tests masked hides are seen by the exact "
                     "buffer: not conservative\n",
                     static_cast<unsigned long long>(wrong));
        return kExitFailure;
    }
    return 0;
}

}  // namespace occsim_cli
