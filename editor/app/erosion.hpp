#pragma once
// The erosion panel's CPU/GPU switch: one interface over the CPU reference physics
// (physics/SandPhysics, sequential active list) and the GPU relaxation
// (gpu/GpuSandPhysics, Jacobi on the device, heights read back into the TIN). The editor holds
// no physics of its own; this only forwards.

#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "gpu/gpu_sand_physics.hpp"
#include "physics/sand_physics.hpp"

namespace sandtin::editor {

enum class ErosionBackend { Cpu, Gpu };

class Erosion {
  public:
    virtual ~Erosion() = default;
    virtual ErosionBackend backend() const = 0;
    virtual TalusSettings& settings() = 0;
    virtual void set_materials(const MaterialTable& materials) = 0;
    virtual void activate_all() = 0;
    virtual bool at_rest() const = 0;
    virtual std::size_t active_count() const = 0;
    /// Up to `iterations` relaxation iterations; vertices whose height changed are appended to
    /// `changed`.
    virtual PhysicsStepReport step(int iterations, std::vector<VertexId>* changed) = 0;
    /// The GPU physics' mirror of the TIN (shared with the renderer's normal-map bake), or
    /// null for the CPU physics.
    virtual gpu::TinMirror* mirror() = 0;
    /// Vertices the caller synced into mirror() itself (edits while erosion is paused): they
    /// may have excess and must be looked at on the next step.
    virtual void activate(std::span<const VertexId> vertices) = 0;
    /// Compute dispatches recorded so far (0 for the CPU): idle must add none.
    virtual std::uint64_t gpu_dispatches() = 0;
};

namespace detail {

template <class Physics>
class ErosionOf final : public Erosion {
  public:
    template <class... Args>
    explicit ErosionOf(ErosionBackend b, Args&&... args)
        : backend_(b), physics_(std::forward<Args>(args)...) {}
    ErosionBackend backend() const override { return backend_; }
    TalusSettings& settings() override { return physics_.settings(); }
    void set_materials(const MaterialTable& m) override { physics_.set_materials(m); }
    void activate_all() override { physics_.activate_all(); }
    bool at_rest() const override { return physics_.at_rest(); }
    std::size_t active_count() const override { return physics_.active_count(); }
    PhysicsStepReport step(int iterations, std::vector<VertexId>* changed) override {
        return physics_.step(iterations, changed);
    }
    gpu::TinMirror* mirror() override {
        if constexpr (std::is_same_v<Physics, gpu::GpuSandPhysics>)
            return &physics_.mirror();
        else
            return nullptr;
    }
    void activate(std::span<const VertexId> vertices) override { physics_.activate(vertices); }
    std::uint64_t gpu_dispatches() override {
        if constexpr (std::is_same_v<Physics, gpu::GpuSandPhysics>)
            return physics_.relaxation().dispatches_recorded();
        else
            return 0;
    }

  private:
    ErosionBackend backend_;
    Physics physics_;
};

}  // namespace detail

inline std::unique_ptr<Erosion> make_cpu_erosion(Tin& tin, const MaterialTable& materials) {
    return std::make_unique<detail::ErosionOf<SandPhysics>>(ErosionBackend::Cpu, tin, materials);
}

/// Texture units per metre of transported height for the GPU's texture sliding: a slide of a
/// few millimetres moves the sand grains by several grain widths, so the flow is visible.
inline constexpr double kSlideGain = 20.0;

/// `source` hands the GPU mirror the TIN's changes (the editor's ChangeFanout channel).
inline std::unique_ptr<Erosion> make_gpu_erosion(Tin& tin, gpu::VulkanContext& context,
                                                 const MaterialTable& materials,
                                                 gpu::GpuSandPhysics::ChangeSource source) {
    return std::make_unique<detail::ErosionOf<gpu::GpuSandPhysics>>(
        ErosionBackend::Gpu, tin, context, materials, TalusSettings{}, kSlideGain,
        std::move(source));
}

}  // namespace sandtin::editor
