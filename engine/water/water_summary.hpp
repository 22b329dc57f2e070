#pragma once
// How much water a terrain holds (VertexArrays::water_depth), for reports and panels.

#include <cstddef>

#include "tin/tin.hpp"

namespace sandtin {

struct WaterSummary {
    double volume = 0.0;  ///< m³: sum over live vertices of lumped area x depth
    std::size_t wet_vertices = 0;
    double max_depth = 0.0;  ///< m
};

/// O(vertices).
WaterSummary measure_water(const Tin& tin);

}  // namespace sandtin
