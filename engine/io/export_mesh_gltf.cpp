#include "io/export_mesh_gltf.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "maps/vertex_normals.hpp"

namespace sandtin {

namespace {

/// Appends raw bytes to the buffer as a new 4-byte-aligned buffer view; returns its index.
int add_view(tinygltf::Model& model, const void* data, std::size_t size, int target) {
    std::vector<unsigned char>& buffer = model.buffers[0].data;
    buffer.resize((buffer.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = size;
    view.target = target;
    const auto* bytes = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), bytes, bytes + size);
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size() - 1);
}

int add_accessor(tinygltf::Model& model, const std::vector<float>& values, int components, int type,
                 bool with_bounds) {
    tinygltf::Accessor a;
    a.bufferView =
        add_view(model, values.data(), values.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.count = values.size() / static_cast<std::size_t>(components);
    a.type = type;
    if (with_bounds) {
        a.minValues.assign(static_cast<std::size_t>(components),
                           std::numeric_limits<double>::max());
        a.maxValues.assign(static_cast<std::size_t>(components),
                           -std::numeric_limits<double>::max());
        for (std::size_t i = 0; i < values.size(); ++i) {
            const std::size_t c = i % static_cast<std::size_t>(components);
            a.minValues[c] = std::min(a.minValues[c], static_cast<double>(values[i]));
            a.maxValues[c] = std::max(a.maxValues[c], static_cast<double>(values[i]));
        }
    }
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size() - 1);
}

int add_texture(tinygltf::Model& model, const std::vector<std::uint8_t>& png,
                const std::string& name) {
    tinygltf::Image image;
    image.name = name;
    image.mimeType = "image/png";
    image.bufferView = add_view(model, png.data(), png.size(), 0);
    model.images.push_back(image);
    tinygltf::Texture texture;
    texture.source = static_cast<int>(model.images.size() - 1);
    texture.sampler = 0;
    model.textures.push_back(texture);
    return static_cast<int>(model.textures.size() - 1);
}

int add_indices(tinygltf::Model& model, const std::vector<std::uint32_t>& indices) {
    tinygltf::Accessor a;
    a.bufferView = add_view(model, indices.data(), indices.size() * sizeof(std::uint32_t),
                            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.count = indices.size();
    a.type = TINYGLTF_TYPE_SCALAR;
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size() - 1);
}

/// The water surface as its own mesh, material and node; returns the node's index.
int add_water_node(tinygltf::Model& model, const ExportMesh& water) {
    std::vector<float> positions;
    std::vector<float> normals;
    for (std::size_t i = 0; i < water.positions.size(); ++i) {
        for (double v : {water.positions[i].x, water.positions[i].y, water.positions[i].z})
            positions.push_back(static_cast<float>(v));
        for (double v : {water.normals[i].x, water.normals[i].y, water.normals[i].z})
            normals.push_back(static_cast<float>(v));
    }
    std::vector<std::uint32_t> indices;
    for (const auto& t : water.triangles)
        indices.insert(indices.end(), t.begin(), t.end());
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.attributes["POSITION"] = add_accessor(model, positions, 3, TINYGLTF_TYPE_VEC3, true);
    primitive.attributes["NORMAL"] = add_accessor(model, normals, 3, TINYGLTF_TYPE_VEC3, false);
    primitive.indices = add_indices(model, indices);

    tinygltf::Material material;
    material.name = "water";
    material.pbrMetallicRoughness.baseColorFactor = {0.05, 0.25, 0.35, 0.55};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.05;
    material.alphaMode = "BLEND";
    material.doubleSided =
        true;  // seen from below through the sand's edge, or from a camera under it
    model.materials.push_back(material);
    primitive.material = static_cast<int>(model.materials.size() - 1);

    tinygltf::Mesh mesh;
    mesh.name = "water";
    mesh.primitives.push_back(primitive);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = "water";
    node.mesh = static_cast<int>(model.meshes.size() - 1);
    model.nodes.push_back(node);
    return static_cast<int>(model.nodes.size() - 1);
}

}  // namespace

