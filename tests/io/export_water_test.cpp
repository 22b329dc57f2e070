// Water on the terrain in exports (issue 40, item 8): the water-depth maps sample the water
// the TIN holds by linear interpolation, so a depth field linear in x comes back exactly (up to
// the 16-bit step or float rounding) at every sample, and a dry terrain's map is black; a glTF of a
// wet terrain has a second node, "water", whose mesh is the wet triangles at bed + depth with a
// translucent material, read back through tinygltf's own loader; a dry terrain's glTF has one
// node, and --no-water leaves the water out.

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "io/export_terrain.hpp"
#include "io/heightmap_import.hpp"
#include "support/scratch_folder.hpp"
#include "support/tin_oracles.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {
namespace {
namespace export_water_test {

namespace fs = std::filesystem;

/// Water deepest in the east: 0 at x <= 4, then 0.02 m per metre; a bumpy bed under it.
double depth_at(Vec2 p) {
    return std::max(0.0, 0.02 * (p.x - 4.0));
}

Tin wet_tin() {
    Tin tin = Tin::random_points(Rect{{0.0, 0.0}, {12.0, 8.0}}, 400, 7, [](Vec2 p) {
        return 1.0 + 0.2 * std::sin(p.x) * std::cos(0.7 * p.y);
    });
    for (VertexId v : test::live_ids(tin))
        tin.set_water_depth(v, depth_at(tin.position(v)));
    return tin;
}

class ExportWater : public test::ScratchFolderTest {
  protected:
    ExportWater() : ScratchFolderTest("export-water") {}
    fs::path run(const Tin& tin, const std::string& name, ExportOptions o = {},
                 const std::string& map = "") {
        const fs::path p = dir_ / name;
        report_ = export_terrain(tin, p, export_format_for(p, map), o);
        return p;
    }
    ExportReport report_;
};

/// Water over the whole terrain, its depth linear in x: linear interpolation over any
/// triangulation gives it back exactly.
double linear_depth(Vec2 p) {
    return 0.01 + 0.02 * p.x;
}

TEST_F(ExportWater, WaterDepthMapsSampleTheWaterExactly) {
    Tin tin = wet_tin();
    for (VertexId v : test::live_ids(tin))
        tin.set_water_depth(v, linear_depth(tin.position(v)));
    ExportOptions o;
    o.map_size = 97;
    for (const std::string name : {"depth.png", "depth.exr"}) {
        const fs::path p = run(tin, name, o, "water");
        const HeightRaster r = read_heightmap(p);
        ASSERT_EQ(r.width, 97u) << name;
        const double deepest = linear_depth({12.0, 0.0});
        // 16-bit: half a step of the deepest water; EXR: float rounding.
        const double tolerance = name == "depth.png" ? 0.5 * deepest / 65535.0 + 1e-12 : 1e-7;
        std::size_t checked = 0;
        for (std::uint32_t row = 0; row < r.height; ++row) {
            for (std::uint32_t col = 0; col < r.width; ++col) {
                const Vec2 at{r.origin.x + col * r.cell_size,
                              r.origin.y + (r.height - 1 - row) * r.row_spacing()};
                EXPECT_NEAR(r.at(col, row), linear_depth(at), tolerance)
                    << name << " at " << at.x << ", " << at.y << " row " << row;
                ++checked;
            }
        }
        EXPECT_EQ(checked, r.size()) << name;
    }
}

struct WaterNode {
    std::size_t nodes = 0;
    bool found = false;
    std::vector<std::array<double, 3>> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    tinygltf::Material material;
};

WaterNode water_node_of(const fs::path& file) {
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    const bool ok = file.extension() == ".glb"
                        ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                        : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
    EXPECT_TRUE(ok) << err;
    WaterNode w;
    if (!ok) return w;
    w.nodes = model.scenes.at(0).nodes.size();
    for (int n : model.scenes.at(0).nodes) {
        const tinygltf::Node& node = model.nodes.at(static_cast<std::size_t>(n));
        if (node.name != "water") continue;
        w.found = true;
        const tinygltf::Primitive& prim =
            model.meshes.at(static_cast<std::size_t>(node.mesh)).primitives.at(0);
        w.material = model.materials.at(static_cast<std::size_t>(prim.material));
        const tinygltf::Accessor& pa =
            model.accessors.at(static_cast<std::size_t>(prim.attributes.at("POSITION")));
        const tinygltf::BufferView& pv =
            model.bufferViews.at(static_cast<std::size_t>(pa.bufferView));
        const auto* p = reinterpret_cast<const float*>(model.buffers.at(0).data.data() +
                                                       pv.byteOffset + pa.byteOffset);
        for (std::size_t i = 0; i < pa.count; ++i)
            w.positions.push_back({p[3 * i], p[3 * i + 1], p[3 * i + 2]});
        const tinygltf::Accessor& ia = model.accessors.at(static_cast<std::size_t>(prim.indices));
        const tinygltf::BufferView& iv =
            model.bufferViews.at(static_cast<std::size_t>(ia.bufferView));
        const auto* idx = reinterpret_cast<const std::uint32_t*>(model.buffers.at(0).data.data() +
                                                                 iv.byteOffset + ia.byteOffset);
        for (std::size_t k = 0; k + 2 < ia.count; k += 3)
            w.triangles.push_back({idx[k], idx[k + 1], idx[k + 2]});
    }
    return w;
}

TEST_F(ExportWater, AGltfOfAWetTerrainCarriesTheWaterSurfaceAsASecondNode) {
    const Tin tin = wet_tin();
    ExportOptions o;
    o.textures = false;
    // The wet triangles, counted here from the TIN: those with a corner under a tenth of a
    // millimetre of water or more (a thinner film is the shore; the field is 0 at x = 4 and
    // 1e-4 m at x = 4.005).
    std::size_t wet_triangles = 0;
    std::map<std::pair<double, double>, double> surface;  // (x, y) -> bed + depth, wet corners
    for (const auto& t : tin.triangles()) {
        const auto deep = [&](VertexId v) { return tin.vertices().water_depth[v.index()] >= 1e-4; };
        if (!deep(t[0]) && !deep(t[1]) && !deep(t[2])) continue;
        ++wet_triangles;
        for (VertexId v : t) {
            const Vec2 p = tin.position(v);
            surface[{p.x, p.y}] =
                tin.height(v) + (deep(v) ? tin.vertices().water_depth[v.index()] : 0.0);
        }
    }
    ASSERT_GT(wet_triangles, 0u);
    for (const std::string name : {"wet.glb", "wet.gltf"}) {
        const WaterNode w = water_node_of(run(tin, name, o));
        EXPECT_EQ(w.nodes, 2u) << name;
        ASSERT_TRUE(w.found) << name;
        EXPECT_EQ(w.triangles.size(), wet_triangles) << name;
        EXPECT_EQ(report_.water_triangles, wet_triangles) << name;
        EXPECT_EQ(w.positions.size(), surface.size()) << name;
        // Y-up: (x, z, -y); every vertex at its bed + depth, as float.
        for (const auto& p : w.positions) {
            const auto it = surface.find({p[0], -p[2]});
            if (it == surface.end()) {
                // float coordinates: find the nearest corner instead
                double best = 1e300, z = 0.0;
                for (const auto& [xy, s] : surface) {
                    const double d = std::hypot(xy.first - p[0], xy.second + p[2]);
                    if (d < best) best = d, z = s;
                }
                EXPECT_LT(best, 1e-5) << name;
                EXPECT_NEAR(p[1], z, 1e-5) << name;
            } else {
                EXPECT_NEAR(p[1], it->second, 1e-5) << name;
            }
        }
        // Facing up, like the terrain: +y in a Y-up file.
        for (const auto& t : w.triangles) {
            const auto& a = w.positions[t[0]];
            const auto& b = w.positions[t[1]];
            const auto& c = w.positions[t[2]];
            const double ny = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]);
            EXPECT_GT(ny, 0.0) << name;
        }
        EXPECT_EQ(w.material.name, "water");
        EXPECT_EQ(w.material.alphaMode, "BLEND");
        EXPECT_LT(w.material.pbrMetallicRoughness.baseColorFactor.at(3), 1.0);
    }
    o.water = false;
    const WaterNode without = water_node_of(run(tin, "dry.glb", o));
    EXPECT_EQ(without.nodes, 1u);
    EXPECT_FALSE(without.found);
}

