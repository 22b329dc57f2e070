#include "haptics/haptic_recording.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.hpp"
#include "util/json_document.hpp"
#include "util/json_fields.hpp"

namespace sandtin::haptics {

namespace {

[[noreturn]] void bad(const std::string& name, const std::string& what) {
    throw JsonInputError(name + ": " + what);
}

/// A field the reader does not know is an error, as in scripts: a typo must not be ignored.
void reject_unknown(const nlohmann::json& j, std::initializer_list<const char*> known,
                    const std::string& name) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        if (std::find_if(known.begin(), known.end(),
                         [&](const char* k) { return it.key() == k; }) == known.end()) {
            bad(name, "unknown field \"" + it.key() + "\"");
        }
    }
}

const nlohmann::json& field(const nlohmann::json& j, const char* key, const std::string& name) {
    if (!j.contains(key)) bad(name, std::string("missing field \"") + key + "\"");
    return j.at(key);
}

double number(const nlohmann::json& v, const std::string& name, const std::string& what) {
    if (!v.is_number()) bad(name, what + " must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) bad(name, what + " must be finite");
    return d;
}

std::uint64_t count(const nlohmann::json& v, const std::string& name, const std::string& what) {
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<std::int64_t>() >= 0))
        bad(name, what + " must be a non-negative integer");
    return v.get<std::uint64_t>();
}

std::uint32_t buttons(const nlohmann::json& v, const std::string& name, const std::string& what) {
    const std::uint64_t b = count(v, name, what);
    if (b > 0xFFFFFFFFu) bad(name, what + " does not fit 32 bits");
    return static_cast<std::uint32_t>(b);
}

const nlohmann::json& row(const nlohmann::json& rows, std::size_t i, std::size_t width,
                          const std::string& name, const char* what) {
    const nlohmann::json& r = rows[i];
    if (!r.is_array() || r.size() != width) {
        bad(name, std::string(what) + "[" + std::to_string(i) + "] must be an array of " +
                      std::to_string(width) + " numbers");
    }
    return r;
}

nlohmann::json summary_json(const TerrainSummary& s) {
    return {{"vertices", s.vertices}, {"volume", s.volume}};
}

TerrainSummary summary_from(const nlohmann::json& j, const std::string& name) {
    if (!j.is_object()) bad(name, "must be an object");
    TerrainSummary s;
    s.vertices = count(field(j, "vertices", name), name, "vertices");
    s.volume = number(field(j, "volume", name), name, "volume");
    return s;
}

}  // namespace

TerrainSummary summarise(const Tin& tin) {
    return {tin.vertex_count(), tin.volume()};
}

Tin make_recording_terrain(const ScriptTerrain& t, TinOptions options) {
    const Rect domain = Rect::from_size(t.size.x, t.size.y);
    if (t.points == 0) return Tin::flat_rectangle(domain, t.height, options);
    return Tin::random_points(
        domain, t.points, t.seed, [&t](Vec2) { return t.height; }, options);
}

nlohmann::json recording_to_json(const HapticRecording& r) {
    nlohmann::json j;
    j["format"] = kRecordingFormat;
    j["version"] = kRecordingVersion;
    j["rate_hz"] = r.rate_hz;
    j["tool"] = r.tool;
    j["edit"] = {{"spacing", r.edit.spacing},
                 {"erode_iterations", r.edit.erode_iterations},
                 {"button_mask", r.edit.button_mask},
                 {"relocation_radius", r.edit.physics.relocation_radius},
                 {"damping", r.edit.physics.damping},
                 {"rest_tolerance", r.edit.physics.rest_tolerance}};
    if (r.terrain) {
        j["terrain"] = {{"size", {r.terrain->size.x, r.terrain->size.y}},
                        {"points", r.terrain->points},
                        {"seed", r.terrain->seed},
                        {"height", r.terrain->height}};
    }
    nlohmann::json start = {{"next_generation", r.next_generation}};
    if (r.start) {
        start["vertices"] = r.start->vertices;
        start["volume"] = r.start->volume;
    }
    j["start"] = start;
    nlohmann::json ticks = nlohmann::json::array();
    for (const RecordedTick& t : r.ticks) {
        ticks.push_back(
            {t.position.x, t.position.y, t.position.z, t.buttons, t.force.x, t.force.y, t.force.z});
    }
    j["ticks"] = std::move(ticks);
    nlohmann::json edits = nlohmann::json::array();
    for (const EditInput& e : r.edits)
        edits.push_back({e.tick, e.position.x, e.position.y, e.position.z, e.buttons});
    j["edits"] = std::move(edits);
    if (r.result) j["result"] = summary_json(*r.result);
    return j;
}

