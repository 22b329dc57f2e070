#pragma once
// The water standing on a terrain (VertexArrays::water_depth) as an exportable mesh: its
// surface, bed + depth, over every TIN triangle with a wet corner (one holding at least
// `min_depth`: the film a flow leaves spread over flat ground is not a surface anyone wants
// to see). A dry corner of such a triangle lies on the terrain, so the surface meets the shore
// there instead of ending in a cliff. The frame, units and winding are the terrain mesh's
// (io/export_mesh.hpp), so the two line up in any importer; the whole mesh is "surface" (no base).

#include "io/export_mesh.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// Metres: water thinner than this is left out of the water mesh (a tenth of a millimetre).
inline constexpr double kWaterMeshMinDepth = 1e-4;

/// The water surface of `tin` in `options`' frame and units (its base is ignored); an empty
/// mesh when the terrain is dry. Throws std::invalid_argument for a bad unit scale, as
/// build_export_mesh does.
ExportMesh build_water_mesh(const Tin& tin, const MeshExportOptions& options,
                            double min_depth = kWaterMeshMinDepth);

}  // namespace sandtin
