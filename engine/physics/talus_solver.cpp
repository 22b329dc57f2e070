#include "physics/talus_solver.hpp"

#include "physics/face_kernel.hpp"
#include "physics/talus_kernel_avx512.hpp"
#include "util/prepare_for_writing.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <memory>
#include <stdexcept>

namespace sandtin {

namespace {

constexpr std::size_t kNoWord = ~std::size_t{0};
/// Below this many active vertices the Jacobi phases run on the calling thread: waking the
/// pool costs more than the work.
constexpr std::size_t kThreadedMinimum = 2048;
/// Percentage of the processed slots that must carry sand for the next iteration to take the
/// branch-free passes (passes_after).
constexpr std::size_t kBranchFreePercent = 35;
/// Sets v's bit when `set` (without a branch). The caller widens its word range once per row
/// (widen_to_row), not once per bit: a row's marks are most of the phases' instructions.
inline void mark(std::uint64_t* bits, std::uint32_t v, bool set = true) {
    bits[v >> 6] |= static_cast<std::uint64_t>(set) << (v & 63u);
}
/// Widens the word range [lo, hi) to every word v's row touches (the later phases find the
/// words no bit was set in empty).
inline void widen_to_row(const RowWords* row_words, std::uint32_t v, std::size_t& lo,
                         std::size_t& hi) {
    lo = std::min<std::size_t>(lo, row_words[v].lo);
    hi = std::max<std::size_t>(hi, row_words[v].hi);
}

// Vertices ahead of the one being processed whose neighbours' data is fetched early. A
// neighbour's id is often far from the vertex's own (the TIN's multiscale Hilbert numbering
// puts about a third of the neighbours more than 10⁵ ids away), so without prefetching each
// iteration waits on those cache misses one after another.
// The prefetching helpers below are always inlined: GCC 12 at -O2 and above finds an
// out-of-line function that only prefetches to have no side effects, and deletes its calls
// (the Jacobi schedule's prefetching was not in the binary until this was found).
constexpr std::size_t kPrefetchDistance = 12;

/// `longest` is null without a relocation radius: the kernel never reads it then.
[[gnu::always_inline]] inline void prefetch_outflow(std::uint32_t v, const AdjacencyGraph& g,
                                                    const TalusArrays& a, const double* longest) {
    if (v >= g.degrees().size()) return;
    const std::uint32_t* target = g.targets().data();
    const std::uint32_t row = g.offsets()[v];
    for (std::uint32_t k = row; k < row + g.degrees()[v]; ++k) {
        const std::uint32_t t = target[k];
        __builtin_prefetch(a.height + t);
        __builtin_prefetch(a.area + t);
        if (longest != nullptr) __builtin_prefetch(longest + t);
    }
}

/// The sequential schedule visits vertices in the order they became active: after a stamp that
/// order is scattered over the vertex arrays and over the graph's pool (rows a stamp rewrote
/// move to its end), and each visit waited on its row, then on its neighbours' heights, one
/// cache miss after another. It prefetches in three stages, each reading only what the stage
/// before brought in: the row's place (3 d ahead), the row's slots and the vertex's own data
/// (2 d ahead), the neighbours' heights and areas (d ahead, prefetch_outflow).
[[gnu::always_inline]] inline void prefetch_row_place(std::uint32_t v, const AdjacencyGraph& g) {
    if (v >= g.degrees().size()) return;
    __builtin_prefetch(g.offsets().data() + v);
    __builtin_prefetch(g.degrees().data() + v);
}

[[gnu::always_inline]] inline void prefetch_row(std::uint32_t v, const AdjacencyGraph& g,
                                                const TalusArrays& a, FaceRows faces) {
    if (v >= g.degrees().size()) return;
    const std::uint32_t row = g.offsets()[v];
    __builtin_prefetch(g.targets().data() + row);
    __builtin_prefetch(g.lengths().data() + row);
    if (faces.across != nullptr) __builtin_prefetch(faces.across + row);
    if (faces.corner != nullptr) {
        // 16 bytes a slot: a row of six spans two lines.
        __builtin_prefetch(faces.corner + row);
        __builtin_prefetch(faces.corner + row + 4);
    }
    __builtin_prefetch(a.height + v);
    __builtin_prefetch(a.area + v);
    __builtin_prefetch(a.bedrock + v);
    __builtin_prefetch(a.tan_alpha + v);
}

/// Rows of up to this many slots keep their outflow on the stack of the thread computing it (a
/// TIN's rows have a handful of slots). A heap buffer of a few doubles per thread could share
/// a cache line with the other thread's, and every write would then take the line from the
/// other core: it did, on 2 threads on the strip-numbered 10⁶-vertex grid (30 against
/// 39.5 M updates/s).
constexpr std::uint32_t kStackRowSlots = 32;

/// Where a row of `degree` slots keeps its outflow: `stack`, or for a longer row (rare) `heap`,
/// grown to fit.
inline double* row_buffer(std::array<double, kStackRowSlots>& stack, std::vector<double>& heap,
                          std::uint32_t degree) {
    if (degree <= kStackRowSlots) return stack.data();
    if (heap.size() < degree) heap.resize(degree);
    return heap.data();
}

/// The branch-free sending of a row's levelling volumes q[0, degree) scaled by `scale`, in row
/// order (what talus_outflow does, so the returned total is the same sum bit for bit): one visit
/// of the row. No branch per slot: a slot that does not flow writes its +0.0 into an inflow slot
/// that holds +0.0 already, and marks nothing. Only neighbours that receive something are
/// marked: one that gets 0 from every sender and sends nothing itself would gather exactly 0
/// and keep its height. `target` and `reverse` point at the row's slots.
inline double send_branch_free(const double* q, std::uint32_t degree, double scale,
                               const std::uint32_t* target, const std::uint32_t* reverse,
                               double* inflow, std::uint64_t* receive, std::size_t& flowing) {
    double sent = 0.0;
    for (std::uint32_t k = 0; k < degree; ++k) {
        const double volume = q[k] * scale;
        sent += volume;
        const bool flows = volume > 0.0;
        mark(receive, target[k], flows);
        flowing += flows ? 1u : 0u;
        inflow[reverse[k]] = volume;  // only this sender writes the slot of the edge into target
    }
    return sent;
}

}  // namespace

/// The Jacobi kernel's passes for the next iteration, from the share of the rows' slots that
/// carried sand in this one. Where it is large, whether an edge flows is a coin toss and the
/// kernel's branches mispredict: the branch-free passes win (10⁶ active vertices: 43 % of the
/// slots flow, 13.7 -> 17.4 M updates/s). Where it is small, as on a terrain coming to rest,
/// the branches predict well and skip the work of the edges at rest: the branching passes win
/// (the groove eroded to rest: 5 % of the slots on average, at most 40 %; 81 against 100 ms
/// with the branch-free passes throughout). Both give the same results bit for bit, so only
/// the speed depends on this choice. (The sequential schedule keeps the branching passes: its
/// Gauss-Seidel update branches on each slot anyway, and measured no faster without them.)
RowPasses TalusSolver::passes_after(const RowCensus& census) {
    return census.flowing > 0 && census.flowing * 100 >= census.slots * kBranchFreePercent
               ? RowPasses::BranchFree
               : RowPasses::Branching;
}

TalusSolver::TalusSolver(TalusSettings settings) : settings_(settings) {
    pool_ = std::make_unique<ThreadPool>(std::max(1, settings_.threads));
}

double TalusSolver::levelling_share(const TalusArrays& a, std::uint32_t v) const {
    // Gauss-Seidel levels each edge whole: the receiver's height is current for the next
    // vertex. Jacobi receivers take from every sender at once, so each sends damping of it.
    const double sigma =
        settings_.schedule == Schedule::Sequential ? 1.0 : settings_.parameters.damping;
    if (settings_.randomness <= 0.0) return sigma;
    const std::uint32_t id = a.id != nullptr ? a.id[v] : v;
    return sigma * (1.0 + settings_.randomness * signed_unit_hash(settings_.seed, id, iteration_));
}

void TalusSolver::prepare(const AdjacencyGraph& g, std::size_t vertices) {
    // Grown into prepared memory (util/prepare_for_writing.hpp): at 10⁶ vertices these are tens
    // of megabytes. Per slot, as many as the graph's pool has room for: rows that move to the
    // end of the pool then need no growth here (sized to the pool's size, it doubled at the
    // second stamp at 10⁶ vertices).
    const std::size_t slots = std::max(g.slot_count(), g.slot_capacity());
    // Slots move when the graph rewrites or compacts rows, but every one is zero here.
    if (settings_.schedule == Schedule::Jacobi && inflow_.size() < slots) {
        reserve_for_writing(inflow_, slots);
        inflow_.resize(slots, 0.0);
    }
    if (out_.size() < vertices) {
        reserve_for_writing(out_, vertices);
        reserve_for_writing(changed_, vertices);
        out_.resize(vertices, 0.0);
        changed_.resize(vertices, 0);
    }
    if (pool_->threads() != std::max(1, settings_.threads)) {
        pool_ = std::make_unique<ThreadPool>(std::max(1, settings_.threads));
    }
    scratch_.resize(static_cast<std::size_t>(pool_->threads()));
    const std::size_t words = (out_.size() + 63) / 64;
    for (ThreadScratch& s : scratch_) {
        if (s.receive.size() < words) {
            s.receive.resize(words, 0);
            s.wake.resize(words, 0);
        }
    }
}

template <class Body>
void TalusSolver::run(std::size_t n, bool threaded, Body body) {
    if (threaded) {
        pool_->parallel_for(n, [&](std::size_t b, std::size_t e, int t) {
            body(b, e, scratch_[static_cast<std::size_t>(t)]);
        });
    } else {
        body(0, n, scratch_[0]);
    }
}

void validate_talus_settings(const TalusSettings& s) {
    const TalusParameters& p = s.parameters;
    // Written so that NaN fails too.
    if (!(p.damping > 0.0 && p.damping <= 1.0))
        throw std::invalid_argument("talus relaxation: damping must be in (0, 1]");
    if (!(p.rest_tolerance >= 0.0))
        throw std::invalid_argument("talus relaxation: rest_tolerance must be >= 0");
    if (!(p.relocation_radius >= 0.0))
        throw std::invalid_argument("talus relaxation: relocation_radius must be >= 0");
    if (!(p.settle_margin >= 0.0 && p.settle_margin < 1.0))
        throw std::invalid_argument("talus relaxation: settle_margin must be in [0, 1)");
    if (!(s.randomness >= 0.0 && s.randomness < 1.0))
        throw std::invalid_argument("talus relaxation: randomness must be in [0, 1)");
}

IterationStats TalusSolver::iterate(const AdjacencyGraph& graph, const TalusArrays& arrays,
                                    ActiveSet& active, std::vector<std::uint32_t>* split_around) {
    validate_talus_settings(settings_);  // settings() is writable between iterations
    for (std::uint32_t v : changed_list_)
        changed_[v] = 0;
    changed_list_.clear();
    if (active.empty()) return {};
    std::size_t vertices = std::max<std::size_t>(arrays.size, graph.vertex_capacity());
    vertices = std::max(vertices, active.quiet_.size());
    prepare(graph, vertices);
    IterationStats stats;
    if (settings_.schedule == Schedule::Sequential) {
        stats = sequential(graph, arrays, active, split_around);
        // Changed vertices and their neighbours may now have excess.
        active.age(changed_, settings_.quiet_iterations);
        for (std::uint32_t v : changed_list_) {
            active.activate(v);
            const std::uint32_t b = graph.offset(v);
            for (std::uint32_t k = b; k < b + graph.degree(v); ++k)
                active.activate(graph.targets()[k]);
        }
    } else {
        stats = jacobi(graph, arrays, active, split_around);
    }
    ++iteration_;
    return stats;
}

IterationStats TalusSolver::sequential(const AdjacencyGraph& g, const TalusArrays& a,
                                       ActiveSet& active,
                                       std::vector<std::uint32_t>* split_around) {
    IterationStats stats;
    const std::uint32_t* target = g.targets().data();
    const double* length = g.lengths().data();
    const double* longest = g.longest_edges().data();
    const FaceRows faces = g.face_rows();
    const bool face_rule = settings_.parameters.rule == SlopeRule::Face;
    // A row's outflow lives on the stack (kStackRowSlots), not in an array over the graph's
    // slots: the rows a stamp rewrote sit scattered over the pool, and each visit missed the
    // cache on that array as on the rows themselves.
    std::array<double, kStackRowSlots> stack_q;
    std::vector<double>& heap_q = scratch_[0].row_q;
    const FaceRows prefetched_faces = face_rule ? faces : FaceRows{};
    const double* prefetch_longest =
        settings_.parameters.relocation_radius > 0.0 ? longest : nullptr;
    const std::vector<std::uint32_t>& list = active.list();
    const std::size_t end = list.size();
    for (std::size_t idx = 0; idx < end; ++idx) {
        const std::uint32_t i = list[idx];
        if (idx + 3 * kPrefetchDistance < end)
            prefetch_row_place(list[idx + 3 * kPrefetchDistance], g);
        if (idx + 2 * kPrefetchDistance < end)
            prefetch_row(list[idx + 2 * kPrefetchDistance], g, a, prefetched_faces);
        if (idx + kPrefetchDistance < end)
            prefetch_outflow(list[idx + kPrefetchDistance], g, a, prefetch_longest);
        const std::uint32_t degree = g.degree(i);
        if (degree == 0) continue;
        const std::uint32_t row = g.offset(i);
        const std::uint32_t* row_target = target + row;
        ++stats.processed;
        auto split = [&](std::uint32_t v) {
            if (split_around != nullptr) split_around->push_back(v);
        };
        double* q = row_buffer(stack_q, heap_q, degree);
        const double sent =
            face_rule ? face_outflow(i, 0, degree, row_target, length + row, faces.from(row),
                                     longest, a.height, a.area, a.bedrock, a.tan_alpha[i],
                                     settings_.parameters, levelling_share(a, i), q, split)
                      : talus_outflow(i, 0, degree, row_target, length + row, longest, a.height,
                                      a.area, a.bedrock, a.tan_alpha[i], settings_.parameters,
                                      levelling_share(a, i), q, split);
        if (sent <= 0.0) continue;
        // Gauss-Seidel: apply at once, so the next vertex sees the new heights.
        a.height[i] -= sent / a.area[i];
        // When the sand ran out, h - (A (h - b)) / A can round to an ulp below b; the sand
        // thickness must never be negative, and an ulp of volume is far inside the drift bound.
        if (a.height[i] < a.bedrock[i]) a.height[i] = a.bedrock[i];
        auto mark = [&](std::uint32_t v) {
            if (!changed_[v]) {
                changed_[v] = 1;
                changed_list_.push_back(v);
            }
        };
        mark(i);
        for (std::uint32_t k = 0; k < degree; ++k) {
            if (q[k] > 0.0) {
                a.height[row_target[k]] += q[k] / a.area[row_target[k]];
                mark(row_target[k]);
            }
        }
        stats.volume_moved += sent;
    }
    stats.changed = changed_list_.size();
    return stats;
}

IterationStats TalusSolver::jacobi(const AdjacencyGraph& g, const TalusArrays& a, ActiveSet& active,
                                   std::vector<std::uint32_t>* split_around) {
    IterationStats stats;
    active.ensure(static_cast<std::uint32_t>(out_.size() - 1));
    pass_ = {&g, &a, &active, 0};
    const std::vector<std::uint32_t>& list = active.list_;
    const bool threaded = list.size() >= kThreadedMinimum && pool_->threads() > 1;
    for (ThreadScratch& s : scratch_) {
        s.receive_lo = s.wake_lo = kNoWord;
        s.receive_hi = s.wake_hi = 0;
        s.first = ~0u;
        s.last = 0;
        s.moved = 0.0;
        s.census = {};
        s.splits.clear();
        s.changed.clear();
        s.kept.clear();
    }

    // Phase 1: outflow of every active vertex along each of its edges, from the old heights;
    // senders mark themselves and the neighbours they send to as receivers.
    // The face rule's rows take the branching passes only (face_row_scale): it has no
    // branch-free or AVX-512 twin, and these passes are never chosen for it (passes_after).
    const bool face_rule = settings_.parameters.rule == SlopeRule::Face;
    if (face_rule) row_passes_ = RowPasses::Branching;
    static const bool avx512 = avx512_rows_supported();
    const bool avx512_applies = row_passes_ == RowPasses::BranchFree && avx512 &&
                                settings_.row_kernel != RowKernel::Sse2 &&
                                settings_.parameters.relocation_radius == 0.0;
    std::size_t measured_rows = 0;
    if (avx512_applies && settings_.row_kernel == RowKernel::Auto && !row_kernel_measured_ &&
        list.size() >= kRowKernelSampleRows) {
        measure_row_kernels(threaded);
        measured_rows = kRowKernelSampleRows;
    }
    if (avx512_applies && row_kernel_in_use() == RowKernel::Avx512) {
#if SANDTIN_HAVE_AVX512_ROWS
        if (measured_rows == 0) {
            run(list.size(), threaded, [this](std::size_t b, std::size_t e, ThreadScratch& s) {
                jacobi_outflow_avx512(b, e, s);
            });
        } else {
            run(list.size() - measured_rows, threaded,
                [this, measured_rows](std::size_t b, std::size_t e, ThreadScratch& s) {
                    jacobi_outflow_avx512(measured_rows + b, measured_rows + e, s);
                });
        }
#endif
    } else if (row_passes_ == RowPasses::BranchFree && measured_rows > 0) {
        run(list.size() - measured_rows, threaded,
            [this, measured_rows](std::size_t b, std::size_t e, ThreadScratch& s) {
                jacobi_outflow<RowPasses::BranchFree>(measured_rows + b, measured_rows + e, s);
            });
    } else if (row_passes_ == RowPasses::BranchFree) {
        run(list.size(), threaded, [this](std::size_t b, std::size_t e, ThreadScratch& s) {
            jacobi_outflow<RowPasses::BranchFree>(b, e, s);
        });
    } else {
        run(list.size(), threaded, [this](std::size_t b, std::size_t e, ThreadScratch& s) {
            jacobi_outflow<RowPasses::Branching>(b, e, s);
        });
    }
    stats.processed = list.size();
    std::size_t lo = kNoWord, hi = 0;
    std::uint32_t first = ~0u, last = 0;
    RowCensus census;
    for (const ThreadScratch& s : scratch_) {
        census.slots += s.census.slots;
        census.flowing += s.census.flowing;
        stats.volume_moved += s.moved;
        lo = std::min(lo, s.receive_lo);
        hi = std::max(hi, s.receive_hi);
        first = std::min(first, s.first);
        last = std::max(last, s.last);
        if (split_around != nullptr)
            split_around->insert(split_around->end(), s.splits.begin(), s.splits.end());
    }

    row_passes_ = face_rule ? RowPasses::Branching : passes_after(census);

    // Phase 2: each receiver gathers, in its row order, what its source neighbours sent; the
    // changed ones wake themselves and their neighbours.
    if (hi > lo) {
        pass_.word_begin = lo;
        run(hi - lo, threaded,
            [this](std::size_t b, std::size_t e, ThreadScratch& s) { jacobi_gather(b, e, s); });
    }
    for (const ThreadScratch& s : scratch_)
        changed_list_.insert(changed_list_.end(), s.changed.begin(), s.changed.end());
    stats.changed = changed_list_.size();

    // Phase 3: the next active set, over the words of the old one and of the woken vertices.
    lo = static_cast<std::size_t>(first >> 6);
    hi = static_cast<std::size_t>(last >> 6) + 1;
    for (const ThreadScratch& s : scratch_) {
        lo = std::min(lo, s.wake_lo);
        hi = std::max(hi, s.wake_hi);
    }
    pass_.word_begin = lo;
    run(hi - lo, threaded,
        [this](std::size_t b, std::size_t e, ThreadScratch& s) { jacobi_age(b, e, s); });
    active.list_.clear();
    for (const ThreadScratch& s : scratch_)
        active.list_.insert(active.list_.end(), s.kept.begin(), s.kept.end());
    return stats;
}

RowKernel TalusSolver::row_kernel_in_use() const {
    if (!avx512_rows_supported() || settings_.row_kernel == RowKernel::Sse2) return RowKernel::Sse2;
    if (settings_.row_kernel == RowKernel::Avx512) return RowKernel::Avx512;
    return row_kernel_measured_ && !avx512_rows_faster_ ? RowKernel::Sse2 : RowKernel::Avx512;
}

void TalusSolver::measure_row_kernels(bool threaded) {
    // ABBAAB: each kernel runs early and late, so a machine speeding up or slowing down over
    // the six chunks favours neither. Time per slot, because rows differ in length.
    constexpr std::array<bool, kRowKernelChunks> kAvx512Chunk{true, false, false,
                                                              true, true,  false};
    std::array<double, 3> avx512_ns{}, sse2_ns{};
    std::size_t n_avx512 = 0, n_sse2 = 0;
    auto slots = [this] {
        std::size_t sum = 0;
        for (const ThreadScratch& s : scratch_)
            sum += s.census.slots;
        return sum;
    };
    for (std::size_t c = 0; c < kRowKernelChunks; ++c) {
        const std::size_t first = c * kRowKernelChunkRows;
        const std::size_t slots_before = slots();
        const auto t0 = std::chrono::steady_clock::now();
        if (kAvx512Chunk[c]) {
#if SANDTIN_HAVE_AVX512_ROWS
            run(kRowKernelChunkRows, threaded,
                [this, first](std::size_t b, std::size_t e, ThreadScratch& s) {
                    jacobi_outflow_avx512(first + b, first + e, s);
                });
#endif
        } else {
            run(kRowKernelChunkRows, threaded,
                [this, first](std::size_t b, std::size_t e, ThreadScratch& s) {
                    jacobi_outflow<RowPasses::BranchFree>(first + b, first + e, s);
                });
        }
        const double ns =
            std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
        const double per_slot =
            ns / static_cast<double>(std::max<std::size_t>(slots() - slots_before, 1));
        if (kAvx512Chunk[c]) {
            avx512_ns[n_avx512++] = per_slot;
        } else {
            sse2_ns[n_sse2++] = per_slot;
        }
    }
    // Medians of three: one chunk slowed by another process does not decide.
    std::sort(avx512_ns.begin(), avx512_ns.end());
    std::sort(sse2_ns.begin(), sse2_ns.end());
    avx512_rows_faster_ = avx512_ns[1] <= sse2_ns[1];
    row_kernel_measured_ = true;
}

template <RowPasses kPasses>
void TalusSolver::jacobi_outflow(std::size_t begin, std::size_t end, ThreadScratch& s) {
    const AdjacencyGraph& g = *pass_.graph;
    const TalusArrays& a = *pass_.arrays;
    const std::uint32_t* list = pass_.active->list_.data();
    const std::uint32_t* target = g.targets().data();
    const std::uint32_t* reverse = g.reverses().data();
    const double* length = g.lengths().data();
    const FaceRows faces = g.face_rows();
    const bool face_rule = settings_.parameters.rule == SlopeRule::Face;
    const double* longest = g.longest_edges().data();
    const double* prefetch_longest =
        settings_.parameters.relocation_radius > 0.0 ? longest : nullptr;
    const std::uint32_t* offset = g.offsets().data();
    const std::uint32_t* degree = g.degrees().data();
    const RowWords* row_words = g.row_words().data();
    const std::size_t rows = g.degrees().size();
    std::array<double, kStackRowSlots> stack_q;  // see kStackRowSlots
    double* inflow = inflow_.data();
    double* out = out_.data();
    std::uint64_t* receive = s.receive.data();
    std::size_t lo = s.receive_lo, hi = s.receive_hi;
    std::uint32_t first = s.first, last = s.last;
    double moved = 0.0;
    RowCensus census = s.census;
    for (std::size_t idx = begin; idx < end; ++idx) {
        const std::uint32_t i = list[idx];
        if (idx + kPrefetchDistance < end)
            prefetch_outflow(list[idx + kPrefetchDistance], g, a, prefetch_longest);
        first = std::min(first, i);
        last = std::max(last, i);
        const std::uint32_t deg = i < rows ? degree[i] : 0;
        if (deg == 0) continue;
        const std::uint32_t row = offset[i];
        census.slots += deg;
        double* q = row_buffer(stack_q, s.row_q, deg);
        auto split = [&s](std::uint32_t v) { s.splits.push_back(v); };
        double scale = 0.0;
        if constexpr (kPasses == RowPasses::Branching) {
            // The face rule, from the same old heights (its rows always branch; see jacobi()).
            scale = face_rule ? face_scale(i, 0, deg, target + row, length + row, faces.from(row),
                                           longest, a.height, a.area, a.bedrock, a.tan_alpha[i],
                                           settings_.parameters, levelling_share(a, i), q, split)
                              : talus_scale<kPasses>(i, 0, deg, target + row, length + row, longest,
                                                     a.height, a.area, a.bedrock, a.tan_alpha[i],
                                                     settings_.parameters, levelling_share(a, i), q,
                                                     split);
        } else {
            scale = talus_scale<kPasses>(i, 0, deg, target + row, length + row, longest, a.height,
                                         a.area, a.bedrock, a.tan_alpha[i], settings_.parameters,
                                         levelling_share(a, i), q, split);
        }
        // Scaled as they are sent, in row order (see send_branch_free); only neighbours that
        // receive something are marked.
        double sent = 0.0;
        if (scale > 0.0) {
            if constexpr (kPasses == RowPasses::BranchFree) {
                sent = send_branch_free(q, deg, scale, target + row, reverse + row, inflow, receive,
                                        census.flowing);
            } else {
                for (std::uint32_t k = 0; k < deg; ++k) {
                    if (!(q[k] > 0.0)) continue;
                    const std::uint32_t t = target[row + k];
                    const double volume = q[k] * scale;
                    sent += volume;
                    if (volume > 0.0) {
                        mark(receive, t);
                        ++census.flowing;
                        // Only this sender writes the slot of the edge into target (row + k).
                        inflow[reverse[row + k]] = volume;
                    }
                }
            }
        }
        moved += sent;
        if (sent > 0.0) {
            out[i] = sent;  // the gather takes it, and leaves 0 (see out_)
            mark(receive, i);
            widen_to_row(row_words, i, lo, hi);
        }
    }
    s.receive_lo = lo;
    s.receive_hi = hi;
    s.first = first;
    s.last = last;
    s.moved = moved;
    s.census = census;
}

#if SANDTIN_HAVE_AVX512_ROWS
// jacobi_outflow<RowPasses::BranchFree> with the AVX-512 rows (talus_kernel_avx512.hpp) for
// rows of up to eight slots, and the SSE2 passes for longer ones: the same results bit for bit.
SANDTIN_AVX512_TARGET void TalusSolver::jacobi_outflow_avx512(std::size_t begin, std::size_t end,
                                                              ThreadScratch& s) {
    const AdjacencyGraph& g = *pass_.graph;
    const TalusArrays& a = *pass_.arrays;
    const TalusParameters& p = settings_.parameters;
    const std::uint32_t* list = pass_.active->list_.data();
    const std::uint32_t* target = g.targets().data();
    const std::uint32_t* reverse = g.reverses().data();
    const double* length = g.lengths().data();
    const double* longest = g.longest_edges().data();
    const std::uint32_t* offset = g.offsets().data();
    const std::uint32_t* degree = g.degrees().data();
    const RowWords* row_words = g.row_words().data();
    const std::size_t rows = g.degrees().size();
    std::array<double, kStackRowSlots> stack_q;  // see kStackRowSlots
    double* inflow = inflow_.data();
    double* out = out_.data();
    std::uint64_t* receive = s.receive.data();
    std::size_t lo = s.receive_lo, hi = s.receive_hi;
    std::uint32_t first = s.first, last = s.last;
    double moved = 0.0;
    RowCensus census = s.census;
    for (std::size_t idx = begin; idx < end; ++idx) {
        const std::uint32_t i = list[idx];
        if (idx + kPrefetchDistance < end)
            prefetch_outflow(list[idx + kPrefetchDistance], g, a, nullptr);
        first = std::min(first, i);
        last = std::max(last, i);
        const std::uint32_t deg = i < rows ? degree[i] : 0;
        if (deg == 0) continue;
        const std::uint32_t row = offset[i];
        census.slots += deg;
        double sent = 0.0;
        if (deg <= detail::kAvx512RowSlots) {
            const double hi_i = a.height[i];
            const detail::Avx512Row volumes =
                detail::avx512_flowing_volumes(i, deg, target + row, length + row, a.height, a.area,
                                               a.tan_alpha[i], p, detail::excess_floor(hi_i));
            if (!(volumes.excess.largest > 0.0)) continue;
            const double scale = detail::outflow_scale(volumes.excess, hi_i, a.area[i],
                                                       a.bedrock[i], p, levelling_share(a, i));
            if (scale > 0.0)
                sent = detail::avx512_send(volumes.volume, deg, scale, target + row, reverse + row,
                                           inflow, receive, census.flowing);
        } else {
            double* q = row_buffer(stack_q, s.row_q, deg);
            const double scale = talus_scale<RowPasses::BranchFree>(
                i, 0, deg, target + row, length + row, longest, a.height, a.area, a.bedrock,
                a.tan_alpha[i], p, levelling_share(a, i), q, [](std::uint32_t) {});
            if (scale > 0.0)
                sent = send_branch_free(q, deg, scale, target + row, reverse + row, inflow, receive,
                                        census.flowing);
        }
        moved += sent;
        if (sent > 0.0) {
            out[i] = sent;  // the gather takes it, and leaves 0 (see out_)
            mark(receive, i);
            widen_to_row(row_words, i, lo, hi);
        }
    }
    s.receive_lo = lo;
    s.receive_hi = hi;
    s.first = first;
    s.last = last;
    s.moved = moved;
    s.census = census;
}
#endif

void TalusSolver::jacobi_gather(std::size_t begin, std::size_t end, ThreadScratch& s) {
    const AdjacencyGraph& g = *pass_.graph;
    const TalusArrays& a = *pass_.arrays;
    const std::uint32_t* target = g.targets().data();
    const std::uint32_t* offset = g.offsets().data();
    const std::uint32_t* degree = g.degrees().data();
    const RowWords* row_words = g.row_words().data();
    double* inflow = inflow_.data();
    double* out = out_.data();
    std::uint64_t* wake = s.wake.data();
    std::size_t lo = s.wake_lo, hi = s.wake_hi;
    for (std::size_t w = pass_.word_begin + begin; w < pass_.word_begin + end; ++w) {
        std::uint64_t bits = 0;
        for (ThreadScratch& t : scratch_) {
            bits |= t.receive[w];
            t.receive[w] = 0;
        }
        while (bits != 0) {
            const auto v = static_cast<std::uint32_t>(
                (w << 6) + static_cast<std::size_t>(std::countr_zero(bits)));
            bits &= bits - 1;
            const std::uint32_t row = offset[v];
            const std::uint32_t deg = degree[v];
            // In row order, as the definition sums (a neighbour that sent nothing left 0.0,
            // which changes no sum): the same value bit for bit.
            // 0.0 - 0.0 is +0.0: a vertex that sent nothing starts from the same +0.0 as ever.
            double delta = 0.0 - out[v];
            out[v] = 0.0;
            double* in = inflow + row;
            for (std::uint32_t k = 0; k < deg; ++k) {
                delta += in[k];
                in[k] = 0.0;
            }
            // When the sand ran out, h - (A (h - b)) / A can round to an ulp below b; the
            // thickness must never be negative, and an ulp of volume is far inside the drift
            // bound (the sequential schedule clamps the same way).
            const double h = a.height[v];
            const double nh = std::max(h + delta / a.area[v], a.bedrock[v]);
            if (nh != h) {
                a.height[v] = nh;  // in place: no other vertex reads v's height in this phase
                s.changed.push_back(v);
                mark(wake, v);
                widen_to_row(row_words, v, lo, hi);
                for (std::uint32_t k = row; k < row + deg; ++k)
                    mark(wake, target[k]);
            }
        }
    }
    s.wake_lo = lo;
    s.wake_hi = hi;
}

void TalusSolver::jacobi_age(std::size_t begin, std::size_t end, ThreadScratch& s) {
    ActiveSet& active = *pass_.active;
    std::uint64_t* member = active.bits_.data();
    std::uint8_t* quiet = active.quiet_.data();
    const int limit = settings_.quiet_iterations;
    for (std::size_t w = pass_.word_begin + begin; w < pass_.word_begin + end; ++w) {
        std::uint64_t woken = 0;
        for (ThreadScratch& t : scratch_) {
            woken |= t.wake[w];
            t.wake[w] = 0;
        }
        std::uint64_t bits = woken | member[w];
        std::uint64_t kept = 0;
        while (bits != 0) {
            const int b = std::countr_zero(bits);
            const std::uint64_t bit = std::uint64_t{1} << b;
            bits &= bits - 1;
            const auto v = static_cast<std::uint32_t>((w << 6) + static_cast<std::size_t>(b));
            // Woken: a fresh quiet count. Otherwise one more quiet iteration, and out after
            // `limit` of them (what ActiveSet::age followed by activate does, word by word).
            if ((woken & bit) != 0) {
                quiet[v] = 0;
            } else if (++quiet[v] >= limit) {
                continue;
            }
            kept |= bit;
            s.kept.push_back(v);
        }
        member[w] = kept;
    }
}

}  // namespace sandtin
