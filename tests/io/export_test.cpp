// Mesh and map export: every file parsed back by an independent reader (tests/support
// readers; tinygltf's loader for glTF) must match the TIN; winding and watertightness are
// checked by edge counting; a height map re-imports within its quantisation.

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>

#include "formats/png_image.hpp"
#include "io/export_maps.hpp"
#include "io/export_palette.hpp"
#include "io/export_terrain.hpp"
#include "io/heightmap_import.hpp"
#include "io/import_grid.hpp"
#include "maps/normal_map.hpp"
#include "support/mesh_readers.hpp"
#include "support/tin_oracles.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {
namespace {

namespace fs = std::filesystem;

double hills(Vec2 p) {
    return 2.0 + std::sin(p.x * 0.7) * std::cos(p.y * 0.5) + 0.1 * p.x;
}

Tin test_tin() {
    Tin tin = Tin::random_points(Rect{{0.0, 0.0}, {12.0, 8.0}}, 400, 5, hills);
    // Materials and moisture vary, so the albedo has something to show.
    for (VertexId v : test::live_ids(tin)) {
        if (tin.position(v).x > 6.0) tin.set_material(v, 1);
        if (tin.position(v).y > 4.0) tin.set_moisture(v, 0.5f);
    }
    return tin;
}

class Export : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("sandtin-export-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::vector<std::uint8_t> run(const Tin& tin, const std::string& name, ExportOptions o = {},
                                  const std::string& map = "") {
        const fs::path p = dir_ / name;
        report_ = export_terrain(tin, p, export_format_for(p, map), o);
        return read_file(p);
    }
    static std::string text(const std::vector<std::uint8_t>& b) { return {b.begin(), b.end()}; }

    fs::path dir_;
    ExportReport report_;
};

/// Vertex and triangle counts, and bounds, of a surface-only mesh against the TIN (terrain
/// frame: Z-up, metres; `to_terrain` maps a file vertex back).
void expect_matches_tin(const test::SimpleMesh& m, const Tin& tin, bool y_up, double scale,
                        double tolerance) {
    EXPECT_EQ(m.vertices.size(), tin.vertex_count());
    EXPECT_EQ(m.triangles.size(), tin.triangle_count());
    const test::Bounds b = test::bounds_of(m);
    double zmin = 1e300;
    double zmax = -1e300;
    for (VertexId v : test::live_ids(tin)) {
        zmin = std::min(zmin, tin.height(v));
        zmax = std::max(zmax, tin.height(v));
    }
    const Rect d = tin.domain();
    // Terrain (x, y, z) is (x, z, -y) when Y is up.
    const std::array<double, 3> lo = y_up ? std::array<double, 3>{d.min.x, zmin, -d.max.y}
                                          : std::array<double, 3>{d.min.x, d.min.y, zmin};
    const std::array<double, 3> hi = y_up ? std::array<double, 3>{d.max.x, zmax, -d.min.y}
                                          : std::array<double, 3>{d.max.x, d.max.y, zmax};
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_NEAR(b.min[k], lo[k] * scale, tolerance * scale) << "axis " << k;
        EXPECT_NEAR(b.max[k], hi[k] * scale, tolerance * scale) << "axis " << k;
    }
}

/// Every triangle's normal points up (+z, or +y when Y is up).
void expect_upward(const test::SimpleMesh& m, bool y_up) {
    std::size_t down = 0;
    for (const auto& t : m.triangles) {
        const auto n = test::face_cross(m, t);
        if (!((y_up ? n[1] : n[2]) > 0.0)) ++down;
    }
    EXPECT_EQ(down, 0u) << "triangles facing down";
    const test::EdgeCount c = test::count_edges(test::welded(m));
    EXPECT_EQ(c.inconsistent, 0u) << "inconsistent winding";
    EXPECT_EQ(c.non_manifold, 0u);
}

/// The file's triangles are the TIN's triangles (matched by exact corner positions).
void expect_same_triangles(const test::SimpleMesh& m, const Tin& tin) {
    using P = std::array<double, 2>;
    std::set<std::array<P, 3>> expected;
    auto canon = [](std::array<P, 3> t) {
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        return t;
    };
    for (const auto& t : tin.triangles()) {
        std::array<P, 3> tri;
        for (std::size_t k = 0; k < 3; ++k)
            tri[k] = {tin.position(t[k]).x, tin.position(t[k]).y};
        expected.insert(canon(tri));
    }
    std::set<std::array<P, 3>> got;
    for (const auto& t : m.triangles) {
        std::array<P, 3> tri;
        for (std::size_t k = 0; k < 3; ++k)
            tri[k] = {m.vertices[t[k]][0], m.vertices[t[k]][1]};
        got.insert(canon(tri));
    }
    EXPECT_EQ(got, expected);
}

TEST_F(Export, ObjRoundTrip) {
    const Tin tin = test_tin();
    const auto bytes = run(tin, "t.obj");  // Y-up by default
    const test::SimpleMesh m = test::read_obj_text(text(bytes));
    expect_matches_tin(m, tin, true, 1.0, 0.0);
    expect_upward(m, true);
    // Back to the terrain frame: exact positions (shortest round-trip decimals).
    test::SimpleMesh z_up = m;
    for (auto& v : z_up.vertices)
        v = {v[0], -v[2], v[1]};
    expect_same_triangles(z_up, tin);
    EXPECT_EQ(m.normals.size(), tin.vertex_count());
    ASSERT_EQ(m.uvs.size(), tin.vertex_count());
    for (const auto& uv : m.uvs) {
        EXPECT_GE(uv[0], 0.0);
        EXPECT_LE(uv[1], 1.0);
    }
    // MTL and both textures were written next to it and are referenced.
    const std::string mtl = text(read_file(dir_ / "t.mtl"));
    EXPECT_NE(text(bytes).find("mtllib t.mtl"), std::string::npos);
    EXPECT_NE(mtl.find("map_Kd t_albedo.png"), std::string::npos);
    EXPECT_NE(mtl.find("map_Bump t_normal.png"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir_ / "t_albedo.png"));
    EXPECT_TRUE(fs::exists(dir_ / "t_normal.png"));
    EXPECT_EQ(report_.files.size(), 4u);
}