TEST_F(ExportWater, ADryTerrainExportsNoWater) {
    Tin tin = Tin::random_points(Rect{{0.0, 0.0}, {2.0, 2.0}}, 100, 3, [](Vec2) { return 0.5; });
    ExportOptions o;
    o.textures = false;
    const WaterNode w = water_node_of(run(tin, "dry.glb", o));
    EXPECT_EQ(w.nodes, 1u);
    EXPECT_FALSE(w.found);
    EXPECT_EQ(report_.water_triangles, 0u);
    // A dry depth map is all black.
    o.map_size = 16;
    const HeightRaster r = read_heightmap(run(tin, "dry.png", o, "water"));
    EXPECT_EQ(*std::max_element(r.heights.begin(), r.heights.end()), 0.0);
    // A film thinner than a tenth of a millimetre (what a flow leaves on flat ground) is no
    // water surface, though the depth map still shows it.
    for (VertexId v : test::live_ids(tin))
        tin.set_water_depth(v, 5e-5);
    const WaterNode film = water_node_of(run(tin, "film.glb", o));
    EXPECT_EQ(film.nodes, 1u);
    EXPECT_FALSE(film.found);
    const HeightRaster f = read_heightmap(run(tin, "film.exr", o, "water"));
    EXPECT_NEAR(f.heights.front(), 5e-5, 5e-5 * 1e-7);  // float32 metres
}

TEST_F(ExportWater, WaterMapsAreRefusedWhereTheyCannotBeWritten) {
    EXPECT_THROW(export_format_for("x.obj", "water"), std::invalid_argument);
    EXPECT_EQ(export_format_for("x.exr", "water"), ExportFormat::WaterExr);
    EXPECT_EQ(export_format_for("x.png", "water"), ExportFormat::WaterPng);
}

}  // namespace export_water_test
}  // namespace
}  // namespace sandtin
