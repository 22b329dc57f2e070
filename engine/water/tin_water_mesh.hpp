#pragma once
// The water's view of a TIN (virtual_pipes.hpp): its vertices by id, its triangles, its lumped
// areas and its heights as the bed. Dead ids have no area and no faces, so no pipe reaches
// them.

#include "tin/tin.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin {

WaterMesh water_mesh_of(const Tin& tin);

}  // namespace sandtin
