#pragma once
// A range reader of a Tin's change journal (Tin::open_change_reader) held for the lifetime of its
// owner: opened on construction, closed on destruction, exceptions included. Each consumer that
// copies the TIN keeps one (the render mesh, the GPU mirror, the normal map), so what one takes
// is never taken from another. Its first take reports everything.

#include <cstdint>

#include "tin/tin.hpp"

namespace sandtin {

class ChangeReader {
  public:
    /// `tin` must outlive the reader and stay where it is (a reader holds its address).
    explicit ChangeReader(Tin& tin) : tin_(tin), id_(tin.open_change_reader()) {}
    ~ChangeReader() { tin_.close_change_reader(id_); }
    ChangeReader(const ChangeReader&) = delete;
    ChangeReader& operator=(const ChangeReader&) = delete;

    /// What changed since this reader's previous take (everything, the first time).
    ChangeSet take() { return tin_.take_changes(id_); }
    Tin& tin() const { return tin_; }

  private:
    Tin& tin_;
    std::uint32_t id_;
};

}  // namespace sandtin
