#pragma once
// Binary little-endian PLY: float x y z, nx ny nz, s t (t up) per vertex; faces as a uchar
// count and uint indices.

#include <cstdint>
#include <vector>

#include "io/export_mesh.hpp"

namespace sandtin {

std::vector<std::uint8_t> encode_ply(const ExportMesh& mesh);

}  // namespace sandtin
