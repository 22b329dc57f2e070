#include "water/tin_water_mesh.hpp"

#include "tin/vertex_arrays.hpp"

namespace sandtin {

WaterMesh water_mesh_of(const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    WaterMesh m;
    m.position = va.position;
    m.area = va.lumped_area;
    m.bed = va.height;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) m.area[v] = 0.0;
    }
    m.faces.reserve(tin.triangle_count());
    for (const std::array<VertexId, 3>& t : tin.triangles())
        m.faces.push_back({t[0].value, t[1].value, t[2].value});
    return m;
}

}  // namespace sandtin
