#include "tin/detail/journal_readers.hpp"

#include <algorithm>
#include <limits>

namespace sandtin::detail {

std::uint32_t JournalReaders::open_range_reader(bool starts_full) {
    auto it = std::find_if(range_readers_.begin(), range_readers_.end(),
                           [](const RangeReader& r) { return !r.open; });
    if (it == range_readers_.end()) it = range_readers_.emplace(range_readers_.end());
    it->open = true;
    it->full = starts_full;
    it->seen_epoch = epoch_;  // deaths before it opened are none of its business
    ++open_range_readers_;
    return static_cast<std::uint32_t>(it - range_readers_.begin());
}

void JournalReaders::close_range_reader(std::uint32_t reader) {
    if (!is_open(reader)) return;
    RangeReader& r = range_readers_[reader];
    r.open = false;
    r.full = false;
    r.vertices.clear();
    r.slots.clear();
    --open_range_readers_;
}

bool JournalReaders::is_open(std::uint32_t reader) const {
    return reader < range_readers_.size() && range_readers_[reader].open;
}

JournalReaders::Taken JournalReaders::take(std::uint32_t reader, std::size_t pending_vertices,
                                           std::size_t pending_slots) {
    Taken out;
    if (!is_open(reader)) return out;
    RangeReader& r = range_readers_[reader];
    out.everything = r.full;
    r.full = false;
    if (out.everything) {
        r.vertices.clear();
        r.slots.clear();
    } else {
        out.vertices = r.vertices.take();
        out.slots = r.slots.take();
    }
    // Every death pending now was marked in this reader (or it reports everything).
    ++epoch_;
    r.seen_epoch = epoch_;
    if (pending_vertices > 0 || pending_slots > 0)
        checkpoints_.push_back(Checkpoint{epoch_, pending_vertices, pending_slots});
    return out;
}

JournalReaders::Recyclable JournalReaders::recyclable(std::size_t pending_vertices,
                                                      std::size_t pending_slots) const {
    if (open_range_readers_ == 0) return Recyclable{pending_vertices, pending_slots};
    std::uint64_t oldest = std::numeric_limits<std::uint64_t>::max();
    for (const RangeReader& r : range_readers_)
        if (r.open) oldest = std::min(oldest, r.seen_epoch);
    Recyclable out;
    for (const Checkpoint& c : checkpoints_) {
        if (c.epoch > oldest) break;
        out = Recyclable{c.vertices, c.slots};  // the counts only grow along the checkpoints
    }
    out.vertices = std::min(out.vertices, pending_vertices);
    out.slots = std::min(out.slots, pending_slots);
    return out;
}

void JournalReaders::recycled(Recyclable counts) {
    for (Checkpoint& c : checkpoints_) {
        c.vertices -= std::min(c.vertices, counts.vertices);
        c.slots -= std::min(c.slots, counts.slots);
    }
    while (!checkpoints_.empty() && checkpoints_.front().vertices == 0 &&
           checkpoints_.front().slots == 0)
        checkpoints_.pop_front();
}

std::uint32_t JournalReaders::subscribe_vertex_feed() {
    auto it =
        std::find_if(feeds_.begin(), feeds_.end(), [](const VertexFeed& f) { return !f.open; });
    if (it == feeds_.end()) it = feeds_.emplace(feeds_.end());
    it->open = true;
    return static_cast<std::uint32_t>(it - feeds_.begin());
}

void JournalReaders::unsubscribe_vertex_feed(std::uint32_t feed) {
    if (feed >= feeds_.size()) return;
    VertexFeed& f = feeds_[feed];
    f.open = false;
    f.attributes.clear();
    f.topology.clear();
}

std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> JournalReaders::take_vertex_feed(
    std::uint32_t feed) {
    if (feed >= feeds_.size() || !feeds_[feed].open) return {};
    return {feeds_[feed].attributes.take(), feeds_[feed].topology.take()};
}

}  // namespace sandtin::detail