namespace {

/// Fails on edit.spacing, before anything runs, when the edits' pressed stretches (the button
/// in `edit.button_mask` held at both ends, as the live editor stamps them) are longer than
/// kMaxPlacementsPerOperation spacings.
void check_stamp_count(const HapticRecording& r, const std::string& en) {
    double pressed_length = 0.0;
    for (std::size_t i = 1; i < r.edits.size(); ++i) {
        const EditInput& a = r.edits[i - 1];
        const EditInput& b = r.edits[i];
        if ((a.buttons & r.edit.button_mask) == 0 || (b.buttons & r.edit.button_mask) == 0)
            continue;
        pressed_length += std::hypot(b.position.x - a.position.x, b.position.y - a.position.y);
    }
    const double stamps = pressed_length / r.edit.spacing;
    if (stamps <= kMaxPlacementsPerOperation) return;
    std::ostringstream what;
    what << "spacing of " << r.edit.spacing << " m along the " << pressed_length
         << " m the edits stroke asks for " << stamps << " stamps, more than the "
         << static_cast<long>(kMaxPlacementsPerOperation) << " a replay may place";
    bad(en, what.str());
}

}  // namespace

HapticRecording recording_from_json(const nlohmann::json& j, const std::string& name) {
    if (!j.is_object()) bad(name, "a haptic recording must be a JSON object");
    const nlohmann::json& format = field(j, "format", name);
    if (!format.is_string() || format.get<std::string>() != kRecordingFormat)
        bad(name, "\"format\" must be \"" + std::string(kRecordingFormat) + "\"");
    const std::uint64_t version = count(field(j, "version", name), name, "version");
    if (version != kRecordingVersion)
        bad(name, "unsupported recording version " + std::to_string(version));
    reject_unknown(j,
                   {"format", "version", "rate_hz", "tool", "edit", "terrain", "start", "ticks",
                    "edits", "result"},
                   name);
    HapticRecording r;
    r.rate_hz = number(field(j, "rate_hz", name), name, "rate_hz");
    if (!(r.rate_hz > 0.0)) bad(name, "rate_hz must be positive");
    r.tool = field(j, "tool", name);
    if (!r.tool.is_object()) bad(name, "\"tool\" must be a tool object");

    const nlohmann::json& edit = field(j, "edit", name);
    if (!edit.is_object()) bad(name, "\"edit\" must be an object");
    const std::string en = name + ": edit";
    reject_unknown(edit,
                   {"spacing", "erode_iterations", "button_mask", "relocation_radius", "damping",
                    "rest_tolerance"},
                   en);
    r.edit.spacing = number(field(edit, "spacing", en), en, "spacing");
    if (!(r.edit.spacing > 0.0)) bad(en, "spacing must be positive");
    const std::uint64_t erode = count(field(edit, "erode_iterations", en), en, "erode_iterations");
    if (erode > 1000) bad(en, "erode_iterations must be at most 1000");
    r.edit.erode_iterations = static_cast<int>(erode);
    r.edit.button_mask = buttons(field(edit, "button_mask", en), en, "button_mask");
    if (edit.contains("relocation_radius"))
        r.edit.physics.relocation_radius =
            number(edit["relocation_radius"], en, "relocation_radius");
    if (edit.contains("damping")) r.edit.physics.damping = number(edit["damping"], en, "damping");
    if (edit.contains("rest_tolerance"))
        r.edit.physics.rest_tolerance = number(edit["rest_tolerance"], en, "rest_tolerance");
    if (r.edit.physics.relocation_radius < 0.0 || !(r.edit.physics.damping > 0.0) ||
        r.edit.physics.damping > 1.0 || r.edit.physics.rest_tolerance < 0.0) {
        bad(en,
            "physics parameters out of range (relocation_radius >= 0, damping in (0, 1], "
            "rest_tolerance >= 0)");
    }

    if (j.contains("terrain")) {
        const nlohmann::json& t = j["terrain"];
        const std::string tn = name + ": terrain";
        if (!t.is_object()) bad(tn, "must be an object");
        reject_unknown(t, {"size", "points", "seed", "height"}, tn);
        ScriptTerrain terrain;
        const nlohmann::json& size = field(t, "size", tn);
        if (!size.is_array() || size.size() != 2) bad(tn, "size must be [width, height]");
        terrain.size = {number(size[0], tn, "size[0]"), number(size[1], tn, "size[1]")};
        if (!(terrain.size.x > 0.0) || !(terrain.size.y > 0.0)) bad(tn, "size must be positive");
        terrain.points = count(field(t, "points", tn), tn, "points");
        if (terrain.points > 10'000'000) bad(tn, "points must be at most 10000000");
        terrain.seed = count(field(t, "seed", tn), tn, "seed");
        terrain.height = number(field(t, "height", tn), tn, "height");
        if (!(std::abs(terrain.height) <= kMaxHeight))
            bad(tn, "height must lie within -1e9 and 1e9 m");
        r.terrain = terrain;
    }
    const nlohmann::json& start = field(j, "start", name);
    if (!start.is_object()) bad(name, "\"start\" must be an object");
    reject_unknown(start, {"next_generation", "vertices", "volume"}, name + ": start");
    const std::uint64_t generation =
        count(field(start, "next_generation", name + ": start"), name, "start.next_generation");
    if (generation < 1 || generation > 0xFFFFFFFFu)
        bad(name, "start.next_generation must be in [1, 2^32)");
    r.next_generation = static_cast<Generation>(generation);
    if (start.contains("vertices") || start.contains("volume"))
        r.start = summary_from(start, name + ": start");

    const nlohmann::json& ticks = field(j, "ticks", name);
    if (!ticks.is_array()) bad(name, "\"ticks\" must be an array");
    r.ticks.reserve(ticks.size());
    for (std::size_t i = 0; i < ticks.size(); ++i) {
        const nlohmann::json& t = row(ticks, i, 7, name, "ticks");
        const std::string what = "ticks[" + std::to_string(i) + "]";
        r.ticks.push_back(
            {{number(t[0], name, what), number(t[1], name, what), number(t[2], name, what)},
             buttons(t[3], name, what),
             {number(t[4], name, what), number(t[5], name, what), number(t[6], name, what)}});
    }
    const nlohmann::json& edits = field(j, "edits", name);
    if (!edits.is_array()) bad(name, "\"edits\" must be an array");
    r.edits.reserve(edits.size());
    for (std::size_t i = 0; i < edits.size(); ++i) {
        const nlohmann::json& e = row(edits, i, 5, name, "edits");
        const std::string what = "edits[" + std::to_string(i) + "]";
        r.edits.push_back(
            {count(e[0], name, what),
             {number(e[1], name, what), number(e[2], name, what), number(e[3], name, what)},
             buttons(e[4], name, what)});
    }
    for (std::size_t i = 0; i < r.edits.size(); ++i) {
        // The pen's depth becomes the tool's bottom: a height like the terrain's.
        if (!(std::abs(r.edits[i].position.z) <= kMaxHeight))
            bad(name, "edits[" + std::to_string(i) + "] has a height beyond 1e9 m");
        // The simulation takes the device's latest pose, so its ticks never go back. Edits out
        // of tick order were reordered or spliced by hand: the replay, which follows the list,
        // would not be the session that was recorded.
        if (i > 0 && r.edits[i].tick < r.edits[i - 1].tick) {
            bad(name, "edits[" + std::to_string(i) + "] was taken at tick " +
                          std::to_string(r.edits[i].tick) + ", before edits[" +
                          std::to_string(i - 1) + "] (tick " + std::to_string(r.edits[i - 1].tick) +
                          "); edits must be in the order they were taken");
        }
    }
    check_stamp_count(r, en);
    if (j.contains("result")) {
        r.result = summary_from(j["result"], name + ": result");
        reject_unknown(j["result"], {"vertices", "volume"}, name + ": result");
    }
    return r;
}

std::string format_recording(const HapticRecording& recording) {
    return recording_to_json(recording).dump() + "\n";
}

HapticRecording parse_recording(std::string_view text, const std::string& name) {
    return recording_from_json(parse_json_document(text, name), name);
}

bool is_haptic_recording(std::string_view text) {
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object()) return false;
    const auto it = j.find("format");
    return it != j.end() && it->is_string() && it->get<std::string>() == kRecordingFormat;
}

void save_recording(const std::filesystem::path& path, const HapticRecording& recording) {
    const std::string text = format_recording(recording);
    write_file_atomically(
        path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                            text.size()));
}

HapticRecording load_recording(const std::filesystem::path& path) {
    const std::vector<std::uint8_t> bytes = read_file(path, 1ull << 31);
    return parse_recording(
        std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path.string());
}

}  // namespace sandtin::haptics
