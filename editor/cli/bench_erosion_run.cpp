// Rows, convergence order, CSV and SVG of `sandtin bench erosion` (bench_erosion_run.hpp).

#include "bench_erosion_run.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "physics/material.hpp"

namespace sandtin::cli {

namespace {

/// The methods in plotting order, with their colours and legends.
struct MethodStyle {
    const char* method;
    const char* colour;
    const char* legend;
};
constexpr MethodStyle kMethods[] = {
    {"tin", "#c0392b", "TIN, edges"},           {"tin-face", "#27ae60", "TIN, faces"},
    {"grid", "#2c3e50", "grid, edges"},         {"grid-face", "#8e44ad", "grid, faces"},
    {"tin-proj", "#e67e22", "TIN, projection"}, {"grid-proj", "#2980b9", "grid, projection"},
};

/// A cone-only figure: null where it was not measured (negative).
nlohmann::json measured(double v) {
    return v >= 0.0 ? nlohmann::json(v) : nlohmann::json();
}

std::vector<std::string> scenes_of(const std::vector<ErosionRun>& runs) {
    std::vector<std::string> scenes;
    for (const ErosionRun& r : runs) {
        if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end())
            scenes.push_back(r.scene);
    }
    return scenes;
}

/// One log-log panel at (ox, oy): x(r) against the mean error, a polyline per method.
template <class XOf>
void write_panel(std::ofstream& out, int ox, int oy, const std::string& title,
                 const std::vector<ErosionRun>& runs, const std::string& scene, XOf x_of,
                 const char* x_unit) {
    const int w = 420, h = 320, m = 50;
    double x0 = 1e300, x1 = 0, e0 = 1e300, e1 = 0;
    for (const ErosionRun& r : runs) {
        if (r.scene != scene || !(x_of(r) > 0.0) || !(r.mean_error > 0.0)) continue;
        x0 = std::min(x0, x_of(r)), x1 = std::max(x1, x_of(r));
        e0 = std::min(e0, r.mean_error), e1 = std::max(e1, r.mean_error);
    }
    if (!(x1 > 0.0)) return;
    const double lx0 = std::log10(x0) - 0.2, lx1 = std::log10(x1) + 0.2;
    const double ly0 = std::log10(e0) - 0.2, ly1 = std::log10(e1) + 0.2;
    const auto X = [&](double v) {
        return ox + m + (std::log10(v) - lx0) / (lx1 - lx0) * (w - 2 * m);
    };
    const auto Y = [&](double e) {
        return oy + h - m - (std::log10(e) - ly0) / (ly1 - ly0) * (h - 2 * m);
    };
    out << "<rect x='" << ox + m << "' y='" << oy + m << "' width='" << w - 2 * m << "' height='"
        << h - 2 * m << "' fill='none' stroke='black'/>\n";
    out << "<text x='" << ox + w / 2 << "' y='" << oy + 20 << "' text-anchor='middle'>" << title
        << "</text>\n";
    out << "<text x='" << ox + m << "' y='" << oy + h - m + 15 << "'>" << x0 << ' ' << x_unit
        << "</text>\n";
    out << "<text x='" << ox + w - m << "' y='" << oy + h - m + 15 << "' text-anchor='end'>" << x1
        << ' ' << x_unit << "</text>\n";
    out << "<text x='" << ox + 2 << "' y='" << oy + m + 10 << "'>" << e1 << "</text>\n";
    out << "<text x='" << ox + 2 << "' y='" << oy + h - m << "'>" << e0 << "</text>\n";
    int legend = 0;
    for (const MethodStyle& style : kMethods) {
        std::string poly;
        for (const ErosionRun& r : runs) {
            if (r.scene != scene || r.method != style.method) continue;
            if (!(x_of(r) > 0.0) || !(r.mean_error > 0.0)) continue;
            poly += std::to_string(X(x_of(r))) + "," + std::to_string(Y(r.mean_error)) + " ";
            out << "<circle cx='" << X(x_of(r)) << "' cy='" << Y(r.mean_error) << "' r='4' fill='"
                << style.colour << "'><title>" << r.method << ' ' << r.level << ", " << r.vertices
                << " vertices</title></circle>\n";
        }
        if (poly.empty()) continue;
        out << "<polyline points='" << poly << "' fill='none' stroke='" << style.colour << "'/>\n";
        out << "<text x='" << ox + w - m - 80 << "' y='" << oy + m + 15 + 15 * legend++
            << "' fill='" << style.colour << "'>" << style.legend << "</text>\n";
    }
}

}  // namespace

