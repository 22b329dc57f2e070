#pragma once
// Baked maps (engine/maps) as image files.
//
//  - Height PNG: 16-bit gray, heights mapped linearly from [z_min, z_max] to [0, 65535], so
//    the quantisation step is (z_max - z_min) / 65535. The tEXt chunks sandtin:z_offset,
//    sandtin:z_range and sandtin:cell_size let `sandtin import` restore metres exactly, and
//    sandtin:west, sandtin:south, sandtin:crs and sandtin:horizontal_unit the georeference.
//  - Height EXR: 32-bit float metres (io/heightmap_exr.hpp).
//  - Water-depth PNG: 16-bit gray, black dry and white the deepest water (the range in
//    sandtin:z_range, sandtin:z_offset 0), so it masks the water and `sandtin import` reads
//    it back as metres; water-depth EXR: float metres, like the height EXR.
//  - Normal PNG: 8-bit RGB, (n + 1) / 2 per component (OpenGL convention, +Y = green = north).
//  - Albedo PNG: 8-bit RGB.
//  Both carry their texel size and the georeference in tEXt chunks (TexelFrame).

#include <cstdint>
#include <vector>

#include "io/heightmap_raster.hpp"
#include "maps/map_grid.hpp"

namespace sandtin {

/// The metres a height PNG of `heights` spans from black to white: z_max - z_min, or 1 for a
/// map flat up to rounding (1e-12 of its magnitude). Its 16-bit step is this / 65535.
double height_png_range(const MapImage& heights);

/// `heights` has one channel; `cell_size` (between columns) and, when the rows are spaced
/// differently, `cell_height` (between rows), in metres, are stored for re-import, and so is
/// a known `georeference` of the south-west sample.
std::vector<std::uint8_t> encode_height_png(const MapImage& heights, double cell_size,
                                            double cell_height = 0.0,
                                            const Georeference& georeference = {});
/// The metres a water-depth PNG of `depths` spans from black (dry) to white: the deepest
/// water, or 1 for a dry map.
double water_depth_png_range(const MapImage& depths);
/// `depths` has one channel of metres >= 0; the cell sizes and georeference as for heights.
std::vector<std::uint8_t> encode_water_depth_png(const MapImage& depths, double cell_size,
                                                 double cell_height = 0.0,
                                                 const Georeference& georeference = {});
std::vector<std::uint8_t> encode_height_exr(const MapImage& heights, double cell_size,
                                            double cell_height = 0.0,
                                            const Georeference& georeference = {});
/// Where a normal or albedo map lies, written to its tEXt chunks (sandtin:texel_size,
/// sandtin:texel_height, and the georeference as for height maps). Texel (0, 0): none.
struct TexelFrame {
    Vec2 texel{};  ///< metres per texel: across, down
    Georeference georeference;
};
/// `normals` has three channels, unit vectors.
std::vector<std::uint8_t> encode_normal_png(const MapImage& normals, const TexelFrame& frame = {});
/// `colours` has three channels of linear albedo in [0, 1], written as an 8-bit RGB PNG in the
/// sRGB encoding that image viewers, glTF's baseColorTexture and OBJ's map_Kd expect
/// (IEC 61966-2-1).
std::vector<std::uint8_t> encode_albedo_png(const MapImage& colours, const TexelFrame& frame = {});

}  // namespace sandtin
