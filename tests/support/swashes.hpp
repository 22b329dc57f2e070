#pragma once
// Analytic shallow-water solutions from SWASHES (Delestre et al., "SWASHES: a compilation of
// shallow water analytic solutions for hydraulic and environmental studies", 2013), the
// oracles of the water scheme's tests and of `sandtin bench water`. Units: metres, seconds.

#include <cmath>
#include <numbers>

#include "geom/vec2.hpp"

namespace sandtin::swashes {

/// Ritter's dam break on a dry bed (SWASHES 4.1.2): depth at x, t seconds after a dam at x0
/// holding `upstream` metres gave way. t > 0.
inline double ritter(double x, double x0, double upstream, double t, double g = 9.81) {
    const double c0 = std::sqrt(g * upstream);
    if (x <= x0 - c0 * t) return upstream;
    if (x >= x0 + 2.0 * c0 * t) return 0.0;
    const double c = (2.0 * c0 - (x - x0) / t) / 3.0;
    return c * c / g;
}

/// Stoker's dam break on a wet bed (SWASHES 4.1.1): `downstream` > 0 metres beyond the dam.
/// c_m solves -8 g h_r c² (c_l - c)² + (c² - g h_r)² (c² + g h_r) = 0 between the two
/// celerities, found by bisection.
inline double stoker(double x, double x0, double upstream, double downstream, double t,
                     double g = 9.81) {
    const double c_l = std::sqrt(g * upstream), c_r = std::sqrt(g * downstream);
    const double g_hr = g * downstream;
    const auto f = [&](double c) {
        return -8.0 * g_hr * c * c * (c_l - c) * (c_l - c) +
               (c * c - g_hr) * (c * c - g_hr) * (c * c + g_hr);
    };
    double lo = c_r, hi = c_l;
    const bool lo_negative = f(lo) < 0.0;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        if ((f(mid) < 0.0) == lo_negative) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    const double c_m = 0.5 * (lo + hi);
    const double x_a = x0 - c_l * t;
    const double x_b = x0 + (2.0 * c_l - 3.0 * c_m) * t;
    const double x_c = x0 + 2.0 * c_m * c_m * (c_l - c_m) / (c_m * c_m - g_hr) * t;
    if (x <= x_a) return upstream;
    if (x <= x_b) {
        const double c = (2.0 * c_l - (x - x0) / t) / 3.0;
        return c * c / g;
    }
    if (x <= x_c) return c_m * c_m / g;
    return downstream;
}

/// Thacker's planar surface in a paraboloid (SWASHES 4.2.2), centred on the origin: the bed
/// -h0 (1 - r²/a²), a tilted plane of water sloshing round it with period 2 pi / omega.
struct ThackerPlanar {
    double a = 1.0, h0 = 0.1, eta = 0.5, g = 9.81;

    double omega() const { return std::sqrt(2.0 * g * h0) / a; }
    double period() const { return 2.0 * std::numbers::pi / omega(); }
    double bed(Vec2 p) const { return -h0 * (1.0 - (p.x * p.x + p.y * p.y) / (a * a)); }
    double depth(Vec2 p, double t) const {
        const double w = omega();
        const double h =
            eta * h0 / (a * a) * (2.0 * p.x * std::cos(w * t) + 2.0 * p.y * std::sin(w * t) - eta) -
            bed(p);
        return h > 0.0 ? h : 0.0;
    }
    Vec2 velocity(double t) const {
        const double w = omega();
        return {-eta * w * std::sin(w * t), eta * w * std::cos(w * t)};
    }
};

}  // namespace sandtin::swashes
