#include "physics/sand_physics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace sandtin {

namespace {

/// Spacing of the refinement lattice as a fraction of r_S: Delaunay edges between lattice
/// neighbours are s long, and those next to skipped points stay below about 1.3 s <= r_S.
constexpr double kLatticeSpacing = 0.75;
/// Largest displacement of a lattice point, as a fraction of the spacing: neighbours stay at
/// least (1 - 2 * 0.25) s apart.
constexpr double kLatticeJitter = 0.25;

}  // namespace

void PhysicsStepReport::accumulate(const PhysicsStepReport& o) {
    iterations += o.iterations;
    vertex_updates += o.vertex_updates;
    changed += o.changed;
    refined += o.refined;
    volume_moved += o.volume_moved;
    ms += o.ms;
    at_rest = o.at_rest;
}

SandPhysics::SandPhysics(Tin& tin, MaterialTable materials, TalusSettings settings,
                         VertexOrder order)
    : tin_(tin),
      materials_(std::move(materials)),
      solver_(settings),
      order_(order != VertexOrder::Auto              ? order
             : settings.schedule == Schedule::Jacobi ? VertexOrder::Strips
                                                     : VertexOrder::Tin),
      changes_(tin) {
    const VertexArrays& va = tin_.vertices();
    material_seen_.assign(va.material.begin(), va.material.end());
    moisture_seen_.assign(va.moisture.begin(), va.moisture.end());
    if (order_ == VertexOrder::Strips) {
        numbering_.assign_strips(tin_);
    } else {
        numbering_.assign_identity(tin_);
    }
    graph_.rebuild(tin_, &numbering_);
    grow_local();
}

void SandPhysics::load(std::uint32_t l) {
    const VertexArrays& va = tin_.vertices();
    const std::uint32_t t = numbering_.tin_id(l);
    const bool alive = t < va.size() && va.alive[t];
    height_[l] = alive ? va.height[t] : 0.0;
    tan_alpha_[l] = alive ? materials_.at(va.material[t]).talus_slope(va.moisture[t]) : 0.0;
    if (!numbering_.identity()) {
        area_[l] = alive ? va.lumped_area[t] : 0.0;
        bedrock_[l] = alive ? va.bedrock[t] : 0.0;
    }
}

void SandPhysics::grow_local() {
    const std::uint32_t n = numbering_.size();
    const auto old = static_cast<std::uint32_t>(height_.size());
    if (n <= old) return;
    height_.resize(n);
    tan_alpha_.resize(n);
    if (!numbering_.identity()) {
        area_.resize(n);
        bedrock_.resize(n);
    }
    for (std::uint32_t l = old; l < n; ++l)
        load(l);
}

TalusArrays SandPhysics::arrays() {
    const VertexArrays& va = tin_.vertices();
    if (numbering_.identity())
        return {height_.data(),    va.lumped_area.data(), va.bedrock.data(),
                tan_alpha_.data(), height_.size(),        nullptr};
    return {height_.data(),    area_.data(),   bedrock_.data(),
            tan_alpha_.data(), height_.size(), numbering_.tin_ids().data()};
}

void SandPhysics::number(std::span<const VertexId> vertices) {
    const VertexArrays& va = tin_.vertices();
    bool added = false;
    for (VertexId v : vertices) {
        if (v.value < va.size() && va.alive[v.value] &&
            numbering_.local(v.value) == VertexNumbering::kNone) {
            numbering_.add(v.value);
            added = true;
        }
    }
    if (added) grow_local();
}

void SandPhysics::apply_topology(std::span<const VertexId> topology) {
    if (topology.empty()) return;
    number(topology);
    graph_.update(tin_, topology, &numbering_);
}

bool SandPhysics::is_active(VertexId v) const {
    const std::uint32_t l = numbering_.local(v.value);
    return l != VertexNumbering::kNone && active_.contains(l);
}

