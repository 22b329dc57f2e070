#pragma once
// The change journal's readers. Each consumer of a Tin's changes reads from a cursor of its
// own, so none takes changes away from another:
//   - range readers (Tin::open_change_reader, ChangeReader): dirty vertex ids and triangle
//     slots, for consumers that copy the TIN (the render mesh, the GPU mirror, the normal map);
//     reader 0 is the TIN's default reader (TinOptions::track_changes, Tin::take_changes());
//   - vertex feeds (Tin::subscribe_vertex_changes, VertexChangeFeed): vertices whose attributes
//     or star changed, for consumers that follow vertices (the physics, the undo recorder).
//
// A dead id or slot is recycled only once every open range reader has taken the change that
// reported its death, so no range reader ever sees an id die and be reborn between two of its
// takes. The rule is kept with checkpoints: each take is an epoch, and records how many deaths
// were pending then; once the oldest reader's last take is at or past a checkpoint, its deaths
// are recyclable. Vertex feeds never delay recycling (a reported id only means "look again").

#include <cstdint>
#include <deque>
#include <vector>

#include "tin/change_journal.hpp"

namespace sandtin::detail {

class JournalReaders {
  public:
    /// Opens a range reader; its first take reports everything (ids and slots below the given
    /// capacities) when `starts_full`, else only what changes from now on.
    std::uint32_t open_range_reader(bool starts_full);
    void close_range_reader(std::uint32_t reader);
    bool is_open(std::uint32_t reader) const;
    bool has_range_readers() const { return open_range_readers_ > 0; }

    /// What one reader takes: the dirty ids and slots (unsorted), or everything.
    struct Taken {
        std::vector<std::uint32_t> vertices;
        std::vector<std::uint32_t> slots;
        bool everything = false;
    };
    /// Takes the reader's changes and starts a new epoch. `pending_vertices` and
    /// `pending_slots` are the deaths waiting to be recycled now.
    Taken take(std::uint32_t reader, std::size_t pending_vertices, std::size_t pending_slots);

    /// How many of the oldest pending deaths every open range reader has now seen (all of
    /// them when no range reader is open). The caller recycles that many and then calls
    /// recycled() with the same counts.
    struct Recyclable {
        std::size_t vertices = 0;
        std::size_t slots = 0;
    };
    Recyclable recyclable(std::size_t pending_vertices, std::size_t pending_slots) const;
    void recycled(Recyclable counts);

    std::uint32_t subscribe_vertex_feed();
    void unsubscribe_vertex_feed(std::uint32_t feed);
    /// Attribute and topology changes of the feed since its last take (unsorted ids).
    std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> take_vertex_feed(
        std::uint32_t feed);

    /// A vertex's height or another attribute changed (or it was born or died).
    void note_vertex(std::uint32_t id) {
        for (RangeReader& r : range_readers_)
            if (r.open) r.vertices.mark(id);
        for (VertexFeed& f : feeds_)
            if (f.open) f.attributes.mark(id);
    }
    /// A vertex's star (its triangles or neighbours) changed.
    void note_topology(std::uint32_t id) {
        for (VertexFeed& f : feeds_)
            if (f.open) f.topology.mark(id);
    }
    /// Every vertex and slot is new (a terrain just built or restored): each open range reader
    /// reports everything at its next take, without an id-by-id list. False, noting nothing,
    /// while a vertex feed is open (feeds have no such state): then note each id.
    bool note_everything() {
        for (const VertexFeed& f : feeds_)
            if (f.open) return false;
        for (RangeReader& r : range_readers_)
            if (r.open) r.full = true;
        return true;
    }
    /// A triangle slot was born, died, re-pointed or re-flagged.
    void note_slot(std::uint32_t slot) {
        for (RangeReader& r : range_readers_)
            if (r.open) r.slots.mark(slot);
    }

  private:
    struct RangeReader {
        bool open = false;
        bool full = false;  ///< the next take reports everything
        std::uint64_t seen_epoch = 0;
        DirtySet vertices;
        DirtySet slots;
    };
    struct VertexFeed {
        bool open = false;
        DirtySet attributes;
        DirtySet topology;
    };
    struct Checkpoint {
        std::uint64_t epoch = 0;
        std::size_t vertices = 0;  ///< deaths pending at that take, oldest first
        std::size_t slots = 0;
    };

    std::vector<RangeReader> range_readers_;
    std::uint32_t open_range_readers_ = 0;
    std::vector<VertexFeed> feeds_;
    std::uint64_t epoch_ = 0;
    std::deque<Checkpoint> checkpoints_;
};

}  // namespace sandtin::detail
