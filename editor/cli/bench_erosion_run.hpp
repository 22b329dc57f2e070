#pragma once
// One run of `sandtin bench erosion`: a method (tin, tin-face, tin-proj and the grid's three) on a
// scene at one resolution, with its cost to rest and its error against the scene's reference.

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sandtin::cli {

struct ErosionRun {
    std::string scene, method, level;
    std::size_t vertices = 0;
    /// The run's resolution (m): r_S on a TIN poured from two triangles, the mean spacing
    /// sqrt(area / vertices) on a random TIN, the cell size on a grid.
    double spacing = 0.0;
    long iterations = 0;
    double cpu_ms = 0.0, wall_ms = 0.0;
    double mean_error = 0.0, max_error = 0.0;
    bool at_rest = false;
    double settle_margin = 0.0;  ///< the relaxation's
    /// Per face (physics/face_slopes.hpp; on a grid, its 4-8 mesh's triangles): the share of
    /// the slopes' area steeper than tan(alpha) (1 + 1e-3), the steepest face's
    /// |∇h| / tan(alpha), and the slivers skipped.
    double steep_share = 0.0, max_face_ratio = 0.0;
    long skipped_faces = 0;
    /// Cones only (else negative): the largest |toe radius / R - 1| over 32 directions, the
    /// mean |z - z_ref| inside 1.2 R (m) and the cone's height H (m).
    double toe_error = -1.0, pile_error = -1.0, pile_height = -1.0;
    /// Cones only (else NaN): the mean of toe radius / R - 1 over the same directions. Set
    /// beside toe_error it tells a toe systematically too far out (or in) from a ragged one.
    double toe_bias = std::numeric_limits<double>::quiet_NaN();
};

/// tan(alpha) of the scenes' sand: the first preset material, dry.
double dry_sand_tan_alpha();

nlohmann::json to_json(const ErosionRun& r);

/// The least-squares slope of log(mean error) against log(spacing) over the runs of one scene
/// and method (the order of convergence: 1 when halving the spacing halves the error); null
/// with fewer than two runs.
nlohmann::json fitted_order(const std::vector<ErosionRun>& runs, const std::string& scene,
                            const std::string& method);

/// Every run as CSV. Throws std::runtime_error when the file cannot be written.
void write_erosion_csv(const std::filesystem::path& path, const std::vector<ErosionRun>& runs);
/// Two log-log plots per scene, one SVG: CPU time to rest against mean error, and mean error
/// against spacing. Throws std::runtime_error when the file cannot be written.
void write_erosion_svg(const std::filesystem::path& path, const std::vector<ErosionRun>& runs);

}  // namespace sandtin::cli
