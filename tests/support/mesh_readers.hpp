#pragma once
// Minimal, independent readers for the exported meshes (OBJ, binary PLY, binary STL) and the
// mesh checks the export tests share: bounds, winding, closed 2-manifold by edge counting.
// Written from the format descriptions, sharing no code with engine/io, so a round trip
// compares the exporter against an outside view of the file.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace sandtin::test {

struct SimpleMesh {
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<double, 3>> normals;  ///< per vertex when the file has them
    std::vector<std::array<double, 2>> uvs;      ///< per vertex when the file has them
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// OBJ: "v x y z", "vt u v", "vn x y z", "f a/b/c ..." (1-based, triangles only).
inline SimpleMesh read_obj_text(const std::string& text) {
    SimpleMesh m;
    std::istringstream in(text);
    std::string line;
    std::vector<std::array<double, 2>> vts;
    while (std::getline(in, line)) {
        std::istringstream l(line);
        std::string tag;
        l >> tag;
        if (tag == "v") {
            std::array<double, 3> v{};
            l >> v[0] >> v[1] >> v[2];
            m.vertices.push_back(v);
        } else if (tag == "vt") {
            std::array<double, 2> t{};
            l >> t[0] >> t[1];
            vts.push_back(t);
        } else if (tag == "vn") {
            std::array<double, 3> n{};
            l >> n[0] >> n[1] >> n[2];
            m.normals.push_back(n);
        } else if (tag == "f") {
            std::array<std::uint32_t, 3> f{};
            std::string corner;
            int k = 0;
            while (l >> corner) {
                if (k >= 3) throw std::runtime_error("OBJ face with more than 3 corners");
                f[static_cast<std::size_t>(k++)] =
                    static_cast<std::uint32_t>(std::stoul(corner.substr(0, corner.find('/')))) - 1;
            }
            if (k != 3) throw std::runtime_error("OBJ face with fewer than 3 corners");
            m.triangles.push_back(f);
        }
    }
    m.uvs = vts;
    return m;
}

template <class T>
T read_le(const std::vector<std::uint8_t>& b, std::size_t& at) {
    if (at + sizeof(T) > b.size()) throw std::runtime_error("binary mesh truncated");
    T v;
    std::memcpy(&v, b.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
}

/// Binary little-endian PLY with float vertex properties (any of x y z nx ny nz s t) and a
/// "list uchar uint" face property.
inline SimpleMesh read_ply_binary(const std::vector<std::uint8_t>& b) {
    const std::string all(b.begin(), b.end());
    const std::size_t end = all.find("end_header\n");
    if (all.rfind("ply\n", 0) != 0 || end == std::string::npos) throw std::runtime_error("not PLY");
    std::istringstream header(all.substr(0, end));
    std::string line;
    std::size_t vertices = 0;
    std::size_t faces = 0;
    std::vector<std::string> props;
    std::string element;
    while (std::getline(header, line)) {
        std::istringstream l(line);
        std::string w;
        l >> w;
        if (w == "format" && line != "format binary_little_endian 1.0") {
            throw std::runtime_error("PLY is not binary little-endian");
        }
        if (w == "element") {
            std::size_t n = 0;
            l >> element >> n;
            (element == "vertex" ? vertices : faces) = n;
        } else if (w == "property" && element == "vertex") {
            std::string type;
            std::string name;
            l >> type >> name;
            if (type != "float") throw std::runtime_error("PLY vertex property not float");
            props.push_back(name);
        }
    }
    std::size_t at = end + std::string("end_header\n").size();
    SimpleMesh m;
    for (std::size_t i = 0; i < vertices; ++i) {
        std::map<std::string, double> v;
        for (const std::string& p : props)
            v[p] = read_le<float>(b, at);
        m.vertices.push_back({v["x"], v["y"], v["z"]});
        if (v.count("nx")) m.normals.push_back({v["nx"], v["ny"], v["nz"]});
        if (v.count("s")) m.uvs.push_back({v["s"], v["t"]});
    }
    for (std::size_t i = 0; i < faces; ++i) {
        if (read_le<std::uint8_t>(b, at) != 3) throw std::runtime_error("PLY face not a triangle");
        std::array<std::uint32_t, 3> f{};
        for (auto& c : f)
            c = read_le<std::uint32_t>(b, at);
        m.triangles.push_back(f);
    }
    if (at != b.size()) throw std::runtime_error("PLY has trailing bytes");
    return m;
}

/// Binary STL; vertices are welded by exact coordinates, so the result is indexed.
inline SimpleMesh read_stl_binary(const std::vector<std::uint8_t>& b,
                                  std::vector<std::array<double, 3>>* facet_normals = nullptr) {
    std::size_t at = 80;
    const auto n = read_le<std::uint32_t>(b, at);
    if (b.size() != 84 + 50ull * n) throw std::runtime_error("STL size does not match its count");
    SimpleMesh m;
    std::map<std::array<float, 3>, std::uint32_t> index;
    for (std::uint32_t t = 0; t < n; ++t) {
        std::array<double, 3> normal{};
        for (auto& c : normal)
            c = read_le<float>(b, at);
        if (facet_normals) facet_normals->push_back(normal);
        std::array<std::uint32_t, 3> f{};
        for (auto& corner : f) {
            std::array<float, 3> p{};
            for (auto& c : p)
                c = read_le<float>(b, at);
            const auto [it, fresh] =
                index.emplace(p, static_cast<std::uint32_t>(m.vertices.size()));
            if (fresh) m.vertices.push_back({p[0], p[1], p[2]});
            corner = it->second;
        }
        m.triangles.push_back(f);
        (void)read_le<std::uint16_t>(b, at);
    }
    return m;
}

/// The mesh with vertices welded by exact position (indices remapped).
inline SimpleMesh welded(const SimpleMesh& m) {
    SimpleMesh out;
    std::map<std::array<double, 3>, std::uint32_t> index;
    std::vector<std::uint32_t> remap(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        const auto [it, fresh] =
            index.emplace(m.vertices[i], static_cast<std::uint32_t>(out.vertices.size()));
        if (fresh) out.vertices.push_back(m.vertices[i]);
        remap[i] = it->second;
    }
    for (const auto& t : m.triangles)
        out.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
    return out;
}

inline std::array<double, 3> face_cross(const SimpleMesh& m,
                                        const std::array<std::uint32_t, 3>& t) {
    const auto& a = m.vertices[t[0]];
    const auto& b = m.vertices[t[1]];
    const auto& c = m.vertices[t[2]];
    const std::array<double, 3> u = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const std::array<double, 3> v = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

struct EdgeCount {
    std::size_t edges = 0;         ///< undirected
    std::size_t boundary = 0;      ///< used by one triangle
    std::size_t non_manifold = 0;  ///< used by three or more
    std::size_t inconsistent = 0;  ///< a directed edge used twice (winding flips)
};

/// Counts undirected edges by how many triangles use them, on a welded mesh.
inline EdgeCount count_edges(const SimpleMesh& m) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const auto& t : m.triangles) {
        for (int k = 0; k < 3; ++k)
            ++directed[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
    }
    EdgeCount c;
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    for (const auto& [e, n] : directed) {
        if (n > 1) ++c.inconsistent;
        const auto key = std::minmax(e.first, e.second);
        if (!seen.insert(key).second) continue;
        ++c.edges;
        const auto twin = directed.find({e.second, e.first});
        const int uses = n + (twin == directed.end() ? 0 : twin->second);
        if (uses == 1) ++c.boundary;
        if (uses > 2) ++c.non_manifold;
    }
    return c;
}

/// Closed 2-manifold: every edge shared by exactly two triangles, in opposite directions, and
/// every vertex's triangles form one fan (a single cycle around it).
inline std::vector<std::string> closed_manifold_problems(const SimpleMesh& m) {
    std::vector<std::string> problems;
    const EdgeCount c = count_edges(m);
    if (c.boundary) problems.push_back(std::to_string(c.boundary) + " boundary edges");
    if (c.non_manifold) problems.push_back(std::to_string(c.non_manifold) + " non-manifold edges");
    if (c.inconsistent) problems.push_back(std::to_string(c.inconsistent) + " flipped edges");
    // Vertex links: around vertex v, the edges (b, c) of its triangles (v, b, c) chain into
    // one cycle.
    std::vector<std::map<std::uint32_t, std::uint32_t>> link(m.vertices.size());
    for (const auto& t : m.triangles) {
        for (int k = 0; k < 3; ++k) {
            link[t[static_cast<std::size_t>(k)]][t[static_cast<std::size_t>((k + 1) % 3)]] =
                t[static_cast<std::size_t>((k + 2) % 3)];
        }
    }
    std::size_t bad = 0;
    for (const auto& l : link) {
        if (l.empty()) continue;
        std::uint32_t start = l.begin()->first;
        std::uint32_t at = start;
        std::size_t steps = 0;
        do {
            const auto it = l.find(at);
            if (it == l.end()) break;
            at = it->second;
            ++steps;
        } while (at != start && steps <= l.size());
        if (at != start || steps != l.size()) ++bad;
    }
    if (bad) problems.push_back(std::to_string(bad) + " vertices whose triangles are not one fan");
    return problems;
}

/// Signed volume enclosed by a closed, outward-wound mesh (divergence theorem).
inline double enclosed_volume(const SimpleMesh& m) {
    long double v = 0.0L;
    for (const auto& t : m.triangles) {
        const auto& a = m.vertices[t[0]];
        const auto& b = m.vertices[t[1]];
        const auto& c = m.vertices[t[2]];
        v += static_cast<long double>(a[0]) * (b[1] * c[2] - b[2] * c[1]) -
             static_cast<long double>(a[1]) * (b[0] * c[2] - b[2] * c[0]) +
             static_cast<long double>(a[2]) * (b[0] * c[1] - b[1] * c[0]);
    }
    return static_cast<double>(v / 6.0L);
}

struct Bounds {
    std::array<double, 3> min{1e300, 1e300, 1e300};
    std::array<double, 3> max{-1e300, -1e300, -1e300};
};

inline Bounds bounds_of(const SimpleMesh& m) {
    Bounds b;
    for (const auto& v : m.vertices) {
        for (std::size_t k = 0; k < 3; ++k) {
            b.min[k] = std::min(b.min[k], v[k]);
            b.max[k] = std::max(b.max[k], v[k]);
        }
    }
    return b;
}

}  // namespace sandtin::test