std::vector<std::uint8_t> encode_gltf(const ExportMesh& mesh, const GltfTextures& textures,
                                      bool binary, const ExportMesh* water) {
    if (water != nullptr && water->up != UpAxis::Y) {
        throw std::invalid_argument("glTF export: the water mesh must be Y-up too");
    }
    if (mesh.up != UpAxis::Y) {
        throw std::invalid_argument("glTF export: glTF is Y-up by specification");
    }
    std::vector<float> positions;
    std::vector<float> normals;
    std::vector<float> tangents;
    std::vector<float> uvs;
    std::vector<std::uint32_t> indices;
    auto emit = [&](Vec3 p, Vec3 n, const std::array<double, 2>& uv) {
        const Vec3 t = surface_tangent(n, {0.0, 1.0, 0.0});  // the map's frame
        for (double v : {p.x, p.y, p.z})
            positions.push_back(static_cast<float>(v));
        for (double v : {n.x, n.y, n.z})
            normals.push_back(static_cast<float>(v));
        for (double v : {t.x, t.y, t.z, 1.0})
            tangents.push_back(static_cast<float>(v));
        uvs.push_back(static_cast<float>(uv[0]));
        uvs.push_back(static_cast<float>(uv[1]));
        return static_cast<std::uint32_t>(positions.size() / 3 - 1);
    };
    for (std::size_t i = 0; i < mesh.surface_vertices; ++i)
        emit(mesh.positions[i], mesh.normals[i], mesh.uvs[i]);
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        const auto& t = mesh.triangles[k];
        if (k < mesh.surface_triangles) {
            indices.insert(indices.end(), t.begin(), t.end());
            continue;
        }
        const Vec3 n = triangle_normal(mesh, k);
        for (std::uint32_t v : t)
            indices.push_back(emit(mesh.positions[v], n, mesh.uvs[v]));
    }

    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "sandtin";
    model.buffers.emplace_back();
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.attributes["POSITION"] = add_accessor(model, positions, 3, TINYGLTF_TYPE_VEC3, true);
    primitive.attributes["NORMAL"] = add_accessor(model, normals, 3, TINYGLTF_TYPE_VEC3, false);
    primitive.attributes["TANGENT"] = add_accessor(model, tangents, 4, TINYGLTF_TYPE_VEC4, false);
    primitive.attributes["TEXCOORD_0"] = add_accessor(model, uvs, 2, TINYGLTF_TYPE_VEC2, false);
    primitive.indices = add_indices(model, indices);

    tinygltf::Material material;
    material.name = "sand";
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 1.0;
    material.doubleSided = false;
    if (!textures.albedo_png.empty() || !textures.normal_png.empty()) {
        tinygltf::Sampler sampler;
        sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
        sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
        sampler.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        model.samplers.push_back(sampler);
    }
    if (!textures.albedo_png.empty()) {
        material.pbrMetallicRoughness.baseColorTexture.index =
            add_texture(model, textures.albedo_png, "albedo");
    } else {
        material.pbrMetallicRoughness.baseColorFactor = {
            textures.base_colour.x, textures.base_colour.y, textures.base_colour.z, 1.0};
    }
    if (!textures.normal_png.empty()) {
        material.normalTexture.index = add_texture(model, textures.normal_png, "normal");
    }
    model.materials.push_back(material);
    primitive.material = 0;

    tinygltf::Mesh gltf_mesh;
    gltf_mesh.name = "terrain";
    gltf_mesh.primitives.push_back(primitive);
    model.meshes.push_back(gltf_mesh);
    tinygltf::Node node;
    node.name = "terrain";
    node.mesh = 0;
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.name = "sandtin";
    scene.nodes.push_back(0);
    if (water != nullptr && !water->triangles.empty())
        scene.nodes.push_back(add_water_node(model, *water));
    model.scenes.push_back(scene);
    model.defaultScene = 0;

    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, !binary, binary)) {
        throw std::runtime_error("glTF export: tinygltf could not serialise the model");
    }
    const std::string bytes = out.str();
    return {bytes.begin(), bytes.end()};
}

}  // namespace sandtin