TEST_F(Export, PlyRoundTrip) {
    const Tin tin = test_tin();
    const test::SimpleMesh m = test::read_ply_binary(run(tin, "t.ply"));  // Z-up by default
    expect_matches_tin(m, tin, false, 1.0, 1e-6);
    expect_upward(m, false);
    ASSERT_EQ(m.normals.size(), m.vertices.size());
    for (const auto& n : m.normals) {
        EXPECT_NEAR(std::hypot(n[0], n[1], n[2]), 1.0, 1e-6);
        EXPECT_GT(n[2], 0.0);
    }
}

TEST_F(Export, StlRoundTrip) {
    const Tin tin = test_tin();
    std::vector<std::array<double, 3>> facet_normals;
    const test::SimpleMesh m = test::read_stl_binary(run(tin, "t.stl"), &facet_normals);
    expect_matches_tin(m, tin, false, 1.0, 1e-6);
    expect_upward(m, false);
    // The stored facet normals agree with the winding.
    for (std::size_t k = 0; k < m.triangles.size(); ++k) {
        const auto n = test::face_cross(m, m.triangles[k]);
        const double dot =
            n[0] * facet_normals[k][0] + n[1] * facet_normals[k][1] + n[2] * facet_normals[k][2];
        EXPECT_GT(dot, 0.0);
    }
}

/// Loads a .glb or .gltf with tinygltf and flattens its one primitive.
struct LoadedGltf {
    tinygltf::Model model;
    test::SimpleMesh mesh;
    std::vector<std::array<double, 4>> tangents;  ///< per vertex (xyz, handedness w)
};

