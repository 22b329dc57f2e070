#pragma once
// Binary STL: an 80-byte header, a triangle count, then per triangle a float normal, three
// float corners and a zero attribute word. STL has no units; slicers assume millimetres.

#include <cstdint>
#include <vector>

#include "io/export_mesh.hpp"

namespace sandtin {

std::vector<std::uint8_t> encode_stl(const ExportMesh& mesh);

}  // namespace sandtin
