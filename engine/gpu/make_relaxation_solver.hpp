#pragma once
// One place that turns "where should the relaxation run" into a solver: the CPU reference
// (physics/SandPhysics) or the GPU relaxation (gpu/GpuSandPhysics), behind the physics seam
// (physics/terrain_solver.hpp). The editor and `sandtin run` both create their solver here.

#include <memory>

#include "physics/material.hpp"
#include "physics/talus_solver.hpp"
#include "physics/terrain_solver.hpp"
#include "tin/tin.hpp"

namespace sandtin::gpu {

class TinMirror;
class VulkanContext;

/// Texture units per metre of transported height for the GPU's texture sliding in the editor:
/// a slide of a few millimetres moves the sand grains by several grain widths, so the flow is
/// visible.
inline constexpr double kEditorSlideGain = 20.0;

struct RelaxationPlacement {
    SolverDevice device = SolverDevice::Cpu;
    /// The device for SolverDevice::Gpu (unless `mirror` is given); it must outlive the solver.
    VulkanContext* context = nullptr;
    /// A mirror of the TIN that someone else owns and syncs too (the editor's terrain view):
    /// the GPU solver relaxes on it instead of keeping a second copy of the TIN on the GPU.
    TinMirror* mirror = nullptr;
    /// Texture-sliding gain of the GPU relaxation (texture units per metre moved; 0 = off).
    double slide_gain = 0.0;
};

/// A relaxation solver following `tin` from now on. Throws std::invalid_argument when the GPU
/// is asked for without a context or mirror, or with a mirror of another TIN; GpuError when
/// the device cannot run it.
std::unique_ptr<RelaxationSolver> make_relaxation_solver(Tin& tin, const MaterialTable& materials,
                                                         const TalusSettings& settings,
                                                         const RelaxationPlacement& placement);

}  // namespace sandtin::gpu
