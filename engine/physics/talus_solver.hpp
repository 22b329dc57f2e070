#pragma once
// Talus relaxation over an AdjacencyGraph, in one of two schedules:
//  - Sequential (the seeds' Gauss-Seidel over the active list): each vertex sees the heights
//    its predecessors in the list just wrote. The CPU default.
//  - Jacobi: phase 1 computes every active vertex's outflow per directed edge from the old
//    heights, phase 2 lets every vertex gather what its neighbours sent. Deterministic and
//    independent of the thread count (each vertex sums in its fixed row order); the exact CPU
//    twin of the compute shader. Its active set is processed and rebuilt in vertex-id order
//    (the TIN numbers bulk-built vertices along a Hilbert curve, so that order is also
//    spatially coherent), and all three phases (outflow, gather, ageing) run on the threads.
// Both move volume, never height: what leaves a vertex is exactly what its neighbours receive.
// Both run either slope rule (TalusParameters::rule); the face rule's Jacobi rows always take
// the branching passes (physics/face_kernel.hpp has no branch-free or AVX-512 twin).

#include <cstdint>
#include <memory>
#include <vector>

#include "physics/active_set.hpp"
#include "physics/adjacency_graph.hpp"
#include "physics/talus_kernel.hpp"
#include "util/thread_pool.hpp"

namespace sandtin {

enum class Schedule : std::uint8_t { Sequential, Jacobi };

/// Which instruction set runs the Jacobi schedule's branch-free rows. Both give the same
/// results bit for bit; only the speed differs, and which is faster depends on the CPU and on
/// the graph's memory layout (measured on an AMD EPYC: AVX-512 10 % faster on TIN-id order,
/// 5 % slower on strip order).
enum class RowKernel : std::uint8_t {
    /// Measured on the solver's first large iteration (TalusSolver::row_kernel_in_use()).
    Auto,
    Avx512,  ///< where the CPU runs it (avx512_rows_supported()), else SSE2
    Sse2,
};

struct TalusSettings;
/// Throws std::invalid_argument naming the first setting out of range.
void validate_talus_settings(const TalusSettings& settings);

struct TalusSettings {
    Schedule schedule = Schedule::Sequential;
    TalusParameters parameters;
    int quiet_iterations = 3;  ///< K: a vertex leaves the active set after K still iterations
    double randomness = 0.0;   ///< relative jitter of each outflow, in [0, 1); 0 = none
    std::uint64_t seed = 1;    ///< seed of the jitter (results depend on it deterministically)
    int threads = 1;           ///< Jacobi worker threads
    /// Jacobi: the instruction set of the branch-free rows (the others are for comparing).
    RowKernel row_kernel = RowKernel::Auto;
};

/// The seeds' rule: the edge rule (SlopeRule::Edge) with no settle margin
/// (TalusParameters::settle_margin), as the seeds' experiments ran.
inline TalusSettings seeds_rule() {
    TalusSettings settings;
    settings.parameters.rule = SlopeRule::Edge;
    settings.parameters.settle_margin = 0.0;
    return settings;
}

/// The per-vertex arrays a relaxation reads and writes, indexed by vertex id.
struct TalusArrays {
    double* height = nullptr;           ///< m, updated in place
    const double* area = nullptr;       ///< m², lumped
    const double* bedrock = nullptr;    ///< m
    const double* tan_alpha = nullptr;  ///< tan of the angle of repose
    std::size_t size = 0;
    /// The TIN id of each index when the arrays are in another numbering (VertexNumbering):
    /// the jitter is hashed from it, so a renumbered run draws the same numbers. Null: the
    /// index is the id.
    const std::uint32_t* id = nullptr;
};

struct IterationStats {
    std::size_t processed = 0;  ///< vertices whose outflow was computed
    std::size_t changed = 0;    ///< vertices whose height changed
    double volume_moved = 0.0;  ///< m³ that left their vertices
};

class TalusSolver {
  public:
    explicit TalusSolver(TalusSettings settings);

    TalusSettings& settings() { return settings_; }
    const TalusSettings& settings() const { return settings_; }
    std::uint64_t iteration() const { return iteration_; }

    /// One iteration over the active set. Throws std::invalid_argument naming the setting when
    /// the settings are out of range (damping in (0, 1], settle margin and randomness in
    /// [0, 1), tolerance and r_S >= 0). Appends to `split_around` the vertices whose edges
    /// longer than the relocation radius kept material from moving (duplicates possible).
    /// Updates the active set (changed vertices and their neighbours stay or become active).
    IterationStats iterate(const AdjacencyGraph& graph, const TalusArrays& arrays,
                           ActiveSet& active, std::vector<std::uint32_t>* split_around = nullptr);
    /// Sizes the per-slot and per-vertex work arrays for `g` and `vertices`. iterate() does it
    /// too; a physics being created calls it first, so the first iteration after an edit
    /// allocates nothing (at 10⁶ vertices tens of megabytes, which the first stamp's erosion
    /// paid for).
    void prepare(const AdjacencyGraph& g, std::size_t vertices);

    /// The kernel's passes the next Jacobi iteration will take (chosen from how much of the last
    /// one flowed; the results are the same either way). Always Branching under the face rule.
    RowPasses jacobi_row_passes() const { return row_passes_; }