double dry_sand_tan_alpha() {
    return MaterialTable::presets().at(0).talus_slope(0.0);
}

nlohmann::json to_json(const ErosionRun& r) {
    return {{"scene", r.scene},
            {"method", r.method},
            {"level", r.level},
            {"vertices", r.vertices},
            {"spacing_m", r.spacing},
            {"iterations", r.iterations},
            {"cpu_ms", r.cpu_ms},
            {"wall_ms", r.wall_ms},
            {"mean_error_m", r.mean_error},
            {"max_error_m", r.max_error},
            {"at_rest", r.at_rest},
            {"settle_margin", r.settle_margin},
            {"steep_share_of_slopes", r.steep_share},
            {"max_face_ratio", r.max_face_ratio},
            {"skipped_faces", r.skipped_faces},
            {"toe_error", measured(r.toe_error)},
            {"toe_bias", std::isfinite(r.toe_bias) ? nlohmann::json(r.toe_bias) : nlohmann::json()},
            {"pile_mean_error_m", measured(r.pile_error)},
            {"pile_height_m", measured(r.pile_height)}};
}

nlohmann::json fitted_order(const std::vector<ErosionRun>& runs, const std::string& scene,
                            const std::string& method) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const ErosionRun& r : runs) {
        if (r.scene != scene || r.method != method) continue;
        if (!(r.spacing > 0.0) || !(r.mean_error > 0.0)) continue;
        const double x = std::log(r.spacing), y = std::log(r.mean_error);
        n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double d = n * sxx - sx * sx;
    if (n < 2 || !(std::abs(d) > 0.0)) return nullptr;
    return (n * sxy - sx * sy) / d;
}

void write_erosion_csv(const std::filesystem::path& path, const std::vector<ErosionRun>& runs) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
    out << "scene,method,level,vertices,spacing_m,iterations,cpu_ms,wall_ms,mean_error_m,"
           "max_error_m,at_rest,settle_margin,steep_share_of_slopes,max_face_ratio,"
           "skipped_faces,toe_error,pile_mean_error_m,pile_height_m,toe_bias\n";
    for (const ErosionRun& r : runs) {
        out << r.scene << ',' << r.method << ',' << r.level << ',' << r.vertices << ',' << r.spacing
            << ',' << r.iterations << ',' << r.cpu_ms << ',' << r.wall_ms << ',' << r.mean_error
            << ',' << r.max_error << ',' << (r.at_rest ? 1 : 0) << ',' << r.settle_margin << ','
            << r.steep_share << ',' << r.max_face_ratio << ',' << r.skipped_faces;
        // Cones only: empty cells elsewhere.
        for (const double v : {r.toe_error, r.pile_error, r.pile_height}) {
            out << ',';
            if (v >= 0.0) out << v;
        }
        out << ',';
        if (std::isfinite(r.toe_bias)) out << r.toe_bias;
        out << '\n';
    }
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
}

void write_erosion_svg(const std::filesystem::path& path, const std::vector<ErosionRun>& runs) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
    const std::vector<std::string> scenes = scenes_of(runs);
    out << "<svg xmlns='http://www.w3.org/2000/svg' width='840' height='"
        << 320 * std::max<std::size_t>(scenes.size(), 1)
        << "' font-family='sans-serif' font-size='11'>\n";
    int oy = 0;
    for (const std::string& scene : scenes) {
        write_panel(
            out, 0, oy, scene + ": CPU ms to rest (log) vs mean |dz| m (log)", runs, scene,
            [](const ErosionRun& r) { return r.cpu_ms; }, "ms");
        write_panel(
            out, 420, oy, scene + ": spacing m (log) vs mean |dz| m (log)", runs, scene,
            [](const ErosionRun& r) { return r.spacing; }, "m");
        oy += 320;
    }
    out << "</svg>\n";
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
}

}  // namespace sandtin::cli
