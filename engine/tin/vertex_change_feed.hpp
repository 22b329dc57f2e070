#pragma once
// A change channel of a Tin (Tin::subscribe_vertex_changes) held for the lifetime of its owner:
// opened on construction, closed on destruction, exceptions included. The physics, the undo
// recorder and the curved tools' sampling each keep one.

#include <cstdint>

#include "tin/tin.hpp"

namespace sandtin {

class VertexChangeFeed {
  public:
    /// `tin` must outlive the feed.
    explicit VertexChangeFeed(Tin& tin) : tin_(tin), id_(tin.subscribe_vertex_changes()) {}
    ~VertexChangeFeed() { tin_.unsubscribe_vertex_changes(id_); }
    VertexChangeFeed(const VertexChangeFeed&) = delete;
    VertexChangeFeed& operator=(const VertexChangeFeed&) = delete;

    /// The vertices that changed since the last take() (or since construction).
    VertexChanges take() { return tin_.take_vertex_changes(id_); }

  private:
    Tin& tin_;
    std::uint32_t id_;
};

}  // namespace sandtin