    /// The instruction set the Jacobi schedule's branch-free rows run in now (Avx512 or Sse2;
    /// rows with a relocation radius always take the SSE2 or branching passes). With
    /// RowKernel::Auto it is AVX-512 where supported until the first iteration with at least
    /// kRowKernelSampleRows active rows in branch-free passes; that iteration's first rows are
    /// computed in alternating chunks by both kernels (each row once, so nothing is repeated),
    /// and the one with the smaller median time per slot runs from then on.
    RowKernel row_kernel_in_use() const;
    /// Whether RowKernel::Auto has measured the two kernels yet.
    bool row_kernel_measured() const { return row_kernel_measured_; }
    /// Rows per measured chunk, and chunks (alternating AVX-512 and SSE2, ABBAAB).
    static constexpr std::size_t kRowKernelChunkRows = 16384;
    static constexpr std::size_t kRowKernelChunks = 6;
    static constexpr std::size_t kRowKernelSampleRows = kRowKernelChunkRows * kRowKernelChunks;

    /// Ids whose height changed in the last iteration.
    const std::vector<std::uint32_t>& changed() const { return changed_list_; }

  private:
    /// Slots of the rows the Jacobi schedule processed in an iteration, and how many of them
    /// carried sand: what picks the kernel's passes (RowPasses) for the next iteration.
    struct RowCensus {
        std::size_t slots = 0;
        std::size_t flowing = 0;
    };
    static RowPasses passes_after(const RowCensus& census);
    /// Per-thread scratch of the Jacobi schedule, on its own cache lines. The bitmaps hold one
    /// bit per vertex id and are written only by their thread, so marking needs no atomics;
    /// the next phase ORs them word by word (64 ids at a time) in id order.
    struct alignas(64) ThreadScratch {
        std::vector<std::uint64_t> receive;  ///< senders and their neighbours (phase 1)
        std::vector<std::uint64_t> wake;     ///< changed vertices and their neighbours (phase 2)
        std::size_t receive_lo = 0, receive_hi = 0;  ///< word range marked in `receive`
        std::size_t wake_lo = 0, wake_hi = 0;        ///< word range marked in `wake`
        std::uint32_t first = 0, last = 0;           ///< smallest and largest id in phase 1
        double moved = 0.0;
        RowCensus census;                    ///< phase 1
        std::vector<std::uint32_t> splits;   ///< phase 1, in list order
        std::vector<std::uint32_t> changed;  ///< phase 2, in id order
        std::vector<std::uint32_t> kept;     ///< phase 3: the next active list, in id order
        std::vector<double> row_q;           ///< the outflow of a row too long for the stack
    };
    /// What the Jacobi phases read, so the pool's task captures `this` only (no allocation).
    struct JacobiPass {
        const AdjacencyGraph* graph = nullptr;
        const TalusArrays* arrays = nullptr;
        ActiveSet* active = nullptr;
        std::size_t word_begin = 0;  ///< first bitmap word of phases 2 and 3
    };

    IterationStats sequential(const AdjacencyGraph& g, const TalusArrays& a, ActiveSet& active,
                              std::vector<std::uint32_t>* split_around);
    IterationStats jacobi(const AdjacencyGraph& g, const TalusArrays& a, ActiveSet& active,
                          std::vector<std::uint32_t>* split_around);
    template <RowPasses kPasses>
    void jacobi_outflow(std::size_t begin, std::size_t end, ThreadScratch& s);
    /// jacobi_outflow<RowPasses::BranchFree> in AVX-512, without a relocation radius (only
    /// called where avx512_rows_supported()).
    void jacobi_outflow_avx512(std::size_t begin, std::size_t end, ThreadScratch& s);
    void jacobi_gather(std::size_t begin, std::size_t end, ThreadScratch& s);
    void jacobi_age(std::size_t begin, std::size_t end, ThreadScratch& s);
    /// Runs body(begin, end, scratch) over [0, n) on the pool, or inline when n is small.
    template <class Body>
    void run(std::size_t n, bool threaded, Body body);
    /// Phase 1 of the first kRowKernelSampleRows rows of the active list, a chunk at a time,
    /// alternating the AVX-512 and SSE2 rows; records the faster (row_kernel_measured_).
    void measure_row_kernels(bool threaded);
    /// The share of each of vertex v's levelling volumes it sends this step (v an index into
    /// the arrays): the schedule's sigma (physics/talus_kernel.hpp; 1 sequential, damping
    /// Jacobi) times v's jitter.
    double levelling_share(const TalusArrays& a, std::uint32_t v) const;
    TalusSettings settings_;
    std::uint64_t iteration_ = 0;
    std::unique_ptr<ThreadPool> pool_;
    /// Jacobi: per slot k of v's row, the volume target(k) sends to v this iteration. Phase 1
    /// scatters each sender's outflow into its receivers' rows (through the reverse slots), so
    /// phase 2 reads its own row in order and zeroes it: all zero between iterations.
    std::vector<double> inflow_;
    /// Jacobi: per vertex, the total it sends this iteration (m³). Phase 1 writes each
    /// sender's, phase 2 takes it and leaves 0: all zero between iterations, so a vertex that
    /// sent nothing needs no mark saying so.
    std::vector<double> out_;
    std::vector<std::uint8_t> changed_;  ///< per vertex (sequential schedule)
    std::vector<std::uint32_t> changed_list_;
    // Jacobi schedule.
    /// The kernel's passes (RowPasses) for the next iteration, from this one's RowCensus.
    RowPasses row_passes_ = RowPasses::Branching;
    bool row_kernel_measured_ = false;
    bool avx512_rows_faster_ = true;  ///< the measurement's verdict (once measured)
    std::vector<ThreadScratch> scratch_;
    JacobiPass pass_;
};

}  // namespace sandtin