LoadedGltf load_gltf(const std::vector<std::uint8_t>& bytes, bool binary) {
    LoadedGltf out;
    tinygltf::TinyGLTF loader;
    std::string err;
    std::string warn;
    const bool ok = binary
                        ? loader.LoadBinaryFromMemory(&out.model, &err, &warn, bytes.data(),
                                                      static_cast<unsigned int>(bytes.size()))
                        : loader.LoadASCIIFromString(&out.model, &err, &warn,
                                                     reinterpret_cast<const char*>(bytes.data()),
                                                     static_cast<unsigned int>(bytes.size()), "");
    EXPECT_TRUE(ok) << err;
    EXPECT_EQ(err, "");
    if (!ok) return out;
    const tinygltf::Primitive& prim = out.model.meshes.at(0).primitives.at(0);
    auto floats = [&](int accessor, int n) {
        const tinygltf::Accessor& a = out.model.accessors.at(static_cast<std::size_t>(accessor));
        const tinygltf::BufferView& v =
            out.model.bufferViews.at(static_cast<std::size_t>(a.bufferView));
        const auto* data = reinterpret_cast<const float*>(
            out.model.buffers.at(static_cast<std::size_t>(v.buffer)).data.data() + v.byteOffset +
            a.byteOffset);
        return std::vector<float>(data, data + a.count * static_cast<std::size_t>(n));
    };
    const std::vector<float> p = floats(prim.attributes.at("POSITION"), 3);
    const std::vector<float> n = floats(prim.attributes.at("NORMAL"), 3);
    const std::vector<float> uv = floats(prim.attributes.at("TEXCOORD_0"), 2);
    const std::vector<float> t = prim.attributes.count("TANGENT")
                                     ? floats(prim.attributes.at("TANGENT"), 4)
                                     : std::vector<float>{};
    for (std::size_t i = 0; i < t.size() / 4; ++i)
        out.tangents.push_back({t[4 * i], t[4 * i + 1], t[4 * i + 2], t[4 * i + 3]});
    for (std::size_t i = 0; i < p.size() / 3; ++i) {
        out.mesh.vertices.push_back({p[3 * i], p[3 * i + 1], p[3 * i + 2]});
        out.mesh.normals.push_back({n[3 * i], n[3 * i + 1], n[3 * i + 2]});
        out.mesh.uvs.push_back({uv[2 * i], uv[2 * i + 1]});
    }
    const tinygltf::Accessor& ia = out.model.accessors.at(static_cast<std::size_t>(prim.indices));
    EXPECT_EQ(ia.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    const tinygltf::BufferView& iv =
        out.model.bufferViews.at(static_cast<std::size_t>(ia.bufferView));
    const auto* idx = reinterpret_cast<const std::uint32_t*>(out.model.buffers.at(0).data.data() +
                                                             iv.byteOffset + ia.byteOffset);
    for (std::size_t k = 0; k + 2 < ia.count; k += 3)
        out.mesh.triangles.push_back({idx[k], idx[k + 1], idx[k + 2]});
    return out;
}

TEST_F(Export, GlbRoundTripThroughTinygltf) {
    const Tin tin = test_tin();
    const LoadedGltf g = load_gltf(run(tin, "t.glb"), true);
    expect_matches_tin(g.mesh, tin, true, 1.0, 1e-5);
    expect_upward(g.mesh, true);
    // Accessor bounds as the spec requires, normals of unit length pointing up.
    const tinygltf::Accessor& pa = g.model.accessors.at(
        static_cast<std::size_t>(g.model.meshes[0].primitives[0].attributes.at("POSITION")));
    ASSERT_EQ(pa.minValues.size(), 3u);
    EXPECT_NEAR(pa.maxValues[0], 12.0, 1e-6);
    for (const auto& n : g.mesh.normals) {
        EXPECT_NEAR(std::hypot(n[0], n[1], n[2]), 1.0, 1e-5);
        EXPECT_GT(n[1], 0.0);
    }
    EXPECT_TRUE(g.model.meshes[0].primitives[0].attributes.count("TANGENT"));
    // The material carries the albedo and normal textures; tinygltf decodes both PNGs.
    ASSERT_EQ(g.model.materials.size(), 1u);
    const tinygltf::Material& mat = g.model.materials[0];
    ASSERT_GE(mat.pbrMetallicRoughness.baseColorTexture.index, 0);
    ASSERT_GE(mat.normalTexture.index, 0);
    ASSERT_EQ(g.model.images.size(), 2u);
    for (const tinygltf::Image& image : g.model.images) {
        EXPECT_EQ(image.mimeType, "image/png");
        EXPECT_EQ(image.width, 1024);
        EXPECT_EQ(image.height, 683);  // 1024 * 8 / 12, rounded
        EXPECT_FALSE(image.image.empty());
    }
    // uv (0, 0) is the north-west corner.
    for (std::size_t i = 0; i < g.mesh.vertices.size(); ++i) {
        const auto& v = g.mesh.vertices[i];
        EXPECT_NEAR(g.mesh.uvs[i][0], v[0] / 12.0, 1e-6);
        EXPECT_NEAR(g.mesh.uvs[i][1], (8.0 + v[2]) / 8.0, 1e-6);
    }
}

/// What a glTF viewer shades at the centre of every `step`-th texel of the material's normal
/// texture, in the terrain's frame (x east, y north, z up), with the texel's (col, row). The
/// glTF 2.0 rule, written here from the specification and not from the exporter: find the
/// triangle under the texture coordinate, interpolate the vertex NORMAL and TANGENT there and
/// normalise them, B = (N x T) w, decode the texel t = 2 rgb / 255 - 1, and shade
/// normalise(T t.x + B t.y + N t.z).
struct ShadedTexel {
    std::uint32_t col, row;
    Vec3 shaded;
    Vec3 texel;  ///< the decoded tangent-space vector
};

std::vector<ShadedTexel> shade_normal_texture(const LoadedGltf& g, std::uint32_t step) {
    const tinygltf::Material& mat = g.model.materials.at(0);
    const tinygltf::Texture& tex =
        g.model.textures.at(static_cast<std::size_t>(mat.normalTexture.index));
    const tinygltf::Image& image = g.model.images.at(static_cast<std::size_t>(tex.source));
    EXPECT_EQ(image.bits, 8);
    const auto w = static_cast<std::uint32_t>(image.width);
    const auto h = static_cast<std::uint32_t>(image.height);
    const auto comp = static_cast<std::size_t>(image.component);
    const test::SimpleMesh& m = g.mesh;
    const auto v3 = [](const std::array<double, 3>& a) { return Vec3{a[0], a[1], a[2]}; };
    std::vector<ShadedTexel> out;
    for (std::uint32_t row = step / 2; row < h; row += step) {
        for (std::uint32_t col = step / 2; col < w; col += step) {
            const double u = (col + 0.5) / w;
            const double v = (row + 0.5) / h;
            for (const auto& tri : m.triangles) {
                const auto& a = m.uvs[tri[0]];
                const auto& b = m.uvs[tri[1]];
                const auto& c = m.uvs[tri[2]];
                const double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
                if (area == 0.0) continue;
                const double wa = ((b[0] - u) * (c[1] - v) - (b[1] - v) * (c[0] - u)) / area;
                const double wb = ((c[0] - u) * (a[1] - v) - (c[1] - v) * (a[0] - u)) / area;
                const double wc = 1.0 - wa - wb;
                if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
                Vec3 n{};
                Vec3 t{};
                for (const auto& [k, weight] :
                     {std::pair{tri[0], wa}, std::pair{tri[1], wb}, std::pair{tri[2], wc}}) {
                    n += v3(m.normals[k]) * weight;
                    const auto& tk = g.tangents[k];
                    t += Vec3{tk[0], tk[1], tk[2]} * weight;
                }
                n = normalised(n);
                t = normalised(t);
                const Vec3 bitangent = cross(n, t) * g.tangents[tri[0]][3];
                const std::size_t px = (static_cast<std::size_t>(row) * w + col) * comp;
                const Vec3 texel{image.image[px] / 255.0 * 2.0 - 1.0,
                                 image.image[px + 1] / 255.0 * 2.0 - 1.0,
                                 image.image[px + 2] / 255.0 * 2.0 - 1.0};
                const Vec3 s = normalised(t * texel.x + bitangent * texel.y + n * texel.z);
                out.push_back({col, row, Vec3{s.x, -s.z, s.y}, texel});  // Y-up to terrain frame
                break;
            }
        }
    }
    return out;
}

double degrees_between(Vec3 a, Vec3 b) {
    return std::acos(std::clamp(dot(normalised(a), normalised(b)), -1.0, 1.0)) * 180.0 /
           std::numbers::pi;
}

// glTF's normalTexture is a tangent-space map. The oracle is the viewer's rule above: what it
// shades must be the terrain's own normals, baked in the terrain's frame (bake_normal_map), on
// the full mesh, on a coarse re-mesh whose map must carry the lost detail, and faceted. An
// object-space map shaded by that rule tilts each slope twice (this terrain's slopes reach
// 40 degrees).
TEST_F(Export, GlbNormalTextureShadesTheTerrainsNormalsThroughTheMeshsTangentFrame) {
    const Tin tin = test_tin();
    struct Case {
        const char* name;
        std::optional<double> max_error;
        NormalMode mode;
    };
    for (const Case& c : {Case{"full mesh", std::nullopt, NormalMode::Smooth},
                          Case{"re-mesh", 0.05, NormalMode::Smooth},
                          Case{"faceted", std::nullopt, NormalMode::Faceted}}) {
        SCOPED_TRACE(c.name);
        ExportOptions o;
        o.max_error = c.max_error;
        o.normal_mode = c.mode;
        o.map_size = 256;
        const LoadedGltf g = load_gltf(run(tin, "n.glb", o), true);
        ASSERT_EQ(g.tangents.size(), g.mesh.vertices.size());
        const std::vector<ShadedTexel> texels = shade_normal_texture(g, 3);
        ASSERT_GT(texels.size(), 4000u);  // 256 x 171 texels, every third
        const MapGrid grid(tin.domain(), report_.map_width, report_.map_height, SampleAt::Centres);
        const MapImage world = bake_normal_map(tin, grid, c.mode);
        double worst = 0.0;
        double largest_tilt = 0.0;  // how far the texels lean off (0, 0, 1)
        for (const ShadedTexel& t : texels) {
            const Vec3 want{world.at(t.col, t.row, 0), world.at(t.col, t.row, 1),
                            world.at(t.col, t.row, 2)};
            worst = std::max(worst, degrees_between(t.shaded, want));
            largest_tilt = std::max(largest_tilt, degrees_between(t.texel, {0.0, 0.0, 1.0}));
        }
        EXPECT_LT(worst, 1.0) << "8-bit texels resolve about half a degree";
        if (c.max_error || c.mode == NormalMode::Faceted) {
            EXPECT_GT(largest_tilt, 5.0) << "the map carries what the mesh lacks";
        } else {
            // The full mesh already carries every normal: the map is flat.
            EXPECT_LT(largest_tilt, 1.0);
        }
    }
}

TEST_F(Export, GltfTextIsSelfContainedAndMatchesGlb) {
    const Tin tin = test_tin();
    const LoadedGltf text_version = load_gltf(run(tin, "t.gltf"), false);
    const LoadedGltf binary_version = load_gltf(run(tin, "u.glb"), true);
    EXPECT_EQ(text_version.mesh.vertices, binary_version.mesh.vertices);
    EXPECT_EQ(text_version.mesh.triangles, binary_version.mesh.triangles);
    EXPECT_EQ(report_.files.size(), 1u) << "one self-contained file";
}

TEST_F(Export, SolidBaseIsAClosedTwoManifoldInEveryFormat) {
    const Tin tin = test_tin();
    ExportOptions o;
    o.base = BaseKind::Solid;
    o.base_depth = 0.5;
    o.textures = false;
    std::vector<std::pair<std::string, test::SimpleMesh>> meshes;
    meshes.emplace_back("obj", test::read_obj_text(text(run(tin, "s.obj", o))));
    meshes.emplace_back("ply", test::read_ply_binary(run(tin, "s.ply", o)));
    meshes.emplace_back("stl", test::read_stl_binary(run(tin, "s.stl", o)));
    meshes.emplace_back("glb", load_gltf(run(tin, "s.glb", o), true).mesh);
    double zmin = 1e300;
    for (VertexId v : test::live_ids(tin))
        zmin = std::min(zmin, tin.height(v));
    // The enclosed volume is the volume between the surface and the bottom plane.
    const double expected = test::brute_force_volume(tin, zmin - 0.5);
    for (const auto& [format, mesh] : meshes) {
        SCOPED_TRACE(format);
        const test::SimpleMesh w = test::welded(mesh);
        EXPECT_EQ(test::join(test::closed_manifold_problems(w)), "");
        // Euler: V - E + F = 2 for a closed surface of genus 0.
        const test::EdgeCount c = test::count_edges(w);
        EXPECT_EQ(static_cast<long>(w.vertices.size()) - static_cast<long>(c.edges) +
                      static_cast<long>(w.triangles.size()),
                  2);
        EXPECT_NEAR(test::enclosed_volume(w), expected, 1e-4 * expected) << "outward winding";
    }
}

TEST_F(Export, SkirtHangsWallsWithoutClosingTheBottom) {
    const Tin tin = test_tin();
    ExportOptions o;
    o.base = BaseKind::Skirt;
    o.base_depth = 2.0;
    const test::SimpleMesh m = test::welded(test::read_ply_binary(run(tin, "k.ply", o)));
    const test::EdgeCount c = test::count_edges(m);
    EXPECT_EQ(c.inconsistent, 0u);
    EXPECT_EQ(c.non_manifold, 0u);
    // The open edges are exactly the bottom ring: one per border edge of the TIN.
    EXPECT_EQ(c.boundary, test::border_vertex_count(tin));
    EXPECT_NEAR(test::bounds_of(m).min[2], report_.min.z, 1e-5);
}

TEST_F(Export, UnitsAndUpAxis) {
    const Tin tin = test_tin();
    ExportOptions mm;
    mm.units = "mm";
    const test::SimpleMesh m = test::read_ply_binary(run(tin, "mm.ply", mm));
    expect_matches_tin(m, tin, false, 1000.0, 1e-6);
    ExportOptions y;
    y.up = UpAxis::Y;
    y.units = "cm";
    const test::SimpleMesh my = test::read_stl_binary(run(tin, "y.stl", y));
    expect_matches_tin(my, tin, true, 100.0, 1e-6);
    expect_upward(my, true);
    ExportOptions z;
    z.up = UpAxis::Z;
    EXPECT_THROW(run(tin, "z.glb", z), std::invalid_argument);
    ExportOptions bad;
    bad.units = "furlong";
    EXPECT_THROW(run(tin, "f.obj", bad), std::invalid_argument);
}

TEST_F(Export, SimplifyingOnExportKeepsTheErrorBound) {
    // A domain away from the origin: the simplified mesh must stay where the terrain is.
    const Tin tin = Tin::regular_grid(Rect{{3, -2}, {23, 8}}, 80, 40, hills);
    ExportOptions o;
    o.max_error = 0.05;
    o.cell_size = 0.25;  // the grid's own spacing
    const test::SimpleMesh m = test::read_ply_binary(run(tin, "s.ply", o));
    ASSERT_TRUE(report_.simplified.has_value());
    EXPECT_LT(m.vertices.size(), tin.vertex_count());
    EXPECT_LE(report_.simplified->max_error, 0.05);
    // Independently: rebuild the exported surface and compare it with the TIN at every grid
    // vertex (a brute-force search in the exported triangles).
    std::size_t checked = 0;
    double worst = 0.0;
    for (VertexId v : test::live_ids(tin)) {
        const Vec2 p = tin.position(v);
        for (const auto& t : m.triangles) {
            const auto& a = m.vertices[t[0]];
            const auto& b = m.vertices[t[1]];
            const auto& c = m.vertices[t[2]];
            const auto w = test::barycentric(p, {a[0], a[1]}, {b[0], b[1]}, {c[0], c[1]});
            if (w[0] < -1e-9L || w[1] < -1e-9L || w[2] < -1e-9L) continue;
            const double z = static_cast<double>(w[0] * a[2] + w[1] * b[2] + w[2] * c[2]);
            worst = std::max(worst, std::abs(z - tin.height(v)));
            ++checked;
            break;
        }
    }
    EXPECT_EQ(checked, tin.vertex_count());
    EXPECT_LE(worst, 0.05 + 1e-5);  // float positions in the file
    const test::Bounds b = test::bounds_of(m);
    EXPECT_NEAR(b.min[0], 3.0, 1e-6);
    EXPECT_NEAR(b.min[1], -2.0, 1e-6);
    EXPECT_NEAR(b.max[0], 23.0, 1e-6);
    EXPECT_NEAR(b.max[1], 8.0, 1e-6);
}

TEST_F(Export, HeightPngReimportsWithinTheQuantisation) {
    // An imported terrain: the export grid is the import grid, so every sample is a TIN point.
    HeightRaster raster;
    raster.width = 33;
    raster.height = 21;
    raster.cell_size = 0.5;
    for (std::uint32_t row = 0; row < raster.height; ++row) {
        for (std::uint32_t col = 0; col < raster.width; ++col)
            raster.heights.push_back(hills(raster.position(col, row)) * 10.0);
    }
    const Tin tin = greedy_tin(raster, {0.01, 0}).tin;
    ExportOptions o;
    o.cell_size = 0.5;
    run(tin, "h.png", o);
    EXPECT_EQ(report_.map_width, 33u);
    EXPECT_EQ(report_.map_height, 21u);
    const HeightRaster back = read_heightmap(dir_ / "h.png");
    ASSERT_EQ(back.width, 33u);
    ASSERT_EQ(back.height, 21u);
    EXPECT_EQ(back.cell_size, 0.5);
    EXPECT_EQ(back.domain(), tin.domain());
    const double step = report_.height_step;
    EXPECT_GT(step, 0.0);
    for (std::uint32_t row = 0; row < back.height; ++row) {
        for (std::uint32_t col = 0; col < back.width; ++col) {
            const double z = test::brute_force_height(tin, back.position(col, row));
            ASSERT_NEAR(back.at(col, row), z, 0.5 * step + 1e-9) << col << ", " << row;
        }
    }
    // EXR keeps float precision.
    run(tin, "h.exr", o);
    const HeightRaster exr = read_heightmap(dir_ / "h.exr");
    for (std::uint32_t row = 0; row < exr.height; ++row) {
        for (std::uint32_t col = 0; col < exr.width; ++col) {
            const double z = test::brute_force_height(tin, exr.position(col, row));
            ASSERT_NEAR(exr.at(col, row), z, 1e-6 * std::max(1.0, std::abs(z)));
        }
    }
}

TEST_F(Export, AHeightMapWithRowsSpacedUnlikeColumnsReimportsUnstretched) {
    // 1 x 0.5 m at 0.3 m cells: 4 columns 1/3 m apart, 3 rows 0.25 m apart. A plane, so the
    // baked samples are exact and a stretched re-import shows as a wrong height.
    const Rect domain = Rect::from_size(1.0, 0.5);
    const auto plane = [](Vec2 p) { return 1.0 + 0.4 * p.x + 0.8 * p.y; };
    const Tin tin = Tin::random_points(domain, 300, 611, plane);
    ExportOptions o;
    o.cell_size = 0.3;
    for (const char* file : {"rows.png", "rows.exr"}) {
        run(tin, file, o);
        ASSERT_EQ(report_.map_width, 4u);
        ASSERT_EQ(report_.map_height, 3u);
        const HeightRaster back = read_heightmap(dir_ / file);
        EXPECT_DOUBLE_EQ(back.cell_size, 1.0 / 3.0) << file;
        EXPECT_DOUBLE_EQ(back.row_spacing(), 0.25) << file;
        EXPECT_DOUBLE_EQ(report_.map_spacing.x, 1.0 / 3.0) << file;
        EXPECT_DOUBLE_EQ(report_.map_spacing.y, 0.25) << file;
        EXPECT_DOUBLE_EQ(back.domain().width(), 1.0) << file;
        EXPECT_DOUBLE_EQ(back.domain().height(), 0.5) << file;
        for (std::uint32_t row = 0; row < back.height; ++row) {
            for (std::uint32_t col = 0; col < back.width; ++col) {
                const Vec2 p = back.position(col, row);
                EXPECT_NEAR(back.at(col, row), plane(p), 1e-4)  // both origins at 0
                    << file << " " << col << ", " << row;
            }
        }
    }
    // Generic EXR readers take the samples' shape from the standard pixel aspect ratio
    // (width / height of a pixel): 1/3 m by 0.25 m.
    EXPECT_FLOAT_EQ(Imf::InputFile((dir_ / "rows.exr").c_str()).header().pixelAspectRatio(),
                    4.0f / 3.0f);
    // A square grid writes no row spacing of its own.
    o.cell_size = 0.25;
    run(tin, "square.png", o);
    EXPECT_EQ(read_heightmap(dir_ / "square.png").cell_height, 0.0);
}

// A terrain imported on 2 x 3 m cells and exported with both spacings re-imports onto the
// same samples; with the column spacing alone its rows would be resampled (a 10 m spike came
// back at 6.67 m).
// A terrain flat up to rounding exports as a flat map (every sample 0, range 1), not as noise
// stretched over the 16-bit range; a real relief of a micrometre at 5 m still shows.
// An imported terrain's georeference (the source coordinates of its south-west sample, its
// CRS and unit) travels in sandtin's height maps, so export followed by import keeps it.
TEST_F(Export, HeightMapsCarryTheGeoreference) {
    const Tin tin = Tin::random_points(Rect::from_size(30.0, 20.0), 100, 3, hills);
    ExportOptions o;
    o.cell_size = 2.0;
    o.georeference.known = true;
    o.georeference.west = 500015.25;
    o.georeference.south = 3999955.5;
    o.georeference.crs = "PROJCS[\"WGS 84 / UTM zone 33N\"]";
    o.georeference.horizontal_unit = "metre";
    for (const char* file : {"geo.png", "geo.exr"}) {
        run(tin, file, o);
        const HeightRaster back = read_heightmap(dir_ / file);
        EXPECT_TRUE(back.georeference.known) << file;
        EXPECT_EQ(back.georeference.west, 500015.25) << file;
        EXPECT_EQ(back.georeference.south, 3999955.5) << file;
        EXPECT_EQ(back.georeference.crs, o.georeference.crs) << file;
        EXPECT_EQ(back.georeference.horizontal_unit, "metre") << file;
    }
    // Meshes keep their vertices in the terrain frame and name the georeference in a comment.
    for (const char* file : {"geo.obj", "geo.ply"}) {
        const std::string header = text(run(tin, file, o)).substr(0, 400);
        EXPECT_NE(header.find("georeference: the terrain point (0, 0) m lies at west 500015.25, "
                              "south 3999955.5 (metre) in PROJCS"),
                  std::string::npos)
            << file << ": " << header;
    }
    EXPECT_EQ(text(run(tin, "plain.obj", {})).find("georeference"), std::string::npos);
    // Without one, none is invented.
    run(tin, "plain.png", {});
    EXPECT_FALSE(read_heightmap(dir_ / "plain.png").georeference.known);
    // The session's metadata is where the CLI and the editor take it from.
    const Georeference g = import_georeference_of(
        R"({"import": {"georeference": {"west": 1005.0, "south": 2000.5, "crs": "",
            "horizontal_unit": "", "vertical_unit": ""}}})");
    EXPECT_TRUE(g.known);
    EXPECT_EQ(g.west, 1005.0);
    EXPECT_EQ(g.south, 2000.5);
    EXPECT_FALSE(import_georeference_of(R"({"import": {"georeference": {"west": 1}}})").known);
}