void SandPhysics::renumber() {
    // Only sync() renumbers, and every sync() in a step follows a flush(): nothing is pending.
    if (!write_local_.empty()) throw std::logic_error("sand physics: renumbering with writes");
    const VertexNumbering old = numbering_;
    numbering_.assign_strips(tin_);
    const std::uint32_t n = numbering_.size();
    std::vector<std::uint32_t> new_id(old.size());
    for (std::uint32_t l = 0; l < old.size(); ++l)
        new_id[l] = numbering_.local(old.tin_id(l));
    // Heights and slopes move with their vertices (height_ may hold what the TIN has not been
    // given yet); area and bedrock are reloaded from the TIN.
    std::vector<double> height(n), tan_alpha(n);
    for (std::uint32_t l = 0; l < old.size(); ++l) {
        if (new_id[l] == VertexNumbering::kNone) continue;
        height[new_id[l]] = height_[l];
        tan_alpha[new_id[l]] = tan_alpha_[l];
    }
    height_ = std::move(height);
    tan_alpha_ = std::move(tan_alpha);
    area_.resize(n);
    bedrock_.resize(n);
    const VertexArrays& va = tin_.vertices();
    for (std::uint32_t l = 0; l < n; ++l) {
        area_[l] = va.lumped_area[numbering_.tin_id(l)];
        bedrock_[l] = va.bedrock[numbering_.tin_id(l)];
    }
    active_.renumber(new_id, VertexNumbering::kNone);
    graph_.rebuild(tin_, &numbering_);
    ++renumberings_;
}

SandPhysics::~SandPhysics() = default;

void SandPhysics::set_materials(MaterialTable materials) {
    materials_ = std::move(materials);
    const VertexArrays& va = tin_.vertices();
    for (std::size_t v = 0; v < va.size() && v < tan_alpha_.size(); ++v) {
        if (va.alive[v]) tan_alpha_[v] = materials_.at(va.material[v]).talus_slope(va.moisture[v]);
    }
    activate_all();
}

void SandPhysics::activate(std::span<const VertexId> vertices) {
    number(vertices);
    for (VertexId v : vertices) {
        if (tin_.is_alive(v)) active_.activate(numbering_.local(v.value));
    }
}

void SandPhysics::activate_all() {
    const VertexArrays& va = tin_.vertices();
    std::vector<VertexId> live;
    live.reserve(tin_.vertex_count());
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) live.push_back(VertexId{v});
    }
    number(live);
    for (VertexId v : live)
        active_.activate(numbering_.local(v.value));
}

void SandPhysics::sync() {
    const VertexChanges changes = changes_.take();
    const VertexArrays& va = tin_.vertices();
    if (material_seen_.size() < va.size()) {
        material_seen_.resize(va.size(), 0xFFFF);
        moisture_seen_.resize(va.size(), -1.0f);
    }
    apply_topology(changes.topology);
    const bool copies = !numbering_.identity();
    std::vector<std::uint32_t> died;     // local ids, leaving the active set in one batch
    std::vector<std::uint32_t> touched;  // local ids of live changed vertices
    auto refresh = [&](VertexId v) {
        const std::uint32_t l = numbering_.local(v.value);
        if (!va.alive[v.value]) {
            if (l != VertexNumbering::kNone) died.push_back(l);
            return;
        }
        height_[l] = va.height[v.value];
        if (copies) {
            area_[l] = va.lumped_area[v.value];  // changes with the star: in `topology`
            bedrock_[l] = va.bedrock[v.value];
        }
        // tan(repose) only when the material or moisture changed: heights change far more often.
        if (material_seen_[v.value] != va.material[v.value] ||
            moisture_seen_[v.value] != va.moisture[v.value]) {
            material_seen_[v.value] = va.material[v.value];
            moisture_seen_[v.value] = va.moisture[v.value];
            tan_alpha_[l] = materials_.at(va.material[v.value]).talus_slope(va.moisture[v.value]);
        }
        active_.activate(l);
        touched.push_back(l);
    };
    // A vertex whose attributes changed without its star is numbered already, unless it was
    // born before the last sync and never seen: number() covers that.
    number(changes.attributes);
    for (VertexId v : changes.attributes)
        refresh(v);
    for (VertexId v : changes.topology)
        refresh(v);
    // And their neighbours (as the GPU's activation does): a vertex an edit lowered, or whose
    // height a simplification shifted, steepens the edges from the neighbours above it, and only
    // those neighbours send sand down them. Measured: a groove stroke's last simplification left
    // edges 46 % steeper than repose beside vertices whose star it had not changed, and "until
    // rest" stopped with them still 4 % too steep.
    const std::uint32_t* target = graph_.targets().data();
    for (std::uint32_t l : touched) {
        const std::uint32_t row = graph_.offsets()[l];
        for (std::uint32_t k = row; k < row + graph_.degree(l); ++k)
            active_.activate(target[k]);
    }
    active_.remove(died);
    if (copies &&
        numbering_.appended() >= std::max<std::size_t>(kRenumberMinimum, numbering_.size() / 4))
        renumber();
}

