#pragma once
// Sand physics on the TIN: talus relaxation over the active vertices, per-vertex materials and
// moisture, bedrock, and refinement of long edges at the relocation radius r_S (so a pile
// poured onto two flat triangles grows its own detail). It follows every change to the TIN
// (tools, brushes, undo) through a Tin change subscription: whatever changed becomes active.

#include <memory>
#include <span>
#include <vector>

#include "physics/adjacency_graph.hpp"
#include "physics/material.hpp"
#include "physics/talus_solver.hpp"
#include "tin/tin.hpp"

namespace sandtin {

struct PhysicsStepReport {
    int iterations = 0;              ///< iterations actually run (fewer when the sand came to rest)
    std::size_t vertex_updates = 0;  ///< sum over iterations of the vertices processed
    std::size_t changed = 0;         ///< sum over iterations of the vertices whose height changed
    std::size_t refined = 0;         ///< vertices inserted to split long edges
    double volume_moved = 0.0;       ///< m³
    double ms = 0.0;
    bool at_rest = false;
    void accumulate(const PhysicsStepReport& o);
};

class SandPhysics {
  public:
    /// Subscribes to the TIN's changes; the TIN must outlive the physics.
    SandPhysics(Tin& tin, MaterialTable materials, TalusSettings settings = {});
    ~SandPhysics();
    SandPhysics(const SandPhysics&) = delete;
    SandPhysics& operator=(const SandPhysics&) = delete;

    TalusSettings& settings() { return solver_.settings(); }
    const MaterialTable& materials() const { return materials_; }
    void set_materials(MaterialTable materials);

    void activate(std::span<const VertexId> vertices);
    /// Every live vertex becomes active (e.g. after loading a terrain that is not at rest).
    void activate_all();
    std::size_t active_count() const { return active_.size(); }
    /// The vertices still being relaxed (ids).
    const ActiveSet& active() const { return active_; }
    bool at_rest() const { return active_.empty(); }

    /// Runs up to `iterations` relaxation iterations (stops early at rest). Vertices whose
    /// height changed are appended to `changed` when given (the caller queues them for
    /// simplification, seed 003 §4 step 2d).
    PhysicsStepReport step(int iterations = 1, std::vector<VertexId>* changed = nullptr);
    /// Iterates until nothing is active or `max_iterations` ran.
    PhysicsStepReport run_to_rest(int max_iterations, std::vector<VertexId>* changed = nullptr);

    /// Splits the edges around `vertices` until none is longer than the relocation radius
    /// (the same refinement the relaxation asks for when sand meets a long edge), so a pour at
    /// a single vertex of a coarse terrain starts from a star of radius r_S. Returns the
    /// vertices inserted; no-op without a relocation radius.
    std::size_t refine_around(std::span<const VertexId> vertices);

    const AdjacencyGraph& graph() const { return graph_; }
    /// tan(angle of repose) of each vertex, from its material and moisture.
    const std::vector<double>& talus_slopes() const { return tan_alpha_; }

  private:
    void sync();
    /// Writes the heights the relaxation changed since the last flush into the TIN (once per
    /// step, and before refinement reads them), and drops the journal entries that write
    /// makes: they echo values height_ already holds, and the solver has already activated
    /// those vertices and their neighbours.
    void flush(std::vector<VertexId>* changed_out);
    /// Refines around the given vertices until their edges are at most r_S (seed 000 §7.2,
    /// "prevention of long edges"): points of a hexagonal lattice of spacing 0.75 r_S inside
    /// their stars, or, where no lattice point fits, the midpoints of their long edges.
    std::size_t refine(std::vector<std::uint32_t>& around);

    Tin& tin_;
    MaterialTable materials_;
    TalusSolver solver_;
    AdjacencyGraph graph_;
    ActiveSet active_;
    std::uint32_t subscription_;
    std::vector<double> height_;
    std::vector<double> tan_alpha_;
    std::vector<std::uint16_t> material_seen_;  ///< material/moisture tan_alpha_ was computed for
    std::vector<float> moisture_seen_;
    std::vector<VertexId> write_ids_;  ///< changed since the last flush, each once
    std::vector<double> write_values_;
    std::vector<std::uint8_t> write_pending_;  ///< per vertex: listed in write_ids_
    std::vector<std::uint8_t> split_requested_;
    LocateHint hint_;
};

}  // namespace sandtin
