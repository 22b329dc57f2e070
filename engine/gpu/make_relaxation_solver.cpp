#include "gpu/make_relaxation_solver.hpp"

#include <stdexcept>

#include "gpu/gpu_sand_physics.hpp"
#include "gpu/tin_mirror.hpp"
#include "physics/sand_physics.hpp"

namespace sandtin::gpu {

std::unique_ptr<RelaxationSolver> make_relaxation_solver(Tin& tin, const MaterialTable& materials,
                                                         const TalusSettings& settings,
                                                         const RelaxationPlacement& placement) {
    if (placement.device == SolverDevice::Cpu)
        return std::make_unique<SandPhysics>(tin, materials, settings);
    if (placement.mirror != nullptr) {
        if (&placement.mirror->tin() != &tin) {
            throw std::invalid_argument(
                "make_relaxation_solver: the mirror given mirrors another terrain");
        }
        placement.mirror->set_materials(materials);
        return std::make_unique<GpuSandPhysics>(*placement.mirror, settings, placement.slide_gain);
    }
    if (placement.context == nullptr) {
        throw std::invalid_argument(
            "make_relaxation_solver: the GPU relaxation needs a Vulkan context or a mirror");
    }
    return std::make_unique<GpuSandPhysics>(tin, *placement.context, materials, settings,
                                            placement.slide_gain);
}

}  // namespace sandtin::gpu