TEST_F(Export, AHeightMapFlatUpToRoundingIsFlat) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(4.0, 4.0), 5.0);
    const std::vector<VertexId> ids = test::live_ids(tin);
    tin.set_height(ids[0], 5.0 - 2e-15);
    ExportOptions o;
    o.map_size = 9;
    run(tin, "flat.png", o);
    EXPECT_EQ(report_.height_step, 1.0 / 65535.0);  // the step the map was written with
    const PngImage flat = read_png(dir_ / "flat.png");
    for (const std::uint16_t v : flat.samples)
        ASSERT_EQ(v, 0u);
    const HeightRaster back = read_heightmap(dir_ / "flat.png");
    for (const double h : back.heights)
        EXPECT_NEAR(h, 5.0, 1e-14);
    tin.set_height(ids[0], 5.0 - 1e-6);
    run(tin, "micro.png", o);
    const PngImage micro = read_png(dir_ / "micro.png");
    EXPECT_EQ(*std::max_element(micro.samples.begin(), micro.samples.end()), 65535u);
}

TEST_F(Export, AnOblongImportGridExportsOntoItsOwnSamples) {
    HeightRaster raster;
    raster.width = 5;
    raster.height = 4;
    raster.cell_size = 2.0;
    raster.cell_height = 3.0;
    for (std::uint32_t i = 0; i < raster.size(); ++i)
        raster.heights.push_back(i == 7 ? 10.0 : 0.1 * static_cast<double>(i % 3));
    const Tin tin = greedy_tin(raster, {0.0, 0}).tin;
    const ImportGrid grid{2.0, 3.0};
    ASSERT_TRUE(tin_lies_on_grid(tin, grid));
    const DefaultSampling sampling = default_sampling(tin, grid, 0.01);
    EXPECT_FALSE(sampling.edited);
    ExportOptions o;
    o.cell_size = sampling.cell_size;
    o.cell_height = sampling.cell_height;
    run(tin, "oblong.exr", o);
    const HeightRaster back = read_heightmap(dir_ / "oblong.exr");
    ASSERT_EQ(back.width, 5u);
    ASSERT_EQ(back.height, 4u);
    EXPECT_DOUBLE_EQ(back.cell_size, 2.0);
    EXPECT_DOUBLE_EQ(back.row_spacing(), 3.0);
    for (std::size_t i = 0; i < raster.size(); ++i)
        EXPECT_NEAR(back.heights[i], raster.heights[i], 1e-6) << i;
    // A row spacing without a cell size has nothing to be relative to.
    ExportOptions rows_only;
    rows_only.cell_height = 3.0;
    EXPECT_THROW(run(tin, "bad.png", rows_only), std::invalid_argument);
}

