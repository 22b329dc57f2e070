#include "physics/repose_projection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace sandtin {

namespace {

constexpr std::uint32_t kNotFree = std::numeric_limits<std::uint32_t>::max();
constexpr double kOverRelaxation = 1.6;  // Boyd et al. §3.4.3: 1.5-1.8 speeds ADMM up
constexpr int kRhoCheckInterval = 10;    // iterations between residual balancing
constexpr double kRhoImbalance = 100.0;  // residual ratio that changes rho
constexpr double kRhoFactor = 2.0;
constexpr int kMaxFactorisations = 60;  // rho settles long before this

/// One constrained face: its free corners' gradient coefficients (grad of the barycentric
/// coordinate, 1/m), the held corners' constant gradient, its area (weight, m²) and bound.
struct FaceOperator {
    std::array<std::uint32_t, 3> free{kNotFree, kNotFree, kNotFree};  // free index per corner
    std::array<Vec2, 3> grad;
    Vec2 held_gradient;  // the held corners' part of grad h
    double weight = 0.0;
    double bound = 0.0;  // tan(alpha), or the rock's own steepness where that is steeper
    Vec2 gradient(const Eigen::VectorXd& h) const {
        Vec2 g = held_gradient;
        for (int k = 0; k < 3; ++k) {
            if (free[k] != kNotFree) g += grad[k] * h[free[k]];
        }
        return g;
    }
};

void check(const ReposeProblem& p) {
    const std::size_t n = p.position.size();
    auto fail = [](const std::string& what) {
        throw std::invalid_argument("repose projection: " + what);
    };
    if (p.area.size() != n || p.height.size() != n)
        fail("position, area and height must have one entry per vertex");
    if (!p.bedrock.empty() && p.bedrock.size() != n) fail("bedrock must be empty or per vertex");
    if (!p.held.empty() && p.held.size() != n) fail("held must be empty or per vertex");
    if (p.face_tan_alpha.size() != p.faces.size()) fail("face_tan_alpha must be per face");
    for (const auto& f : p.faces) {
        for (std::uint32_t v : f) {
            if (v >= n) fail("face corner " + std::to_string(v) + " is not a vertex");
        }
    }
    for (double t : p.face_tan_alpha) {
        if (!(t > 0.0) || !std::isfinite(t)) fail("tan(alpha) must be positive and finite");
    }
    for (std::size_t v = 0; v < n; ++v) {
        if (!std::isfinite(p.height[v]) || !std::isfinite(p.position[v].x) ||
            !std::isfinite(p.position[v].y) || !(p.area[v] >= 0.0))
            fail("vertex " + std::to_string(v) +
                 " has a non-finite position or height, or a negative area");
        if (!p.bedrock.empty() && p.height[v] < p.bedrock[v])
            fail("vertex " + std::to_string(v) + " lies below its bedrock");
    }
}

/// The problem in the free vertices' numbering: what the ADMM loop works on.
struct Discrete {
    std::vector<std::uint32_t> free_of;    // per vertex: free index or kNotFree
    std::vector<std::uint32_t> vertex_of;  // per free index
    std::vector<FaceOperator> faces;
    Eigen::VectorXd area, h0, bedrock;              // per free vertex; bedrock -inf where none
    std::vector<std::uint8_t> on_bedrock;           // per free vertex: has a finite bedrock
    std::vector<Eigen::Triplet<double>> stiffness;  // K over the free vertices
    std::size_t degenerate = 0;
};

/// Phase 1: which vertices move, and each face's gradient operator and bound.
Discrete discretise(const ReposeProblem& p) {
    const std::size_t n = p.position.size();
    Discrete d;
    d.free_of.assign(n, kNotFree);
    std::vector<std::uint8_t> in_face(n, 0);
    std::vector<double> twice_area(p.faces.size(), 0.0);
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
        const auto& c = p.faces[f];
        const Vec2 a = p.position[c[0]], b = p.position[c[1]], e = p.position[c[2]];
        const double scale = std::max({dot(b - a, b - a), dot(e - b, e - b), dot(a - e, a - e)});
        twice_area[f] = cross(b - a, e - a);
        // A face of (near) zero area has no gradient to bound; the local rule judges it.
        if (!(std::abs(twice_area[f]) > 1e-12 * scale)) {
            twice_area[f] = 0.0;
            ++d.degenerate;
            continue;
        }
        for (std::uint32_t v : c)
            in_face[v] = 1;
    }
    for (std::size_t v = 0; v < n; ++v) {
        if (in_face[v] && (p.held.empty() || !p.held[v]) && p.area[v] > 0.0) {
            d.free_of[v] = static_cast<std::uint32_t>(d.vertex_of.size());
            d.vertex_of.push_back(static_cast<std::uint32_t>(v));
        }
    }
    const std::size_t m = d.vertex_of.size();
    d.area.resize(static_cast<Eigen::Index>(m));
    d.h0.resize(static_cast<Eigen::Index>(m));
    d.bedrock.resize(static_cast<Eigen::Index>(m));
    d.on_bedrock.assign(m, 0);
    for (std::size_t i = 0; i < m; ++i) {
        const std::uint32_t v = d.vertex_of[i];
        const auto k = static_cast<Eigen::Index>(i);
        d.area[k] = p.area[v];
        d.h0[k] = p.height[v];
        const bool rock = !p.bedrock.empty() && std::isfinite(p.bedrock[v]);
        d.bedrock[k] = rock ? p.bedrock[v] : -std::numeric_limits<double>::infinity();
        d.on_bedrock[i] = rock ? 1 : 0;
    }
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
        if (twice_area[f] == 0.0) continue;
        const auto& c = p.faces[f];
        FaceOperator op;
        const Vec2 pos[3] = {p.position[c[0]], p.position[c[1]], p.position[c[2]]};
        Vec2 rock_gradient;
        bool any_free = false;
        for (int k = 0; k < 3; ++k) {
            // grad of the barycentric coordinate of corner k: the opposite edge turned a
            // quarter counter-clockwise, over twice the signed area.
            const Vec2 edge = pos[(k + 2) % 3] - pos[(k + 1) % 3];
            op.grad[k] = Vec2{-edge.y, edge.x} / twice_area[f];
            op.free[k] = d.free_of[c[k]];
            any_free = any_free || op.free[k] != kNotFree;
            if (op.free[k] == kNotFree) op.held_gradient += op.grad[k] * p.height[c[k]];
            if (!p.bedrock.empty()) rock_gradient += op.grad[k] * p.bedrock[c[k]];
        }
        if (!any_free) continue;
        op.weight = 0.5 * std::abs(twice_area[f]);
        // A face whose rock is steeper than repose may stand as steep as the rock: the bound
        // must admit the bare rock, or there is no feasible surface at all.
        const double rock_steepness = p.bedrock.empty() || !std::isfinite(length(rock_gradient))
                                          ? 0.0
                                          : length(rock_gradient);
        op.bound = std::max(p.face_tan_alpha[f], rock_steepness * (1.0 + 1e-9));
        for (int a = 0; a < 3; ++a) {
            if (op.free[a] == kNotFree) continue;
            for (int b = 0; b < 3; ++b) {
                if (op.free[b] == kNotFree) continue;
                d.stiffness.emplace_back(op.free[a], op.free[b],
                                         op.weight * dot(op.grad[a], op.grad[b]));
            }
        }
        d.faces.push_back(op);
    }
    return d;
}