std::size_t SandPhysics::refine(std::vector<std::uint32_t>& around) {
    if (around.empty()) return 0;
    const double rs = solver_.settings().parameters.relocation_radius;
    const VertexArrays& va = tin_.vertices();
    if (split_requested_.size() < va.size()) split_requested_.resize(va.size(), 0);
    const std::size_t before = tin_.vertex_count();
    // New vertices come from one hexagonal lattice of spacing s over the whole domain (seed 000
    // §7.2 puts them on the circle of radius r_S around each eroding vertex instead; done for
    // every vertex that meets sand, those circles and the fans of edges they leave towards far
    // vertices put new vertices a fraction of a millimetre apart (measured: 0.05 mm edges with
    // r_S = 1 cm), and the stiff, irregular graph then creeps towards rest thousands of times
    // slower). Lattice points are at least s apart, so the refined region is well shaped
    // whichever vertices asked first. Lattice points within s / 2 of a corner are skipped;
    // when that leaves an edge longer than r_S, it is bisected instead.
    const double s = kLatticeSpacing * rs;
    const double row = s * 0.8660254037844386;
    const Rect domain = tin_.domain();
    // A fixed pseudo-random jitter of each lattice point: a regular lattice has six edge
    // directions, and a pile resting on it is a hexagonal pyramid whose faces are steeper than
    // alpha between them (measured: the apex 4-5 % above the cone's, at any r_S).
    auto lattice_point = [&](long long i, long long j) {
        const auto key =
            static_cast<std::uint64_t>(i) * 0x100000001B3ull ^ static_cast<std::uint64_t>(j);
        const double shift = (j & 1) != 0 ? 0.5 * s : 0.0;
        return Vec2{domain.min.x + shift + static_cast<double>(i) * s +
                        kLatticeJitter * s * signed_unit_hash(0x5A17, key, 1),
                    domain.min.y + static_cast<double>(j) * row +
                        kLatticeJitter * s * signed_unit_hash(0x5A17, key, 2)};
    };
    std::vector<VertexId> ring;
    std::vector<Vec2> points;
    std::vector<EdgeSplit> bisect;
    for (std::uint32_t v : around) {
        if (v >= split_requested_.size() || split_requested_[v] || !va.alive[v]) continue;
        split_requested_[v] = 1;
        tin_.neighbours(VertexId{v}, ring);
        const Vec2 pv = va.position[v];
        points.clear();
        bool long_edge = false;
        for (std::size_t k = 0; k < ring.size(); ++k) {
            const Vec2 a = va.position[ring[k].value];
            const Vec2 b = va.position[ring[(k + 1) % ring.size()].value];
            long_edge = long_edge || distance(pv, a) > rs * (1.0 + 1e-9);
            // The fan triangle (v, a, b); the gap of a border vertex is not a triangle.
            if (!(cross(a - pv, b - pv) > 0.0)) continue;
            if (std::max(distance(pv, a), distance(pv, b)) <= rs * (1.0 + 1e-9)) continue;
            // Lattice points of the triangle within 1.5 r_S of v: enough for v's new
            // neighbours to be lattice-close, without filling a huge far triangle.
            const double reach = 1.5 * rs;
            const double x0 = std::max({std::min({pv.x, a.x, b.x}), pv.x - reach, domain.min.x});
            const double x1 = std::min({std::max({pv.x, a.x, b.x}), pv.x + reach, domain.max.x});
            const double y0 = std::max({std::min({pv.y, a.y, b.y}), pv.y - reach, domain.min.y});
            const double y1 = std::min({std::max({pv.y, a.y, b.y}), pv.y + reach, domain.max.y});
            const auto j0 = static_cast<long long>(std::ceil((y0 - domain.min.y) / row));
            const auto j1 = static_cast<long long>(std::floor((y1 - domain.min.y) / row));
            for (long long j = j0 - 1; j <= j1 + 1; ++j) {  // +-1: the jitter
                const double shift = (j & 1) != 0 ? 0.5 * s : 0.0;
                const auto i0 = static_cast<long long>(std::ceil((x0 - domain.min.x - shift) / s));
                const auto i1 = static_cast<long long>(std::floor((x1 - domain.min.x - shift) / s));
                for (long long i = i0 - 1; i <= i1 + 1; ++i) {
                    const Vec2 p = lattice_point(i, j);
                    if (distance(p, pv) > reach) continue;
                    // Strictly inside (v, a, b), and not crowding a corner.
                    if (!(cross(a - pv, p - pv) > 0.0 && cross(b - a, p - a) > 0.0 &&
                          cross(pv - b, p - b) > 0.0))
                        continue;
                    if (distance(p, pv) < 0.5 * s || distance(p, a) < 0.5 * s ||
                        distance(p, b) < 0.5 * s)
                        continue;
                    points.push_back(p);
                }
            }
        }
        if (!points.empty()) {
            // One call per vertex: the compensation for the Delaunay flips is shared by these
            // new vertices only, all within 1.5 r_S of v (a call over many piles would move
            // volume from a tall pile onto new vertices far away at another's toe).
            tin_.insert_points_on_surface(points, &hint_, VolumePolicy::Conserve);
        } else if (long_edge) {
            for (std::size_t k = 0; k < ring.size(); ++k) {
                if (distance(pv, va.position[ring[k].value]) > rs * (1.0 + 1e-9))
                    bisect.push_back({VertexId{v}, ring[k], 0.5});
            }
        }
    }
    for (std::uint32_t v : around) {
        if (v < split_requested_.size()) split_requested_[v] = 0;
    }
    around.clear();
    // One edge at a time, for the same reason as above. A long edge gets the lattice point
    // nearest its midpoint when that point lies well inside the edge's diametral circle (so
    // the edge will not stay Delaunay) and clear of both ends; the exact midpoint only
    // otherwise, or when the edge survived. Plain midpoints are off the lattice, the lattice
    // points next to them are then skipped as crowded, the holes leave edges longer than r_S,
    // and those were bisected again. Measured on the pile from two triangles: with r_S = 2 cm,
    // 2347 bisections against 807 lattice points and edges down to 0.3 mm; snapping to the
    // lattice took the iterations to rest from 35 935 to 12 498 (sequential) and from 25 508
    // to 9 817 (Jacobi), and with r_S = 1 cm from 103 487 to 53 866 and 119 791 to 60 656.
    std::vector<VertexId> ends;
    for (const EdgeSplit& e : bisect) {
        if (!tin_.is_alive(e.a) || !tin_.is_alive(e.b)) continue;
        const Vec2 pa = va.position[e.a.value];
        const Vec2 pb = va.position[e.b.value];
        const double len = distance(pa, pb);
        const Vec2 m = 0.5 * (pa + pb);
        const auto jm = static_cast<long long>(std::floor((m.y - domain.min.y) / row + 0.5));
        Vec2 best{};
        double best_d = 1e300;
        for (long long j = jm - 2; j <= jm + 2; ++j) {
            const double shift = (j & 1) != 0 ? 0.5 * s : 0.0;
            const auto im =
                static_cast<long long>(std::floor((m.x - domain.min.x - shift) / s + 0.5));
            for (long long i = im - 2; i <= im + 2; ++i) {
                const Vec2 p = lattice_point(i, j);
                if (distance(p, m) < best_d) {
                    best_d = distance(p, m);
                    best = p;
                }
            }
        }
        const bool inside = best.x > domain.min.x && best.x < domain.max.x &&
                            best.y > domain.min.y && best.y < domain.max.y;
        if (inside && best_d < 0.45 * len && distance(best, pa) > 0.5 * s &&
            distance(best, pb) > 0.5 * s) {
            const Vec2 one[] = {best};
            tin_.insert_points_on_surface(one, &hint_, VolumePolicy::Conserve);
            tin_.neighbours(e.a, ends);
            if (std::find(ends.begin(), ends.end(), e.b) == ends.end()) continue;
        }
        tin_.split_edges(std::span<const EdgeSplit>(&e, 1), VolumePolicy::Conserve);
    }
    return tin_.vertex_count() - before;
}

