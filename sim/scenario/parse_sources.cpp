// The keys of each scene source type (docs/scenario-format.md, "Scene sources"). Limits keep a
// typo from asking for a scene that cannot fit in memory.
#include "sim/scenario/parser_parts.h"

namespace occsim {
namespace {

constexpr uint64_t kMaxTeapots = 1'000'000;
constexpr uint64_t kMaxTessellation = 64;
constexpr uint64_t kMaxGridSide = 1000;
constexpr uint64_t kMaxCopies = 100'000;

uint32_t count(JsonObjectReader& r, std::string_view key, uint32_t fallback, uint64_t min,
               uint64_t max) {
    return static_cast<uint32_t>(r.unsignedInteger(key, fallback, min, max));
}

GltfReplication readReplication(JsonObjectReader replicate) {
    static const std::vector<std::string> kModes = {"grid", "random"};
    GltfReplication r;
    if (replicate.requiredEnumeration("mode", kModes) == "grid") {
        r.mode = GltfReplication::Mode::Grid;
        r.count_x = count(replicate, "count_x", r.count_x, 1, kMaxGridSide);
        r.count_z = count(replicate, "count_z", r.count_z, 1, kMaxGridSide);
        r.spacing_m = replicate.number("spacing", r.spacing_m, NumberRange::atLeast(0.0));
        for (const char* other : {"count", "region", "random_yaw"}) {
            if (replicate.has(other)) {
                replicate.fail(other,
                               std::string("'") + other + "' applies to mode \"random\" only");
            }
        }
    } else {
        r.mode = GltfReplication::Mode::Random;
        r.count = count(replicate, "count", r.count, 1, kMaxCopies);
        r.region = readRegion(replicate.required("region"));
        r.random_yaw = replicate.boolean("random_yaw", r.random_yaw);
        for (const char* other : {"count_x", "count_z", "spacing"}) {
            if (replicate.has(other)) {
                replicate.fail(other, std::string("'") + other + "' applies to mode \"grid\" only");
            }
        }
    }
    replicate.finish();
    return r;
}

// "animation": which of the file's animations play and how (names and indices are checked
// against the file when the scene is built).
GltfAnimationSpec readAnimationPlayback(JsonObjectReader animation) {
    static const std::vector<std::string> kModes = {"loop", "clamp", "ping_pong"};
    GltfAnimationSpec spec;
    if (const auto play = animation.optional("play")) {
        if (play->json().is_string()) {
            spec.play_all = play->asEnum({"all", "none"}) == "all";
        } else if (play->json().is_array()) {
            spec.play_all = false;
            const JsonArrayReader list = play->asArray();
            list.requireAtLeast(1, "animation name or index");
            for (std::size_t i = 0; i < list.size(); ++i) {
                const JsonValueReader item = list.at(i);
                AnimationPick pick;
                if (item.json().is_string()) {
                    pick.name = item.asString();
                    if (pick.name.empty()) item.failExpected("an animation name or index");
                } else if (item.json().is_number()) {
                    pick.index = static_cast<uint32_t>(item.asUnsigned(0, UINT32_MAX));
                } else {
                    item.failExpected("an animation name or index");
                }
                spec.play.push_back(pick);
            }
        } else {
            play->failExpected("\"all\", \"none\" or a list of animation names and indices");
        }
    }
    spec.speed = animation.number("speed", spec.speed, NumberRange::closed(0.0, 1000.0));
    const std::string mode = animation.enumeration("mode", kModes, "loop");
    spec.mode = mode == "loop"    ? AnimationMode::Loop
                : mode == "clamp" ? AnimationMode::Clamp
                                  : AnimationMode::PingPong;
    spec.time_offset_s =
        animation.number("time_offset", spec.time_offset_s, NumberRange::closed(-1e6, 1e6));
    spec.random_phase = animation.boolean("random_phase", spec.random_phase);
    animation.finish();
    return spec;
}

}  // namespace

TeapotFieldSpec readTeapotField(JsonObjectReader& source) {
    TeapotFieldSpec spec;
    spec.count = count(source, "count", spec.count, 1, kMaxTeapots);
    if (const auto region = source.optional("region")) spec.region = readRegion(*region);
    const auto size =
        source.range("size", {spec.size_min_m, spec.size_max_m}, NumberRange::greaterThan(0.0));
    spec.size_min_m = size.first;
    spec.size_max_m = size.second;
    spec.tessellation = count(source, "tessellation", spec.tessellation, 1, kMaxTessellation);
    return spec;
}

GltfSourceSpec readGltfSource(JsonObjectReader& source, const std::filesystem::path& scenario_dir) {
    GltfSourceSpec spec;
    const JsonValueReader path = source.required("path");
    const std::string text = path.asString();
    if (text.empty()) path.failExpected("a path to a .gltf or .glb file");
    spec.path = scenario_dir / text;
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(spec.path, ec);
    if (std::filesystem::is_directory(status)) {
        path.fail("expected a .gltf or .glb file, got a directory: " + spec.path.string());
    }
    if (!std::filesystem::is_regular_file(status)) {
        path.fail("no such file: " + spec.path.string());
    }
    spec.scale = source.number("scale", spec.scale, NumberRange::greaterThan(0.0));
    spec.offset = source.vec3("offset", spec.offset);
    if (auto replicate = source.optionalObject("replicate")) {
        spec.replicate = readReplication(std::move(*replicate));
    }
    spec.place = source.boolean("place", spec.place);
    if (!spec.place && source.has("replicate")) {
        source.fail("replicate", "a source with \"place\": false places no copies to replicate");
    }
    if (auto animation = source.optionalObject("animation")) {
        spec.animation = readAnimationPlayback(std::move(*animation));
    }
    const std::string lights =
        source.enumeration("lights", {"shadows", "no_shadows", "ignore"}, "shadows");
    spec.lights = lights == "ignore"       ? GltfLights::Ignore
                  : lights == "no_shadows" ? GltfLights::NoShadows
                                           : GltfLights::Shadows;
    return spec;
}

CitySpec readCity(JsonObjectReader& source) {
    CitySpec spec;
    spec.blocks_x = count(source, "blocks_x", spec.blocks_x, 1, 200);
    spec.blocks_z = count(source, "blocks_z", spec.blocks_z, 1, 200);
    spec.block_size_m =
        source.number("block_size", spec.block_size_m, NumberRange::closed(5, 1000));
    spec.street_width_m =
        source.number("street_width", spec.street_width_m, NumberRange::closed(2, 200));
    const auto height = source.range("height", {spec.height_min_m, spec.height_max_m},
                                     NumberRange::closed(1, 2000));
    spec.height_min_m = height.first;
    spec.height_max_m = height.second;
    spec.buildings_per_block =
        count(source, "buildings_per_block", spec.buildings_per_block, 1, 64);
    return spec;
}

LibrarySpec readLibrary(JsonObjectReader& source) {
    LibrarySpec spec;
    spec.rows = count(source, "rows", spec.rows, 1, 200);
    spec.shelves_per_row = count(source, "shelves_per_row", spec.shelves_per_row, 1, 200);
    spec.levels = count(source, "levels", spec.levels, 1, 20);
    spec.books_per_level = count(source, "books_per_level", spec.books_per_level, 1, 200);
    spec.aisle_width_m =
        source.number("aisle_width", spec.aisle_width_m, NumberRange::closed(0.5, 20));
    return spec;
}

PlantSpec readPlant(JsonObjectReader& source) {
    PlantSpec spec;
    spec.units_x = count(source, "units_x", spec.units_x, 1, 50);
    spec.units_z = count(source, "units_z", spec.units_z, 1, 50);
    spec.unit_size_m = source.number("unit_size", spec.unit_size_m, NumberRange::closed(5, 500));
    spec.floors = count(source, "floors", spec.floors, 1, 20);
    spec.floor_height_m =
        source.number("floor_height", spec.floor_height_m, NumberRange::closed(2.5, 100));
    spec.pipes_per_unit = count(source, "pipes_per_unit", spec.pipes_per_unit, 0, 1000);
    spec.tanks_per_unit = count(source, "tanks_per_unit", spec.tanks_per_unit, 0, 100);
    return spec;
}

}  // namespace occsim
