#include "formats/obj_mesh.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "util/atomic_file.hpp"

namespace sandtin {

namespace {

std::string_view next_token(std::string_view& line) {
    std::size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string_view::npos) {
        line = {};
        return {};
    }
    std::size_t end = line.find_first_of(" \t\r", start);
    if (end == std::string_view::npos) end = line.size();
    const std::string_view token = line.substr(start, end - start);
    line.remove_prefix(end);
    return token;
}

}  // namespace

TriangleMesh parse_obj(std::string_view text, const std::string& name) {
    TriangleMesh mesh;
    std::size_t line_number = 0;
    auto fail = [&](const std::string& what) {
        throw std::runtime_error(name + ":" + std::to_string(line_number) + ": " + what);
    };
    while (!text.empty()) {
        ++line_number;
        const std::size_t eol = text.find('\n');
        std::string_view line = text.substr(0, eol);
        text = eol == std::string_view::npos ? std::string_view{} : text.substr(eol + 1);
        const std::string_view keyword = next_token(line);
        if (keyword == "v") {
            std::array<double, 3> p{};
            for (double& c : p) {
                const std::string_view t = next_token(line);
                const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), c);
                if (t.empty() || ec != std::errc() || ptr != t.data() + t.size() ||
                    !std::isfinite(c)) {
                    fail("vertex needs three finite coordinates");
                }
            }
            mesh.vertices.push_back(p);
        } else if (keyword == "f") {
            std::vector<std::uint32_t> corners;
            for (std::string_view t = next_token(line); !t.empty(); t = next_token(line)) {
                const std::string_view index_text = t.substr(0, t.find('/'));
                long long index = 0;
                const auto [ptr, ec] = std::from_chars(
                    index_text.data(), index_text.data() + index_text.size(), index);
                if (index_text.empty() || ec != std::errc() ||
                    ptr != index_text.data() + index_text.size() || index == 0) {
                    fail("bad face index '" + std::string(t) + "'");
                }
                const long long n = static_cast<long long>(mesh.vertices.size());
                const long long resolved = index > 0 ? index - 1 : n + index;
                if (resolved < 0 || resolved >= n)
                    fail("face index " + std::to_string(index) + " is out of range");
                corners.push_back(static_cast<std::uint32_t>(resolved));
            }
            if (corners.size() < 3) fail("face has fewer than three corners");
            for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
                mesh.triangles.push_back({corners[0], corners[i], corners[i + 1]});
            }
        }
        // Other keywords (vt, vn, o, g, s, usemtl, mtllib, comments) carry nothing we need.
    }
    return mesh;
}

TriangleMesh read_obj(const std::filesystem::path& path) {
    const std::vector<std::uint8_t> bytes = read_file(path, 1ull << 31);
    return parse_obj(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                     path.string());
}

}  // namespace sandtin