// An edit that inserts a vertex between the import grid's samples makes the default sampling
// finer, so the edit is not sampled away; heights changed on grid vertices keep the grid.
TEST_F(Export, TheImportGridIsTheDefaultOnlyWhileTheTerrainLiesOnIt) {
    HeightRaster raster;
    raster.width = 11;
    raster.height = 11;
    raster.cell_size = 2.0;
    raster.heights.assign(raster.size(), 5.0);
    raster.heights[60] = 6.0;  // a bump, so the TIN keeps an inner vertex
    Tin tin = greedy_tin(raster, {0.0, 0}).tin;
    const std::optional<ImportGrid> grid = import_grid_of(
        R"({"import": {"raster": {"cell_size": 2.0, "cell_height": 0.0}}, "scene": "x"})");
    ASSERT_TRUE(grid.has_value());
    EXPECT_EQ(grid->cell_size, 2.0);
    EXPECT_EQ(grid->row_spacing(), 2.0);
    EXPECT_TRUE(tin_lies_on_grid(tin, *grid));
    VertexId bump = kInvalidVertex;
    for (const VertexId v : test::live_ids(tin))
        if (tin.position(v) == Vec2{10.0, 10.0}) bump = v;
    ASSERT_NE(bump, kInvalidVertex);
    tin.set_height(bump, 7.0);
    EXPECT_TRUE(tin_lies_on_grid(tin, *grid)) << "a height change keeps the vertex on the grid";
    // A 0.5 m pit between samples.
    const VertexId pit = tin.insert_point(Vec2{13.0, 9.0}, 4.5);
    ASSERT_TRUE(tin.is_alive(pit));
    EXPECT_FALSE(tin_lies_on_grid(tin, *grid));
    const DefaultSampling sampling = default_sampling(tin, *grid, 20.0 / 1023.0);
    EXPECT_TRUE(sampling.edited);
    EXPECT_DOUBLE_EQ(sampling.cell_size, 20.0 / 1023.0);
    ExportOptions o;
    o.cell_size = sampling.cell_size;
    run(tin, "edited.png", o);
    const HeightRaster back = read_heightmap(dir_ / "edited.png");
    double lowest = 1e300;
    for (const double h : back.heights)
        lowest = std::min(lowest, h);
    EXPECT_NEAR(lowest, 4.5, 0.01) << "the pit survives the export";
    // No import record, or one with no positive spacing: no import grid.
    EXPECT_FALSE(import_grid_of(R"({"scene": "x"})").has_value());
    EXPECT_FALSE(import_grid_of(R"({"import": {"raster": {"cell_size": 0}}})").has_value());
    EXPECT_FALSE(import_grid_of("not json").has_value());
}

