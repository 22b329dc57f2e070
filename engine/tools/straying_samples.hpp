#pragma once
// Detail where a curved tool needs it. A mesh, heightfield or ball profile is sampled on a
// lattice inside I, and the terrain must follow it there. Inserting every lattice point (the
// simplifier then removed nine in ten again: on the foot, 5 000 insertions and removals per
// stamp) costs the same on a trail already pressed to the profile as on fresh sand. Instead,
// points go in only where the surface strays from their target height, coarse to fine, so a
// coarse pass carries the smooth parts of the profile and finer points land only where it
// curves.

#include <span>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin {

/// Inserts, at its target height, each sample where the surface strays from the target by
/// more than `tolerance` (m; plus a few ulps of the heights, which interpolation at a vertex
/// can round away). Samples are visited in passes over every 64th, 16th, 4th and
/// finally every one (in the order given: a lattice in row order spreads each pass over the
/// whole region); the full pass repeats until it inserts nothing, each repeat over only the
/// samples whose triangle changed (a corner's height or star), since the others' heights
/// cannot have moved. On return the surface lies
/// within the tolerance of every finite target whose sample is in the domain (unless two
/// samples share a position but not a target: the full pass runs at most 8 times). Returns the
/// inserted vertices in insertion order; a sample exactly on a vertex sets that vertex's height.
/// Throws std::invalid_argument when the spans differ in size or the tolerance is negative.
std::vector<VertexId> insert_straying_samples(Tin& tin, std::span<const Vec2> samples,
                                              std::span<const double> targets, double tolerance,
                                              LocateHint* hint, EditReport* edit);

}  // namespace sandtin
