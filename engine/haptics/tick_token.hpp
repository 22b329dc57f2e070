#pragma once
// Who runs the next haptic tick, and whether the loop is over, in one atomic word.
//
// The force loop may run a backup thread that races the primary for every tick (it takes a
// tick whose owner woke late). Both threads read the token, wait for the tick's deadline and
// try to claim it; exactly one claim of each tick number succeeds. The end of the loop lives in
// the same word as the tick number: with a separate "finished" flag, a thread that read the flag
// just before the last tick ended and the token just after could claim a tick past the end and
// read a lost device again (seen once in a CI sanitizer run).
//
// Invariant: claims succeed only on the exact word a thread saw, that word is neither owned nor
// finished, and a finished token is never claimed again until reset().

#include <atomic>
#include <cstdint>

namespace sandtin::haptics {

class TickToken {
  public:
    /// One reading of the token.
    struct Seen {
        std::uint64_t word = 0;
        std::uint64_t tick() const { return word & kTickMask; }
        bool owned() const { return (word & kOwned) != 0; }
        bool finished() const { return (word & kFinished) != 0; }
    };

    /// Back to tick 0, unowned, not finished. Only while no thread uses the token.
    void reset() { word_.store(0, std::memory_order_release); }

    Seen load() const { return {word_.load(std::memory_order_acquire)}; }

    /// Claims the tick `observed` names if the token has not changed since: false when the other
    /// thread claimed it, ran it or ended the loop meanwhile (or `observed` was owned or
    /// finished).
    bool try_claim(Seen observed) {
        if (observed.owned() || observed.finished()) return false;
        std::uint64_t expected = observed.word;
        return word_.compare_exchange_strong(expected, observed.word | kOwned,
                                             std::memory_order_acq_rel);
    }

    /// By the claimant after running tick `tick`: hands over the next tick, or ends the loop.
    /// Everything the tick wrote before (the next deadline) is visible to the next claimant.
    void release(std::uint64_t tick, bool last) {
        word_.store(last ? (tick + 1) | kFinished : tick + 1, std::memory_order_release);
    }

  private:
    static constexpr std::uint64_t kOwned = std::uint64_t{1} << 63;
    static constexpr std::uint64_t kFinished = std::uint64_t{1} << 62;
    static constexpr std::uint64_t kTickMask = kFinished - 1;

    std::atomic<std::uint64_t> word_{0};
};

}  // namespace sandtin::haptics
