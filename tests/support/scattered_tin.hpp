#pragma once
// A random-point TIN with points about `spacing` apart: a lattice jittered by up to 0.45 of a
// spacing each way, plus points along the border at that spacing. Tin::random_points lets two
// points crowd (a cell a hundredth of the mean area sets a finite-volume scheme's time step)
// and puts none on the border but the corners (a 10 m x 0.2 m strip's long sides would be
// single edges 10 m long).

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin::support {

inline Tin scattered_tin(Rect d, double spacing, unsigned seed,
                         const std::function<double(Vec2)>& height = {}) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.45, 0.45);
    const int nx = std::max(1, static_cast<int>(std::round(d.width() / spacing)));
    const int ny = std::max(1, static_cast<int>(std::round(d.height() / spacing)));
    const double sx = d.width() / nx, sy = d.height() / ny;
    std::vector<Vec2> points;
    std::vector<double> heights;
    for (int j = 0; j <= ny; ++j) {
        for (int i = 0; i <= nx; ++i) {
            Vec2 p{d.min.x + i * sx, d.min.y + j * sy};
            if (i != 0 && i != nx) p.x += jitter(rng) * sx;
            if (j != 0 && j != ny) p.y += jitter(rng) * sy;
            points.push_back(p);
            heights.push_back(height ? height(p) : 0.0);
        }
    }
    return Tin::from_points(d, points, heights);
}

}  // namespace sandtin::support
