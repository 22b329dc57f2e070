#pragma once
// Drops datagrams that arrive late or twice: a packet is accepted only when its sequence is
// newer than the last accepted one in serial-number arithmetic (RFC 1982 style, 32 bits), so
// the counter may wrap. The first packet is always accepted.

#include <cstdint>

namespace sandtin::haptics {

class SequenceFilter {
  public:
    bool accept(std::uint32_t sequence) {
        if (has_last_ && static_cast<std::int32_t>(sequence - last_) <= 0) {
            ++dropped_;
            return false;
        }
        has_last_ = true;
        last_ = sequence;
        ++accepted_;
        return true;
    }
    std::uint32_t last() const { return last_; }
    bool has_last() const { return has_last_; }
    std::uint64_t accepted() const { return accepted_; }
    std::uint64_t dropped() const { return dropped_; }
    void reset() { *this = SequenceFilter{}; }

  private:
    bool has_last_ = false;
    std::uint32_t last_ = 0;
    std::uint64_t accepted_ = 0;
    std::uint64_t dropped_ = 0;
};

}  // namespace sandtin::haptics
