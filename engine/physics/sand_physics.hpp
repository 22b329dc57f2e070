#pragma once
// Sand physics on the TIN: talus relaxation over the active vertices, per-vertex materials and
// moisture, bedrock, and refinement of long edges at the relocation radius r_S (so a pile
// poured onto two flat triangles grows its own detail). It follows every change to the TIN
// (tools, brushes, undo) through a Tin change subscription: whatever changed becomes active.
//
// The relaxation runs in its own vertex numbering (VertexNumbering; strips for Jacobi): the
// graph (packed rows), the per-vertex arrays and the active set are laid out for locality:
// Jacobi at 10⁶ active vertices, 10.1 -> 13.5 M updates per CPU-second over the TIN's ids
// (`sandtin bench erosion --throughput`, sand-physics rows). The numbering is
// invisible outside: heights are bit for bit those of a run in TIN ids (each row keeps its
// order, the jitter hashes TIN ids, and the sequential schedule visits vertices in the same
// activation order). Vertices born later are appended; once they are a quarter of the
// numbering (and at least kRenumberMinimum), everything is renumbered in strips again.

#include <memory>
#include <span>
#include <vector>

#include "physics/adjacency_graph.hpp"
#include "physics/material.hpp"
#include "physics/relocation_refinement.hpp"
#include "physics/talus_solver.hpp"
#include "physics/terrain_solver.hpp"
#include "physics/vertex_numbering.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_change_feed.hpp"

namespace sandtin {

/// The numbering the relaxation runs in (see above).
enum class VertexOrder : std::uint8_t {
    Tin,     ///< the TIN's own ids
    Strips,  ///< strips two mean spacings tall, in x order
    /// Strips for the Jacobi schedule (it sweeps the active set in id order), the TIN's ids for
    /// the sequential one: that visits vertices in activation order, which follows the TIN's
    /// ids, and strips scatter that walk (measured on the dunes bench, sequential, 32 000
    /// points: 3.3 -> 3.6 s CPU in strips).
    Auto,
};

/// The CPU relaxation: the reference the GPU relaxation is checked against.
class SandPhysics final : public RelaxationSolver {
  public:
    /// Subscribes to the TIN's changes; the TIN must outlive the physics.
    SandPhysics(Tin& tin, MaterialTable materials, TalusSettings settings = {},
                VertexOrder order = VertexOrder::Auto);
    ~SandPhysics() override;
    SandPhysics(const SandPhysics&) = delete;
    SandPhysics& operator=(const SandPhysics&) = delete;

    SolverDevice device() const override { return SolverDevice::Cpu; }
    bool conserves_volume_exactly() const override { return true; }
    TalusSettings& settings() override { return solver_.settings(); }
    const MaterialTable& materials() const { return materials_; }
    void set_materials(const MaterialTable& materials) override;

    void activate(std::span<const VertexId> vertices) override;
    /// Every live vertex becomes active (e.g. after loading a terrain that is not at rest).
    void activate_all() override;
    std::size_t active_count() const override { return active_.size(); }
    /// True while vertex v is still being relaxed.
    bool is_active(VertexId v) const;
    bool at_rest() const override { return active_.empty(); }

    /// Runs up to `iterations` relaxation iterations (stops early at rest). Vertices whose
    /// height changed are appended to `changed` when given (the caller queues them for
    /// simplification, seed 003 §4 step 2d), and so are the vertices the relocation radius's
    /// refinement inserted (where no sand came after, they are flat ground to simplify).
    PhysicsStepReport step(int iterations = 1, std::vector<VertexId>* changed = nullptr) override;
    /// Iterates until nothing is active or `max_iterations` ran.
    PhysicsStepReport run_to_rest(int max_iterations,
                                  std::vector<VertexId>* changed = nullptr) override;

    /// Splits the edges around `vertices` until none is longer than the relocation radius
    /// (the same refinement the relaxation asks for when sand meets a long edge), so a pour at
    /// a single vertex of a coarse terrain starts from a star of radius r_S. Returns the
    /// vertices inserted; no-op without a relocation radius.
    std::size_t refine_around(std::span<const VertexId> vertices);

    /// The relaxation's graph, in numbering()'s local ids.
    const AdjacencyGraph& graph() const { return graph_; }
    const VertexNumbering& numbering() const { return numbering_; }
    /// Times the strip numbering was rebuilt since construction (tests, stats).
    std::size_t renumberings() const { return renumberings_; }

    /// Appended vertices that trigger a renumbering at least (below, appending is cheaper).
    static constexpr std::size_t kRenumberMinimum = 4096;

  private:
    void sync();
    /// Numbers the born vertices among `topology`, grows the local arrays and rewrites the
    /// graph rows of `topology`.
    void apply_topology(std::span<const VertexId> topology);
    /// Numbers the live vertices among `vertices` that are not yet (before sync() has seen
    /// them), so they can be activated.
    void number(std::span<const VertexId> vertices);
    /// Numbers the live vertices in strips again and rebuilds the graph and the local arrays.
    void renumber();
    /// Grows the local arrays to the numbering and loads area, bedrock and height of local id
    /// l from the TIN (the strip numbering keeps its own copies of area and bedrock).
    void grow_local();
    /// Sizes the solver's and the active set's arrays to the graph and the numbering (at
    /// creation and renumbering, so an edit's first iteration allocates nothing O(terrain)).
    void prepare_work_arrays();
    void load(std::uint32_t l);
    /// The arrays the solver reads, in local ids.
    TalusArrays arrays();
    /// Writes the heights the relaxation changed since the last flush into the TIN (once per
    /// step, and before refinement reads them), and drops the journal entries that write
    /// makes: they echo values height_ already holds, and the solver has already activated
    /// those vertices and their neighbours.
    void flush(std::vector<VertexId>* changed_out);
    /// Refines around the given vertices until their edges are at most r_S (seed 000 §7.2,
    /// "prevention of long edges"): points of a hexagonal lattice of spacing 0.75 r_S inside
    /// their stars, or, where no lattice point fits, the midpoints of their long edges. The
    /// vertices inserted are appended to `inserted` when given.
    std::size_t refine(std::vector<std::uint32_t>& around,
                       std::vector<VertexId>* inserted = nullptr);

    Tin& tin_;
    MaterialTable materials_;
    TalusSolver solver_;
    VertexOrder order_;
    VertexNumbering numbering_;
    std::size_t renumberings_ = 0;
    AdjacencyGraph graph_{RowSlack::None};  ///< local ids, packed rows
    ActiveSet active_;                      ///< local ids
    VertexChangeFeed changes_;
    // Per local id.
    std::vector<double> height_;
    std::vector<double> tan_alpha_;
    std::vector<double> area_;     ///< strip numbering only (else the TIN's array is read)
    std::vector<double> bedrock_;  ///< strip numbering only
    // Per TIN id.
    std::vector<std::uint16_t> material_seen_;  ///< material/moisture tan_alpha_ was computed for
    std::vector<float> moisture_seen_;
    // The heights the relaxation changed since the last flush, each once, by local id (so
    // reading height_ and the flags stays sequential in the strip numbering).
    std::vector<std::uint32_t> write_local_;
    std::vector<std::uint8_t> write_pending_;  ///< per local id: listed in write_local_
    std::vector<VertexId> write_ids_;          ///< flush() scratch: TIN ids
    std::vector<double> write_values_;         ///< flush() scratch
    RelocationRefiner refiner_;
};

}  // namespace sandtin
