#pragma once
// What the export tests share: a test terrain (hills, with materials and moisture that vary)
// and a fixture that exports it into a scratch folder of its own per test and reads the
// file's bytes back.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/export_terrain.hpp"
#include "support/scratch_folder.hpp"
#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::export_test {

namespace fs = std::filesystem;

/// A smooth hilly height field (m) over the 12 x 8 m test terrain.
inline double hills(Vec2 p) {
    return 2.0 + std::sin(p.x * 0.7) * std::cos(p.y * 0.5) + 0.1 * p.x;
}

/// 400 random points on the hills, with materials and moisture that vary.
inline Tin test_tin() {
    Tin tin = Tin::random_points(Rect{{0.0, 0.0}, {12.0, 8.0}}, 400, 5, hills);
    // Materials and moisture vary, so the albedo has something to show.
    for (VertexId v : test::live_ids(tin)) {
        if (tin.position(v).x > 6.0) tin.set_material(v, 1);
        if (tin.position(v).y > 4.0) tin.set_moisture(v, 0.5f);
    }
    return tin;
}

class Export : public test::ScratchFolderTest {
  protected:
    Export() : ScratchFolderTest("export") {}

    std::vector<std::uint8_t> run(const Tin& tin, const std::string& name, ExportOptions o = {},
                                  const std::string& map = "") {
        const fs::path p = dir_ / name;
        report_ = export_terrain(tin, p, export_format_for(p, map), o);
        return read_file(p);
    }
    static std::string text(const std::vector<std::uint8_t>& b) { return {b.begin(), b.end()}; }

    ExportReport report_;
};

}  // namespace sandtin::export_test