Vec2 project_onto_disc(Vec2 g, double radius) {
    const double len = length(g);
    return len > radius ? g * (radius / len) : g;
}

/// Phase 2: ADMM. The height step's matrix changes only with rho.
class Admm {
  public:
    Admm(const Discrete& d, double rho_per_area) : d_(d) {
        const auto m = static_cast<Eigen::Index>(d.vertex_of.size());
        stiffness_.resize(m, m);
        stiffness_.setFromTriplets(d.stiffness.begin(), d.stiffness.end());
        ones_area_ = d.area;
        z_.resize(d.faces.size());
        u_.assign(d.faces.size(), Vec2{});
        h_ = d.h0;
        y_ = h_;
        w_ = Eigen::VectorXd::Zero(m);
        for (std::size_t f = 0; f < d.faces.size(); ++f)
            z_[f] = project_onto_disc(d.faces[f].gradient(h_), d.faces[f].bound);
        // rho has the multipliers' unit, m²: their scale is that of the settled region (a
        // pile's radius squared). 0.05 of the region's area took the fewest iterations on
        // cones poured on 2 500 to 40 000 vertices (845-1 429 to 1e-4; 1 359-2 393 starting
        // from the geometric mean of the region's and a vertex's area, which scales with the
        // spacing). Residual balancing only rescues a badly scaled start: at a 10x imbalance
        // it raised rho where the iterations wanted it lower.
        rho_ = std::max(rho_per_area * d.area.sum(), 1e-300);
        volume_ = d.area.dot(d.h0);
    }

