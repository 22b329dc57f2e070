#pragma once
// The regular-grid baseline, with the same angle of repose, damping, rest tolerance, active set
// and kernel as the TIN, under either slope rule (TalusParameters::rule). It exists to compare
// run time against error with the TIN, in tests and benchmarks: two discretisations of one
// continuum model.
//  - SlopeRule::Edge: classic thermal erosion on a height grid (Musgrave, Kolb & Mace 1989;
//    Beneš & Forsbach), 8-connected cells of equal area.
//  - SlopeRule::Face: the cell centres triangulated with alternating diagonals (a 4-8 mesh:
//    centre (i, j) has 8 neighbours when i + j is even, else 4), each lumped area a third of
//    its triangles' (as the TIN's), so sum(area * height) is the piecewise-linear volume. The
//    alternation matters: with every diagonal one way the pile stretches along it (issue 39's
//    prototype found it does not converge).
// Heights are at the cell centres either way.

#include <array>
#include <cstdint>
#include <vector>

#include "geom/rect.hpp"
#include "physics/active_set.hpp"
#include "physics/adjacency_graph.hpp"
#include "physics/face_slopes.hpp"
#include "physics/repose_projection.hpp"
#include "physics/talus_solver.hpp"

namespace sandtin {

class GridErosion {
  public:
    /// A (cells_x x cells_y) grid of cells covering `domain`; heights are cell centres (m).
    /// Throws std::invalid_argument for fewer than 2 x 2 cells.
    GridErosion(Rect domain, int cells_x, int cells_y, double tan_alpha,
                TalusSettings settings = {});

    SlopeRule rule() const { return solver_.settings().parameters.rule; }

    int cells_x() const { return nx_; }
    int cells_y() const { return ny_; }
    double cell_size_x() const { return dx_; }
    double cell_size_y() const { return dy_; }
    Vec2 centre(int i, int j) const;
    double& height(int i, int j) { return height_[index(i, j)]; }
    double height(int i, int j) const { return height_[index(i, j)]; }
    std::vector<double>& heights() { return height_; }
    /// Volume above z = 0: sum of lumped area times height (m³).
    double volume() const;
    /// Lumped area of cell (i, j) (m²): the cell's under the edge rule, a third of its
    /// triangles' under the face rule.
    double area(int i, int j) const { return area_[index(i, j)]; }
    /// Height at p (m), clamped to the centres' rectangle: bilinear under the edge rule,
    /// linear on the 4-8 mesh's triangles under the face rule.
    double height_at(Vec2 p) const;

    /// Adds `volume` m³ to the cell containing p and activates it.
    void pour(Vec2 p, double volume);
    void activate_all();
    std::size_t active_count() const { return active_.size(); }
    /// Relaxes until rest or max_iterations; returns the iterations run.
    int run_to_rest(int max_iterations);
    /// Vertex updates performed so far (for throughput figures).
    std::size_t vertex_updates() const { return updates_; }
    /// The 4-8 mesh's triangles over the centres (under either rule), for judging the surface
    /// face by face (physics/face_slopes.hpp).
    std::vector<SlopeFace> faces() const;
    /// The same triangles as cell indices j * cells_x + i, counter-clockwise.
    std::vector<std::array<std::uint32_t, 3>> triangles() const;
    /// Projects the heights onto the repose set on the 4-8 mesh (physics/repose_projection.hpp),
    /// keeping sum(area * height), and activates every cell so that the relaxation finishes
    /// what the projection's tolerance left. Returns the projection's figures (heights moved
    /// into height()).
    ReposeProjection settle_by_projection(const ReposeProjectionOptions& options = {});

  private:
    std::size_t index(int i, int j) const {
        return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) +
               static_cast<std::size_t>(i);
    }
    /// Under the face rule: whether quad (i, j)'s diagonal runs from centre (i, j) to
    /// (i + 1, j + 1), else from (i + 1, j) to (i, j + 1). The one place the 4-8 mesh's
    /// alternation is decided (graph, faces and height_at follow it).
    static bool diagonal_from_origin(int i, int j) { return (i + j) % 2 == 0; }
    void build_moore_graph();
    void build_triangulated_graph();

    Rect domain_;
    int nx_, ny_;
    double dx_, dy_;
    std::vector<double> height_, area_, bedrock_, tan_;
    AdjacencyGraph graph_;
    ActiveSet active_;
    TalusSolver solver_;
    std::size_t updates_ = 0;
};

}  // namespace sandtin
