// Mesh and map export: every file parsed back by an independent reader (tests/support
// readers; tinygltf's loader for glTF) must match the TIN; winding and watertightness are
// checked by edge counting (height maps: export_height_map_test.cpp).

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <tuple>

#include "export_fixture.hpp"
#include "formats/png_image.hpp"
#include "io/export_maps.hpp"
#include "io/export_palette.hpp"
#include "io/export_terrain.hpp"
#include "maps/normal_map.hpp"
#include "support/mesh_readers.hpp"
#include "support/tin_oracles.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {
namespace {

using namespace export_test;

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