    void run(const ReposeProjectionOptions& options, ReposeProjection& out) {
        factorise();
        ++out.factorisations;
        ProgressEstimate progress;
        for (int it = 0; it < options.max_iterations; ++it) {
            height_step();
            const Residuals r = constraint_steps();
            out.iterations = it + 1;
            if (r.converged(options.tolerance) && r.steepest <= 1.0 + options.steepness_tolerance) {
                out.converged = true;
                break;
            }
            if (options.on_progress && out.iterations % options.kProgressInterval == 0)
                options.on_progress(
                    progress.update(r.distance(options), out.iterations, options.max_iterations));
            if ((it + 1) % kRhoCheckInterval == 0 && out.factorisations < kMaxFactorisations &&
                rebalance(r)) {
                factorise();
                ++out.factorisations;
            }
        }
        if (options.on_progress) options.on_progress(1.0);
    }
    const Eigen::VectorXd& height() const { return h_; }

  private:
    struct Residuals {
        double primal2 = 0.0, dual2 = 0.0;  // squared norms
        double gradient2 = 0.0, z2 = 0.0, multiplier2 = 0.0;
        double rho = 0.0;
        double steepest = 0.0;  // max |grad h| / bound over the faces
        double primal() const { return std::sqrt(primal2); }
        double dual() const { return rho * std::sqrt(dual2); }
        bool converged(double tolerance) const {
            const double absolute = 1e-14;
            return primal() <= absolute + tolerance * std::sqrt(std::max(gradient2, z2)) &&
                   dual() <= absolute + tolerance * rho * std::sqrt(multiplier2);
        }
        /// How far from converged, as a multiple of the stopping criteria (<= 1: there).
        double distance(const ReposeProjectionOptions& options) const {
            const double tiny = 1e-300;
            const double primal_scale =
                1e-14 + options.tolerance * std::sqrt(std::max(gradient2, z2));
            const double dual_scale = 1e-14 + options.tolerance * rho * std::sqrt(multiplier2);
            const double steep = (steepest - 1.0) / std::max(options.steepness_tolerance, tiny);
            return std::max({primal() / primal_scale, dual() / dual_scale, steep, 1.0});
        }
    };

    /// The fraction done for on_progress: the log of the distance to convergence, against
    /// the first one heard, or the share of the iteration budget; never decreasing.
    struct ProgressEstimate {
        double first = 0.0;
        double shown = 0.0;
        double update(double distance, int iterations, int max_iterations) {
            if (first == 0.0) first = std::max(distance, 1.0 + 1e-9);
            const double by_distance = std::log(first / std::max(distance, 1.0)) / std::log(first);
            const double by_budget =
                static_cast<double>(iterations) / static_cast<double>(max_iterations);
            // Short of 1 until the projection has ended: 1 is the end's own report.
            shown = std::max(shown, std::clamp(std::max(by_distance, by_budget), 0.0, 0.99));
            return shown;
        }
    };

