#include "physics/terrain_solver.hpp"

namespace sandtin {

void PhysicsStepReport::accumulate(const PhysicsStepReport& o) {
    iterations += o.iterations;
    vertex_updates += o.vertex_updates;
    changed += o.changed;
    refined += o.refined;
    volume_moved += o.volume_moved;
    ms += o.ms;
    at_rest = o.at_rest;
}

const char* to_string(SolverDevice device) {
    return device == SolverDevice::Gpu ? "gpu" : "cpu";
}

}  // namespace sandtin
