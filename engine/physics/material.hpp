#pragma once
// Granular materials: angle of repose, moisture response, appearance and haptic feel.
//
// Moisture model (after Hornbaker et al., "What keeps sandcastles standing?", Nature 387, 1997;
// Nowak, Samadani & Kudrolli, Nature Physics 1, 2005; Mitarai & Nori, Adv. Phys. 55, 2006):
// a little water forms capillary bridges between grains, and the angle at which a pile stays
// stable rises quickly and then levels off (the pendular regime); close to saturation the
// bridges merge, cohesion collapses and wet sand slumps (slurry). With saturation m in [0, 1]:
//
//   alpha(m) = a_dry + (a_wet - a_dry) (1 - exp(-m / m_c))                for m <= m_s
//   alpha(m) = alpha(m_s) + (a_sat - alpha(m_s)) (m - m_s) / (1 - m_s)     for m >  m_s
//
// a_dry, a_wet, a_sat are angles (degrees in files, radians in code), m_c the moisture scale of
// the capillary rise, m_s where slumping starts.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace sandtin {

/// Share of its albedo a material keeps at full saturation: wet sand is darker. The viewport
/// and the exported albedo both shade colour x (1 - (1 - kWetReflectance) m).
inline constexpr float kWetReflectance = 0.6f;

struct Material {
    std::string name = "dry_sand";
    double repose_dry = 0.5585053606381855;         ///< radians (32°)
    double repose_wet = 0.767944870877505;          ///< radians (44°), capillary plateau
    double moisture_scale = 0.04;                   ///< m_c: saturation of the capillary rise
    double slurry_start = 0.85;                     ///< m_s: saturation where slumping starts
    double repose_saturated = 0.20943951023931956;  ///< radians (12°) at full saturation
    float colour[3] = {0.82f, 0.70f, 0.50f};        ///< linear RGB albedo
    double haptic_stiffness = 800.0;  ///< N/m: penetration resistance per metre of depth
    double haptic_friction = 0.55;    ///< dimensionless drag coefficient in the motion direction
    float default_moisture = 0.0f;    ///< saturation the paint tool applies with this material

    /// Angle of repose (radians) at saturation m in [0, 1].
    double repose(double moisture) const;
    /// tan(repose(moisture)): the largest stable height difference per metre.
    double talus_slope(double moisture) const;
};

/// Materials indexed by the per-vertex material id.
class MaterialTable {
  public:
    MaterialTable() = default;
    explicit MaterialTable(std::vector<Material> materials);

    /// The shipped presets (also in assets/materials/presets.json): 0 dry sand, 1 moist sand,
    /// 2 gravel.
    static MaterialTable presets();
    /// Loads a JSON array of materials (degrees for angles). Throws JsonInputError naming the
    /// entry and field for bad values.
    static MaterialTable load(const std::filesystem::path& path);
    /// The same from an already parsed array; errors start with `context` (a file, "session
    /// metadata").
    static MaterialTable from_json(const nlohmann::json& list, const std::string& context);
    /// The table as the array load() and from_json() read (degrees for angles).
    nlohmann::json to_json() const;

    std::size_t size() const { return materials_.size(); }
    /// Material `id`, or the first one for ids beyond the table (so painted ids that a later
    /// table lacks never crash the physics).
    const Material& at(std::uint16_t id) const;
    const std::vector<Material>& all() const { return materials_; }

  private:
    std::vector<Material> materials_;
};

}  // namespace sandtin
