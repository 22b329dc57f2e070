#pragma once
// The embedded SPIR-V of sandtin's compute shaders (compiled from shaders/*.comp at build time).

#include <cstdint>
#include <span>

namespace sandtin::gpu::shaders {

std::span<const uint32_t> talus_outflow();
std::span<const uint32_t> talus_face_outflow();  // SlopeRule::Face
std::span<const uint32_t> talus_gather();
std::span<const uint32_t> talus_age();
std::span<const uint32_t> talus_activate();
std::span<const uint32_t> talus_control();
std::span<const uint32_t> talus_pack();
std::span<const uint32_t> vertex_normals();
std::span<const uint32_t> corner_normals();
std::span<const uint32_t> bake_maps();
std::span<const uint32_t> water_flux();  // gpu_water.hpp
std::span<const uint32_t> water_depth();
std::span<const uint32_t> water_measure();
std::span<const uint32_t> moisture_weights();  // gpu_moisture.hpp
std::span<const uint32_t> moisture_wet();
std::span<const uint32_t> moisture_spread();
std::span<const uint32_t> moisture_finish();
std::span<const uint32_t> sediment_capacity();  // gpu_sediment.hpp
std::span<const uint32_t> sediment_exchange();
std::span<const uint32_t> sediment_carry();
std::span<const uint32_t> sediment_settle();

}  // namespace sandtin::gpu::shaders