TEST_F(Export, NormalAndAlbedoMapsAreRgbPngs) {
    const Tin tin = test_tin();
    ExportOptions o;
    o.map_size = 64;
    const auto n = run(tin, "n.png", o, "normal");
    EXPECT_EQ(report_.map_width, 64u);
    EXPECT_EQ(report_.map_height, 43u);
    const PngImage normal = decode_png(n);
    EXPECT_EQ(normal.channels, 3);
    // Every texel decodes to an upward unit vector.
    for (std::size_t i = 0; i < normal.samples.size(); i += 3) {
        const double x = normal.samples[i] / 127.5 - 1.0;
        const double y = normal.samples[i + 1] / 127.5 - 1.0;
        const double z = normal.samples[i + 2] / 127.5 - 1.0;
        EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, 0.02);
        EXPECT_GT(z, 0.0);
    }
    const PngImage albedo = decode_png(run(tin, "a.png", o, "albedo"));
    EXPECT_EQ(albedo.channels, 3);
    // Wet sand (north half) is darker than dry sand of the same material (south-west).
    const auto luminance = [&](std::uint32_t col, std::uint32_t row) {
        return albedo.sample(col, row, 0) + albedo.sample(col, row, 1) + albedo.sample(col, row, 2);
    };
    EXPECT_LT(luminance(10, 5), luminance(10, 38));
    // Both say how large a texel is (12 / 64 by 8 / 43 m) and, for an imported terrain, where
    // the terrain's south-west corner lies.
    o.georeference.known = true;
    o.georeference.west = 500000.0;
    o.georeference.south = 4000000.0;
    for (const char* map : {"normal", "albedo"}) {
        const PngImage image = decode_png(run(tin, "geo.png", o, map));
        const auto text = [&](const std::string& key) {
            for (const auto& [k, v] : image.text)
                if (k == key) return std::stod(v);
            ADD_FAILURE() << map << ": no " << key;
            return 0.0;
        };
        EXPECT_DOUBLE_EQ(text("sandtin:texel_size"), 12.0 / 64.0) << map;
        EXPECT_DOUBLE_EQ(text("sandtin:texel_height"), 8.0 / 43.0) << map;
        EXPECT_DOUBLE_EQ(text("sandtin:west"), 500000.0) << map;
        EXPECT_DOUBLE_EQ(text("sandtin:south"), 4000000.0) << map;
    }
}

