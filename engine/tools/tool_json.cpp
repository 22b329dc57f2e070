#include "tools/tool_json.hpp"

#include "util/asset_path.hpp"
#include "util/json_document.hpp"
#include "util/json_fields.hpp"

namespace sandtin {

namespace {

void apply_fields(ToolSpec& spec, JsonFields& f, const std::filesystem::path& base_dir) {
    spec.name = f.text("name", spec.name);
    if (f.has("contour")) {
        const std::string c = f.choice("contour", "circle", {"circle", "rectangle", "polygon"});
        spec.contour = c == "circle"      ? ContourKind::Circle
                       : c == "rectangle" ? ContourKind::Rectangle
                                          : ContourKind::Polygon;
    }
    spec.radius = f.positive("radius", spec.radius);
    spec.width = f.positive("width", spec.width);
    spec.length = f.positive("length", spec.length);
    if (f.has("polygon")) spec.polygon = f.points("polygon", 3);
    spec.scale = f.positive("scale", spec.scale);
    if (f.has("profile")) {
        const std::string p =
            f.choice("profile", "flat", {"flat", "half_sphere", "heightfield", "mesh"});
        spec.profile = p == "flat"          ? ProfileKind::Flat
                       : p == "half_sphere" ? ProfileKind::HalfSphere
                       : p == "heightfield" ? ProfileKind::Heightfield
                                            : ProfileKind::Mesh;
    }
    spec.sphere_radius = f.non_negative("sphere_radius", spec.sphere_radius);
    if (f.has("profile_file")) {
        const std::filesystem::path file = f.text("profile_file", "");
        spec.profile_file = file.is_absolute() ? file : base_dir / file;
    }
    spec.relief = f.non_negative("relief", spec.relief);
    spec.contour_from_mesh = f.boolean("contour_from_mesh", spec.contour_from_mesh);
    spec.control_points =
        static_cast<int>(f.integer("control_points", spec.control_points, 3, 4096));
    spec.gap = f.non_negative("gap", spec.gap);
    spec.rim_spacing = f.non_negative("rim_spacing", spec.rim_spacing);
    spec.rim_tolerance = f.non_negative("rim_tolerance", spec.rim_tolerance);
    if (f.has("mode"))
        spec.mode = f.choice("mode", "dig", {"dig", "level"}) == "dig" ? ImprintMode::Dig
                                                                       : ImprintMode::Level;
    spec.extrude = f.boolean("extrude", spec.extrude);
    spec.extrusion_width = f.non_negative("extrusion_width", spec.extrusion_width);
    f.reject_unknown();
}

}  // namespace

ToolSpec parse_tool_spec(const nlohmann::json& object, const std::filesystem::path& base_dir,
                         const std::string& context) {
    JsonFields f(object, context);
    ToolSpec spec;
    std::filesystem::path dir = base_dir;
    if (f.has("asset")) {
        const std::string asset = f.text("asset", "");
        try {
            spec = load_tool_asset(asset);
        } catch (const std::exception& e) {
            f.fail_field("asset", std::string("cannot be loaded: ") + e.what());
        }
    }
    apply_fields(spec, f, dir);
    return spec;
}

ToolSpec load_tool_asset(const std::string& name_or_path) {
    std::filesystem::path path = name_or_path;
    if (path.extension() != ".json") path = find_asset("tools/" + name_or_path + ".json");
    const nlohmann::json j = read_json_document(path, "tool file");
    JsonFields f(j, path.string());
    ToolSpec spec;
    apply_fields(spec, f, path.parent_path());
    return spec;
}

}  // namespace sandtin
