#include "geom/plane_fit.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandtin {

double plane_fit_residual(std::span<const Vec2> xy, std::span<const double> z, Vec2 origin) {
    constexpr double kNoPlane = std::numeric_limits<double>::infinity();
    if (xy.size() != z.size() || xy.size() < 3) return kNoPlane;
    double scale2 = 0.0;
    for (Vec2 p : xy)
        scale2 = std::max(scale2, length_squared(p - origin));
    if (!(scale2 > 0.0) || !std::isfinite(scale2)) return kNoPlane;
    const double inv_scale = 1.0 / std::sqrt(scale2);
    // The 3x3 normal equations (LDLT). Points that span the plane well (a star around its
    // vertex, a patch) keep them well conditioned; a set squeezed nearly onto a line (pivot
    // ratio below 1e-8, where the squared condition number would cost digits) goes to a
    // column-pivoting QR of the design matrix, which also tells a true line (rank < 3).
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < xy.size(); ++i) {
        const Vec2 d = (xy[i] - origin) * inv_scale;
        const Eigen::Vector3d row(d.x, d.y, 1.0);
        m.selfadjointView<Eigen::Lower>().rankUpdate(row);
        rhs += row * z[i];
    }
    if (!rhs.allFinite()) return kNoPlane;
    Eigen::Vector3d coef;
    const Eigen::LDLT<Eigen::Matrix3d, Eigen::Lower> ldlt(m);
    const Eigen::Vector3d pivots = ldlt.vectorD().cwiseAbs();
    if (ldlt.info() == Eigen::Success && pivots.minCoeff() > 1e-8 * pivots.maxCoeff()) {
        coef = ldlt.solve(rhs);
    } else {
        const auto n = static_cast<Eigen::Index>(xy.size());
        Eigen::MatrixX3d a(n, 3);
        Eigen::VectorXd b(n);
        for (Eigen::Index i = 0; i < n; ++i) {
            const Vec2 d = (xy[static_cast<std::size_t>(i)] - origin) * inv_scale;
            a.row(i) << d.x, d.y, 1.0;
            b(i) = z[static_cast<std::size_t>(i)];
        }
        const Eigen::ColPivHouseholderQR<Eigen::MatrixX3d> qr(a);
        if (qr.rank() < 3) return kNoPlane;
        coef = qr.solve(b);
    }
    double worst = 0.0;
    for (std::size_t i = 0; i < xy.size(); ++i) {
        const Vec2 d = (xy[i] - origin) * inv_scale;
        worst = std::max(worst, std::abs(coef(0) * d.x + coef(1) * d.y + coef(2) - z[i]));
    }
    return worst;
}

}  // namespace sandtin