std::size_t SandPhysics::refine_around(std::span<const VertexId> vertices) {
    if (!(solver_.settings().parameters.relocation_radius > 0.0)) return 0;
    const double rs = solver_.settings().parameters.relocation_radius;
    std::size_t inserted = 0;
    // Bisection halves the longest edges each round, so this takes log2(longest / r_S) rounds.
    for (;;) {
        sync();
        std::vector<std::uint32_t> around;
        for (VertexId v : vertices) {
            if (tin_.is_alive(v) &&
                graph_.longest_edge(numbering_.local(v.value)) > rs * (1.0 + 1e-9))
                around.push_back(v.value);
        }
        const std::size_t added = refine(around);
        inserted += added;
        if (added == 0) break;
    }
    sync();
    return inserted;
}

void SandPhysics::flush(std::vector<VertexId>* changed_out) {
    if (write_local_.empty()) return;
    write_ids_.clear();
    write_values_.clear();
    for (std::uint32_t l : write_local_) {
        write_ids_.push_back(VertexId{numbering_.tin_id(l)});
        write_values_.push_back(height_[l]);
        write_pending_[l] = 0;
    }
    write_local_.clear();
    tin_.set_heights(write_ids_, write_values_);
    if (changed_out != nullptr)
        changed_out->insert(changed_out->end(), write_ids_.begin(), write_ids_.end());
    const VertexChanges echo = changes_.take();
    // set_heights changes attributes only; anything else would be an edit we must not drop.
    apply_topology(echo.topology);
}

