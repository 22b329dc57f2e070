#include "physics/talus_solver.hpp"

#include <algorithm>
#include <memory>

namespace sandtin {

TalusSolver::TalusSolver(TalusSettings settings) : settings_(settings) {
    pool_ = std::make_unique<ThreadPool>(std::max(1, settings_.threads));
}

double TalusSolver::random_factor(std::uint32_t v) const {
    if (settings_.randomness <= 0.0) return 1.0;
    return 1.0 + settings_.randomness * signed_unit_hash(settings_.seed, v, iteration_);
}

void TalusSolver::ensure(const AdjacencyGraph& g, std::size_t vertices) {
    if (q_.size() < g.slot_count()) q_.resize(g.slot_count(), 0.0);
    if (out_.size() < vertices) {
        out_.resize(vertices, 0.0);
        new_height_.resize(vertices, 0.0);
        source_.resize(vertices, 0);
        receiver_flag_.resize(vertices, 0);
        changed_.resize(vertices, 0);
    }
    if (pool_->threads() != std::max(1, settings_.threads)) {
        pool_ = std::make_unique<ThreadPool>(std::max(1, settings_.threads));
    }
    split_per_thread_.resize(static_cast<std::size_t>(pool_->threads()));
    moved_per_thread_.assign(static_cast<std::size_t>(pool_->threads()), 0.0);
}

IterationStats TalusSolver::iterate(const AdjacencyGraph& graph, const TalusArrays& arrays,
                                    ActiveSet& active, std::vector<std::uint32_t>* split_around) {
    for (std::uint32_t v : changed_list_)
        changed_[v] = 0;
    changed_list_.clear();
    if (active.empty()) return {};
    ensure(graph, std::max<std::size_t>(arrays.size, graph.vertex_capacity()));
    const IterationStats stats = settings_.schedule == Schedule::Sequential
                                     ? sequential(graph, arrays, active, split_around)
                                     : jacobi(graph, arrays, active, split_around);
    // Changed vertices and their neighbours may now have excess.
    active.age(changed_, settings_.quiet_iterations);
    for (std::uint32_t v : changed_list_) {
        active.activate(v);
        const std::uint32_t b = graph.offset(v);
        for (std::uint32_t k = b; k < b + graph.degree(v); ++k)
            active.activate(graph.targets()[k]);
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
    double* q = q_.data();
    for (std::uint32_t i : active.list()) {
        const std::uint32_t begin = g.offset(i);
        const std::uint32_t degree = g.degree(i);
        if (degree == 0) continue;
        ++stats.processed;
        const double sent = talus_outflow(i, begin, degree, target, length, longest, a.height,
                                          a.area, a.bedrock, a.tan_alpha[i], settings_.parameters,
                                          random_factor(i), q, [&](std::uint32_t v) {
                                              if (split_around != nullptr)
                                                  split_around->push_back(v);
                                          });
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
        for (std::uint32_t k = begin; k < begin + degree; ++k) {
            if (q[k] > 0.0) {
                a.height[target[k]] += q[k] / a.area[target[k]];
                mark(target[k]);
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
    const std::uint32_t* target = g.targets().data();
    const std::uint32_t* reverse = g.reverses().data();
    const double* length = g.lengths().data();
    const double* longest = g.longest_edges().data();
    double* q = q_.data();
    const std::vector<std::uint32_t>& list = active.list();
    for (auto& l : split_per_thread_)
        l.clear();
    std::fill(moved_per_thread_.begin(), moved_per_thread_.end(), 0.0);
    const bool threaded = list.size() >= 2048;
    auto run = [&](std::size_t n, const std::function<void(std::size_t, std::size_t, int)>& body) {
        if (threaded) {
            pool_->parallel_for(n, body);
        } else {
            body(0, n, 0);
        }
    };

    // Phase 1: outflow of every active vertex along each of its edges, from the old heights.
    run(list.size(), [&](std::size_t b, std::size_t e, int t) {
        auto& splits = split_per_thread_[static_cast<std::size_t>(t)];
        double moved = 0.0;
        for (std::size_t idx = b; idx < e; ++idx) {
            const std::uint32_t i = list[idx];
            const std::uint32_t begin = g.offset(i);
            const std::uint32_t degree = g.degree(i);
            out_[i] = degree == 0 ? 0.0
                                  : talus_outflow(i, begin, degree, target, length, longest,
                                                  a.height, a.area, a.bedrock, a.tan_alpha[i],
                                                  settings_.parameters, random_factor(i), q,
                                                  [&](std::uint32_t v) { splits.push_back(v); });
            source_[i] = 1;
            moved += out_[i];
        }
        moved_per_thread_[static_cast<std::size_t>(t)] = moved;
    });
    for (double m : moved_per_thread_)
        stats.volume_moved += m;
    stats.processed = list.size();
    if (split_around != nullptr) {
        for (const auto& l : split_per_thread_)
            split_around->insert(split_around->end(), l.begin(), l.end());
    }

    // The receivers: every source and its neighbours.
    receivers_.clear();
    auto add = [&](std::uint32_t v) {
        if (!receiver_flag_[v]) {
            receiver_flag_[v] = 1;
            receivers_.push_back(v);
        }
    };
    for (std::uint32_t i : list) {
        if (out_[i] <= 0.0) continue;
        add(i);
        const std::uint32_t begin = g.offset(i);
        for (std::uint32_t k = begin; k < begin + g.degree(i); ++k)
            add(target[k]);
    }

    // Phase 2: each receiver gathers, in its row order, what its source neighbours sent.
    run(receivers_.size(), [&](std::size_t b, std::size_t e, int) {
        for (std::size_t idx = b; idx < e; ++idx) {
            const std::uint32_t v = receivers_[idx];
            double delta = source_[v] ? -out_[v] : 0.0;
            const std::uint32_t begin = g.offset(v);
            for (std::uint32_t k = begin; k < begin + g.degree(v); ++k) {
                const std::uint32_t w = target[k];
                if (source_[w]) delta += q[reverse[k]];
            }
            // Clamped for the same rounding reason as in the sequential schedule.
            new_height_[v] = std::max(a.height[v] + delta / a.area[v], a.bedrock[v]);
        }
    });
    for (std::uint32_t v : receivers_) {
        receiver_flag_[v] = 0;
        if (new_height_[v] != a.height[v]) {
            a.height[v] = new_height_[v];
            changed_[v] = 1;
            changed_list_.push_back(v);
        }
    }
    for (std::uint32_t i : list)
        source_[i] = 0;
    stats.changed = changed_list_.size();
    return stats;
}

}  // namespace sandtin