    void factorise() {
        Eigen::SparseMatrix<double> m = rho_ * stiffness_;
        for (Eigen::Index i = 0; i < m.rows(); ++i) {
            const double rock = d_.on_bedrock[static_cast<std::size_t>(i)] ? rho_ : 0.0;
            m.coeffRef(i, i) += d_.area[i] * (1.0 + rock);
        }
        if (!analysed_) {
            solver_.analyzePattern(m);
            analysed_ = true;
        }
        solver_.factorize(m);
        if (solver_.info() != Eigen::Success)
            throw std::runtime_error("repose projection: the height system did not factor");
        // The volume direction: M e = A 1, so h1 + mu e holds the volume for the right mu.
        volume_direction_ = solver_.solve(ones_area_);
        volume_weight_ = d_.area.dot(volume_direction_);
    }

    void height_step() {
        Eigen::VectorXd rhs = d_.area.cwiseProduct(d_.h0);
        for (std::size_t f = 0; f < d_.faces.size(); ++f) {
            const FaceOperator& op = d_.faces[f];
            const Vec2 target = (z_[f] - u_[f] - op.held_gradient) * (rho_ * op.weight);
            for (int k = 0; k < 3; ++k) {
                if (op.free[k] != kNotFree) rhs[op.free[k]] += dot(op.grad[k], target);
            }
        }
        for (Eigen::Index i = 0; i < rhs.size(); ++i) {
            if (d_.on_bedrock[static_cast<std::size_t>(i)])
                rhs[i] += rho_ * d_.area[i] * (y_[i] - w_[i]);
        }
        h_ = solver_.solve(rhs);
        h_ += ((volume_ - d_.area.dot(h_)) / volume_weight_) * volume_direction_;
    }

    Residuals constraint_steps() {
        Residuals r;
        r.rho = rho_;
        for (std::size_t f = 0; f < d_.faces.size(); ++f) {
            const FaceOperator& op = d_.faces[f];
            const Vec2 g = op.gradient(h_);
            const Vec2 relaxed = g * kOverRelaxation + z_[f] * (1.0 - kOverRelaxation);
            const Vec2 v = relaxed + u_[f];
            const Vec2 z = project_onto_disc(v, op.bound);
            u_[f] = v - z;
            r.primal2 += op.weight * dot(g - z, g - z);
            r.steepest = std::max(r.steepest, length(g) / op.bound);
            r.dual2 += op.weight * dot(z - z_[f], z - z_[f]);
            r.gradient2 += op.weight * dot(g, g);
            r.z2 += op.weight * dot(z, z);
            r.multiplier2 += op.weight * dot(u_[f], u_[f]);
            z_[f] = z;
        }
        for (Eigen::Index i = 0; i < h_.size(); ++i) {
            if (!d_.on_bedrock[static_cast<std::size_t>(i)]) continue;
            const double a = d_.area[i];
            const double relaxed = kOverRelaxation * h_[i] + (1.0 - kOverRelaxation) * y_[i];
            const double q = relaxed + w_[i];
            const double y = std::max(d_.bedrock[i], q);
            w_[i] = q - y;
            r.primal2 += a * (h_[i] - y) * (h_[i] - y);
            r.dual2 += a * (y - y_[i]) * (y - y_[i]);
            r.multiplier2 += a * w_[i] * w_[i];
            y_[i] = y;
        }
        return r;
    }