/// The sRGB transfer function as IEC 61966-2-1 writes it, for the oracle: linear -> encoded.
double srgb_from_linear(double c) {
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// Exports bake each material's colour as the viewport shades it (linear albedo, wet sand
// darker by the viewport's factor) and store it sRGB-encoded, as PNG viewers, glTF and OBJ
// read it; a material table the artist recoloured (the editor's Materials panel, a scene's
// metadata) reaches the albedo map and the untextured glTF's base colour. Before, every export
// used fixed colours near the presets', stored unencoded.
TEST_F(Export, AlbedoIsTheScenesMaterialColourInSrgb) {
    Tin tin = Tin::random_points(Rect{{0.0, 0.0}, {4.0, 4.0}}, 200, 3, hills);
    for (VertexId v : test::live_ids(tin)) {
        if (tin.position(v).x > 2.0) tin.set_material(v, 1);
        if (tin.position(v).y > 2.0) tin.set_moisture(v, 1.0f);
    }
    MaterialTable table = MaterialTable::presets();
    std::vector<Material> recoloured = table.all();
    recoloured[0].colour[0] = 0.6f;
    recoloured[0].colour[1] = 0.05f;
    recoloured[0].colour[2] = 0.0f;
    recoloured[1].colour[0] = 0.1f;
    recoloured[1].colour[1] = 0.3f;
    recoloured[1].colour[2] = 0.9f;
    for (const MaterialTable& materials : {table, MaterialTable(recoloured)}) {
        ExportOptions o;
        o.map_size = 16;
        o.palette = export_palette(materials);
        const PngImage albedo = decode_png(run(tin, "a.png", o, "albedo"));
        // Texel centres in the middle of each quadrant lie inside one material and moisture
        // (the terrain's triangles are far smaller than a quadrant's interior).
        for (const auto& [col, row, material, moisture] :
             std::vector<std::tuple<std::uint32_t, std::uint32_t, std::size_t, double>>{
                 {3, 12, 0, 0.0}, {12, 12, 1, 0.0}, {3, 3, 0, 1.0}, {12, 3, 1, 1.0}}) {
            const Material& m = materials.all()[material];
            for (std::uint32_t c = 0; c < 3; ++c) {
                const double linear =
                    static_cast<double>(m.colour[c]) *
                    (1.0 - (1.0 - static_cast<double>(kWetReflectance)) * moisture);
                EXPECT_EQ(static_cast<long>(albedo.sample(col, row, c)),
                          std::lround(255.0 * srgb_from_linear(linear)))
                    << m.name << " channel " << c << " at texel " << col << ", " << row;
            }
        }
        o.textures = false;
        const LoadedGltf g = load_gltf(run(tin, "plain.glb", o), true);
        const std::vector<double> factor =
            g.model.materials.at(0).pbrMetallicRoughness.baseColorFactor;
        ASSERT_EQ(factor.size(), 4u);
        for (std::size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(factor[c], static_cast<double>(materials.all()[0].colour[c]), 1e-7);
    }
}

// The albedo PNG's encoding over the whole range, against the transfer function written out
// above: every linear value in steps of 1/2000, and values past either end (clamped).
TEST(AlbedoPng, EncodesLinearAlbedoAsTheNearestSrgbCode) {
    MapImage ramp{2003, 1, 3, {}};
    std::vector<double> linear;
    for (int i = -1; i <= 2001; ++i)
        linear.push_back(i / 2000.0);
    for (const double v : linear)
        ramp.values.insert(ramp.values.end(), {v, v, v});
    const PngImage png = decode_png(encode_albedo_png(ramp));
    ASSERT_EQ(png.width, 2003u);
    for (std::uint32_t i = 0; i < png.width; ++i) {
        const double v = std::clamp(linear[i], 0.0, 1.0);
        EXPECT_EQ(static_cast<long>(png.sample(i, 0, 1)), std::lround(255.0 * srgb_from_linear(v)))
            << "linear " << linear[i];
    }
}

// A texel size (the CLI's --cell-size) spaces the texels of normal and albedo maps and of mesh
// textures, each side rounded to whole texels; the report gives the spacing the map got.
TEST_F(Export, ATexelSizeSpacesNormalAndAlbedoMapsAndMeshTextures) {
    const Tin tin = test_tin();  // 12 x 8 m
    ExportOptions o;
    o.texel_size = 0.5;
    for (const char* map : {"normal", "albedo"}) {
        const PngImage image = decode_png(run(tin, "t.png", o, map));
        EXPECT_EQ(image.width, 24u) << map;
        EXPECT_EQ(image.height, 16u) << map;
        EXPECT_DOUBLE_EQ(report_.map_spacing.x, 0.5) << map;
        EXPECT_DOUBLE_EQ(report_.map_spacing.y, 0.5) << map;
    }
    o.texel_size = 0.7;  // 17.1 and 11.4 texels: 17 x 11, spaced 12/17 and 8/11 m
    run(tin, "t.png", o, "normal");
    EXPECT_EQ(report_.map_width, 17u);
    EXPECT_EQ(report_.map_height, 11u);
    EXPECT_DOUBLE_EQ(report_.map_spacing.x, 12.0 / 17.0);
    EXPECT_DOUBLE_EQ(report_.map_spacing.y, 8.0 / 11.0);
    o.texel_size = 0.25;
    const LoadedGltf g = load_gltf(run(tin, "t.glb", o), true);
    ASSERT_EQ(g.model.images.size(), 2u);
    for (const tinygltf::Image& image : g.model.images) {
        EXPECT_EQ(image.width, 48);
        EXPECT_EQ(image.height, 32);
    }
    // Height maps sample corners: 12 / 0.5 + 1 columns; their spacing is reported too.
    ExportOptions h;
    h.cell_size = 0.5;
    run(tin, "h.png", h);
    EXPECT_EQ(report_.map_width, 25u);
    EXPECT_DOUBLE_EQ(report_.map_spacing.x, 0.5);
    o.texel_size = 1e-4;  // 120 000 texels along 12 m
    EXPECT_THROW(run(tin, "fine.png", o, "normal"), std::invalid_argument);
    o.texel_size = -1.0;
    EXPECT_THROW(run(tin, "neg.png", o, "albedo"), std::invalid_argument);
}

TEST_F(Export, BadExportRequests) {
    const Tin tin = test_tin();
    EXPECT_THROW(export_format_for("x.fbx"), std::invalid_argument);
    EXPECT_THROW(export_format_for("x.png", "curvature"), std::invalid_argument);
    EXPECT_THROW(export_format_for("x.obj", "normal"), std::invalid_argument);
    ExportOptions o;
    o.base = BaseKind::Solid;
    o.base_depth = -1.0;
    EXPECT_THROW(run(tin, "b.stl", o), std::invalid_argument);
    ExportOptions maps;
    maps.base = BaseKind::Solid;
    EXPECT_THROW(run(tin, "b.png", maps), std::invalid_argument);
    ExportOptions cell;
    cell.cell_size = 1e-6;
    EXPECT_THROW(run(tin, "c.png", cell), std::invalid_argument);
    EXPECT_THROW(export_terrain(tin, dir_ / "no" / "such" / "dir.stl", ExportFormat::Stl),
                 std::runtime_error);
}

}  // namespace
}  // namespace sandtin
