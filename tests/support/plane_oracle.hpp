#pragma once
// An independent least-squares plane fit for tests: a singular value decomposition of the
// unscaled design matrix [x - x0, y - y0, 1], with no normal equations and no pivoting choice
// in common with geom/plane_fit.

#include <Eigen/Dense>

#include <span>

#include "geom/vec2.hpp"

namespace sandtin::test {

/// Largest vertical distance (m) of the points from their least-squares plane.
inline double plane_residual_by_svd(std::span<const Vec2> xy, std::span<const double> z) {
    const auto n = static_cast<Eigen::Index>(xy.size());
    Eigen::MatrixXd a(n, 3);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Vec2 p = xy[static_cast<std::size_t>(i)] - xy.front();
        a.row(i) << p.x, p.y, 1.0;
        b(i) = z[static_cast<std::size_t>(i)];
    }
    const Eigen::VectorXd coef = a.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(b);
    return ((a * coef) - b).cwiseAbs().maxCoeff();
}

}  // namespace sandtin::test