PhysicsStepReport SandPhysics::step(int iterations, std::vector<VertexId>* changed_out) {
    PhysicsStepReport report;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::uint32_t> split_local, split_around;
    // Heights stay in height_ for the whole step: writing them into the TIN every iteration and
    // reading them back through the change journal cost about 12 % of the step
    // (physics-perf.md). They go into the TIN at the end and before refinement, which
    // interpolates the TIN's heights.
    sync();
    for (int it = 0; it < iterations; ++it) {
        if (active_.empty()) break;
        if (write_pending_.size() < height_.size()) write_pending_.resize(height_.size(), 0);
        const IterationStats stats = solver_.iterate(graph_, arrays(), active_, &split_local);
        ++report.iterations;
        report.vertex_updates += stats.processed;
        report.changed += stats.changed;
        report.volume_moved += stats.volume_moved;
        for (std::uint32_t l : solver_.changed()) {
            if (!write_pending_[l]) {
                write_pending_[l] = 1;
                write_local_.push_back(l);
            }
        }
        if (!split_local.empty()) {
            split_around.clear();
            for (std::uint32_t l : split_local)
                split_around.push_back(numbering_.tin_id(l));
            split_local.clear();
            // Jacobi reports them in the order of its (local) ids; refinement depends on the
            // order, so it gets them in TIN-id order, whatever the numbering. The sequential
            // schedule's order is its visiting order, the same in every numbering.
            if (solver_.settings().schedule == Schedule::Jacobi) {
                std::sort(split_around.begin(), split_around.end());
                split_around.erase(std::unique(split_around.begin(), split_around.end()),
                                   split_around.end());
            }
            flush(changed_out);
            report.refined += refine(split_around);
            sync();
        }
    }
    flush(changed_out);
    sync();
    report.at_rest = active_.empty();
    report.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

PhysicsStepReport SandPhysics::run_to_rest(int max_iterations, std::vector<VertexId>* changed) {
    PhysicsStepReport total;
    constexpr int kChunk = 64;
    while (total.iterations < max_iterations) {
        const PhysicsStepReport r =
            step(std::min(kChunk, max_iterations - total.iterations), changed);
        total.accumulate(r);
        if (r.at_rest || r.iterations == 0) break;
    }
    total.at_rest = active_.empty();
    return total;
}

}  // namespace sandtin