    /// Boyd et al. §3.4.1: keep the primal and dual residuals within a factor of each other.
    /// The scaled multipliers follow rho so that the unscaled ones are unchanged.
    bool rebalance(const Residuals& r) {
        double factor = 1.0;
        if (r.primal() > kRhoImbalance * r.dual()) factor = kRhoFactor;
        if (r.dual() > kRhoImbalance * r.primal()) factor = 1.0 / kRhoFactor;
        if (factor == 1.0) return false;
        rho_ *= factor;
        for (Vec2& u : u_)
            u = u / factor;
        w_ /= factor;
        return true;
    }

    const Discrete& d_;
    Eigen::SparseMatrix<double> stiffness_;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
    bool analysed_ = false;
    Eigen::VectorXd ones_area_, volume_direction_, h_, y_, w_;
    double volume_weight_ = 0.0, volume_ = 0.0, rho_ = 1.0;
    std::vector<Vec2> z_, u_;
};

/// Phase 3: ADMM leaves heights within its tolerance of the bedrock, some a hair below. Those
/// are raised onto it, and the volume that adds is taken evenly from the vertices with sand
/// to spare (water-filling: a vertex that would go below its rock stops on it and the rest
/// share its part), so the volume stays exact and no sand lies under the rock.
void settle_onto_bedrock(const Discrete& d, Eigen::VectorXd& h) {
    double added = 0.0;
    for (Eigen::Index i = 0; i < h.size(); ++i) {
        if (h[i] < d.bedrock[i]) {
            added += d.area[i] * (d.bedrock[i] - h[i]);
            h[i] = d.bedrock[i];
        }
    }
    for (int pass = 0; pass < 64 && added > 0.0; ++pass) {
        double spare_area = 0.0;
        for (Eigen::Index i = 0; i < h.size(); ++i) {
            if (h[i] > d.bedrock[i]) spare_area += d.area[i];
        }
        if (!(spare_area > 0.0)) return;  // all sand on rock: nothing left to take from
        const double drop = added / spare_area;
        added = 0.0;
        for (Eigen::Index i = 0; i < h.size(); ++i) {
            if (!(h[i] > d.bedrock[i])) continue;
            const double spare = h[i] - d.bedrock[i];
            const double taken = std::min(drop, spare);
            h[i] = taken == spare ? d.bedrock[i] : h[i] - taken;  // exactly on the rock
            added += d.area[i] * (drop - taken);
        }
    }
}

}  // namespace

ReposeProjection project_onto_repose(const ReposeProblem& problem,
                                     const ReposeProjectionOptions& options) {
    if (!(options.tolerance > 0.0) || !(options.steepness_tolerance >= 0.0) ||
        options.max_iterations < 1 || !(options.rho_per_area > 0.0) ||
        !std::isfinite(options.rho_per_area))
        throw std::invalid_argument(
            "repose projection: tolerance must be > 0, steepness_tolerance >= 0, "
            "max_iterations >= 1 and rho_per_area > 0");
    check(problem);
    ReposeProjection out;
    out.height.assign(problem.height.begin(), problem.height.end());
    const Discrete d = discretise(problem);
    out.free_vertices = d.vertex_of.size();
    out.degenerate_faces = d.degenerate;
    if (d.vertex_of.empty() || d.faces.empty()) {
        out.converged = true;
        if (options.on_progress) options.on_progress(1.0);
        return out;
    }
    Admm admm(d, options.rho_per_area);
    admm.run(options, out);
    Eigen::VectorXd h = admm.height();
    settle_onto_bedrock(d, h);
    for (std::size_t i = 0; i < d.vertex_of.size(); ++i) {
        const double moved = h[static_cast<Eigen::Index>(i)];
        out.volume_change +=
            d.area[static_cast<Eigen::Index>(i)] * (moved - d.h0[static_cast<Eigen::Index>(i)]);
        out.height[d.vertex_of[i]] = moved;
    }
    for (const FaceOperator& op : d.faces)
        out.steepest_ratio = std::max(out.steepest_ratio, length(op.gradient(h)) / op.bound);
    return out;
}

}  // namespace sandtin
