#pragma once
// State that lives across edits of one sculpting session: the stamp generation counter, the
// point-location hint along the tool path, and the simplification queue.

#include <cstddef>

#include "tin/tin.hpp"
#include "tools/simplifier.hpp"

namespace sandtin {

struct SculptSettings {
    SimplifySettings simplify;
    /// Remove redundant vertices at the end of every stamp, brush dab and pour.
    bool simplify_after_edit = true;
    /// Constraints of stamps more than this many generations old are released wherever that
    /// changes no triangle (their edges are Delaunay anyway); the rest go when a later stamp
    /// covers them.
    Generation keep_generations = 64;
    /// A stamp removes the sand its imprint replaces in bulk before enforcing its contours
    /// (tin/bulk_removal.hpp). Same result; off only to compare against the plain path.
    bool clear_before_imprint = true;
    /// ... when at least this many vertices qualify. Measured on the seeds' groove: at 10^5
    /// points (about 60 per stamp) clearing cost 7 % more CPU than the plain path, at 10^6
    /// (about 800) 30 % less.
    std::size_t min_bulk_clearing = 200;
    /// A stamp first constrains the bent edges, longer than the tool is wide, that inserting
    /// its rim would re-triangulate (Tin::fence_bent_edges), so on a coarse TIN it re-shapes
    /// nothing beyond its outer contour; brush dabs and pours fence the points they refine
    /// with (tools/refine.hpp). Off only to measure what that costs.
    bool fence_coarse_edges = true;
};

class SculptContext {
  public:
    SculptContext() = default;
    explicit SculptContext(const Rect& domain) {
        settings.simplify.tolerance = default_simplify_tolerance(domain);
    }

    /// The generation for the next stamp (increasing from 1).
    Generation next_generation() { return next_generation_++; }
    Generation peek_generation() const { return next_generation_; }
    /// Restores the counter from a session file.
    void set_next_generation(Generation g) { next_generation_ = g < 1 ? 1 : g; }

    SculptSettings settings;
    LocateHint hint;
    Simplifier simplifier;

  private:
    Generation next_generation_ = 1;
};

}  // namespace sandtin
