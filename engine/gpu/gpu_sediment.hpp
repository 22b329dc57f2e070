#pragma once
// Sand carried by the water on the GPU (issue 40, item 6): the law of
// water/sediment_transport.hpp (its CPU reference, in double), recorded after each step of a
// GpuWater run in the same submission (a WaterStepHook), vertex-parallel in float on the
// mirror (shaders/sediment_*.comp): capacity from the pipes' discharge and the bed's slope,
// pick-up of the material on top or drop towards it, and transport with the flow at the
// sending vertex's concentration, each volume leaving one vertex and entering the other as
// the same float. The bed is the mirror's height buffer: the water flows over the bed the
// sediment leaves. What a float height cannot take of a change stays in a per-vertex bed
// residual, so sum(area height + residual) + suspended is kept to float rounding. The rock is
// never eroded.
//
// Materials travel with the sand, as on the CPU: the suspension keeps a volume per material
// of the palette (the materials on the terrain when the sediment starts, at most 8), and
// each vertex counts what it received of each; deposited_materials() says what lies on top.
//
// copy_beds_into() hands the beds back to the terrain (journaled). Do so before the terrain
// is edited elsewhere or the water's depths are copied back (GpuWater::copy_depths_into): the
// next sync puts the terrain's heights back on every vertex it uploads. Settle (settle_all)
// and copy before the terrain is re-triangulated: suspension at a vertex that dies is lost
// (suspended_lost() counts it).
// Units: metres, seconds, m³.

#include <cstdint>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/compute_kernel.hpp"
#include "gpu/gpu_water.hpp"
#include "tin/change_reader.hpp"
#include "water/sediment_transport.hpp"

namespace sandtin::gpu {

class GpuSediment final : public WaterStepHook {
  public:
    static constexpr uint32_t kMaxKinds = 8;  ///< shaders/sediment_common.glsl's MAX_KINDS

    /// Sediment for `water`'s runs: pass it to GpuWater::run. Throws GpuError for constants
    /// out of range (as SedimentTransport) or more than kMaxKinds materials on the terrain.
    GpuSediment(GpuWater& water, SedimentOptions options = {});
    ~GpuSediment() override;
    GpuSediment(const GpuSediment&) = delete;
    GpuSediment& operator=(const GpuSediment&) = delete;

    void prepare() override;
    void record_step(VkCommandBuffer cb, uint32_t parity, double dt) override;

    /// Drops every grain still suspended where it is (the end of a run); submits and waits.
    void settle_all();

    /// m³ suspended, summed in double from the GPU's floats.
    double suspended() const;
    /// sum(area x height + bed residual) over the live vertices (m³, heights from the mirror's
    /// origin) plus the suspension: what the sediment keeps.
    double sand_volume() const;
    /// The beds (m, the terrain's own heights: the float height plus, in double, the bed
    /// residual over the vertex's area), mirror vertex capacity long.
    std::vector<double> read_beds() const;
    /// Writes the GPU's beds into the terrain (Tin::set_height, journaled) where they differ;
    /// returns how many were written.
    std::size_t copy_beds_into(Tin& tin) const;
    /// Per vertex id: the material that makes up most of the sand dropped there, the bed's own
    /// where none was (SedimentTransport::deposited_material).
    std::vector<std::uint16_t> deposited_materials() const;
    /// m³ dropped at each vertex since construction (settle_all included), of all materials.
    std::vector<double> dropped() const;
    double suspended_lost() const { return lost_; }

  private:
    struct Push {
        uint32_t vertex_count;
        uint32_t edge_capacity;
        uint32_t parity;
        uint32_t half;
        uint32_t kinds;
        uint32_t stride;  ///< vertices per half of held and kind: the buffers' capacity
        float dt;
        float capacity_k;
        float pick_up;
        float drop_rate;
        float least_slope;
        float max_concentration;
    };
    Push push(uint32_t parity, double dt) const;
    void ensure_buffers();
    std::vector<float> read(const Buffer& b, VkDeviceSize floats, VkDeviceSize offset = 0) const;

    VulkanContext& context_;
    GpuWater& water_;
    TinMirror& mirror_;
    SedimentOptions options_;
    ChangeReader changes_;
    ComputeKernel capacity_;
    ComputeKernel exchange_;
    ComputeKernel carry_;
    ComputeKernel settle_;
    std::vector<std::uint16_t> palette_;
    std::vector<std::uint32_t> kind_of_material_;  ///< by material: palette index + 1, 0: none
    Buffer capacity_buffer_, held_, kind_, dropped_, scale_, bed_kind_, bed_residual_;
    uint32_t vertex_capacity_ = 0;  ///< what the buffers are laid out for
    uint64_t bound_generation_ = UINT64_MAX;
    uint32_t half_ = 0;
    double lost_ = 0.0;
};

}  // namespace sandtin::gpu
