#pragma once
// Tool definitions in JSON: the files in assets/tools/ and the "tool" objects of scripts.
//
//   { "asset": "lambda",            // optional: start from assets/tools/lambda.json
//     "contour": "circle" | "rectangle" | "polygon",
//     "radius": 0.04, "width": 0.08, "length": 0.08, "polygon": [[x, y], ...], "scale": 1,
//     "profile": "flat" | "half_sphere" | "heightfield" | "mesh",
//     "sphere_radius": 0, "profile_file": "foot.obj", "relief": 0.02, "contour_from_mesh": false,
//     "control_points": 12, "gap": 0, "rim_spacing": 0, "rim_tolerance": 0,
//     "mode": "dig" | "level", "extrude": false, "extrusion_width": 0, "name": "..." }
//
// Lengths are metres; 0 means "derive from the tool size" (see ToolSpec).

#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "tools/tool.hpp"

namespace sandtin {

/// Parses a tool object; `base_dir` resolves relative profile files; errors name `context`.
ToolSpec parse_tool_spec(const nlohmann::json& object, const std::filesystem::path& base_dir,
                         const std::string& context);

/// Loads assets/tools/<name>.json (or a path to a .json file).
ToolSpec load_tool_asset(const std::string& name_or_path);

}  // namespace sandtin
