#pragma once
// Private to engine/tin: the bookkeeping every edit ends with. An edit runs CGAL inside an
// EventScope, which records the vertices born and died and the slots touched; EditFinisher then
// turns those events into the slot cache, lumped areas, journal and volume updates.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "tin/change_journal.hpp"
#include "tin/detail/cgal_tin.hpp"
#include "tin/tin.hpp"
#include "util/compensated_sum.hpp"

namespace sandtin::detail {

/// Bookkeeping shared by all edits: turns the CGAL events of one edit into attribute, area,
/// journal and volume updates.
class EditFinisher {
  public:
    explicit EditFinisher(Tin::Impl& impl) : impl_(impl) {}

    void mark_vertex(std::uint32_t id) { impl_.note_attribute(id); }

    /// Gives the vertices CGAL created in this edit their position and default attributes.
    /// Their heights are NaN until the edit resolves them. Batch edits call it once per inserted
    /// point, so it resumes where it stopped instead of rescanning the whole batch.
    void prepare_born();

    /// Attributes of a new vertex from weighted existing vertices: moisture and bedrock are
    /// interpolated, the material and texture offset come from the heaviest source.
    void inherit(std::uint32_t id, std::span<const std::uint32_t> sources,
                 std::span<const double> weights);

    /// Completes the edit: slot cache, lumped areas, journal, volume accounting and, with
    /// VolumePolicy::Conserve, compensation: a uniform height shift of the `absorb` vertices
    /// when given (new vertices of an insertion), else of all re-triangulated vertices.
    void finish(VolumePolicy policy, std::span<const std::uint32_t> absorb, EditReport* report);

  private:
    /// The steps of finish(), in order.
    void update_slots(EditReport& local);
    void retire_dead(CompensatedSum& dv, EditReport& local);
    void welcome_born(EditReport& local);
    void update_lumped_areas(VolumePolicy policy, CompensatedSum& dv);
    void level_slivers(std::uint32_t id, bool take_neighbour, VolumePolicy policy,
                       double& net_change);
    void end_edit();

    double shift_to_conserve(std::span<const std::uint32_t> ids, double volume, double& net_change);
    void clamp_bedrock(std::uint32_t id);
    void resolve_height_from_neighbours(std::uint32_t id);

    Tin::Impl& impl_;
    std::size_t prepared_born_ = 0;  ///< born_vertices[0, prepared_born_) are initialised
    static thread_local DirtySet affected_;
    static thread_local std::vector<std::uint32_t> near_snapped_;
    static thread_local std::vector<std::uint8_t> shift_floor_;  ///< shift_to_conserve's
};

}  // namespace sandtin::detail
