#pragma once
// A lock-free triple buffer: one writer thread publishes whole values, one reader thread takes
// the latest one. Neither side ever waits for the other (wait-free), and the reader never sees
// a value that is being written. The simulation publishes haptic snapshots through one of these
// and the force loop publishes device samples back through another.
//
// Three slots: the writer owns one ("back"), the reader owns one ("front"), and the third sits
// in `middle_` together with a "fresh" bit. Publishing swaps back and middle and sets the bit;
// update() on the reader side swaps front and middle when the bit is set. The acquire/release
// exchanges carry the written bytes from writer to reader.

#include <array>
#include <atomic>
#include <cstdint>
#include <type_traits>

namespace sandtin::haptics {

template <typename T>
class TripleBuffer {
    static_assert(std::is_trivially_copyable_v<T>, "published values are copied bytewise");

  public:
    TripleBuffer() = default;
    explicit TripleBuffer(const T& initial) { slots_.fill(initial); }
    TripleBuffer(const TripleBuffer&) = delete;
    TripleBuffer& operator=(const TripleBuffer&) = delete;

    // ---- Writer thread only ----
    /// The slot to fill before publish().
    T& back() { return slots_[back_]; }
    /// Makes back() the latest value.
    void publish() {
        const std::uint32_t old = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel);
        back_ = old & kIndexMask;
    }
    void write(const T& value) {
        back() = value;
        publish();
    }

    // ---- Reader thread only ----
    /// Takes the latest published value if there is a newer one; returns whether it did.
    bool update() {
        if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
        const std::uint32_t old = middle_.exchange(front_, std::memory_order_acq_rel);
        front_ = old & kIndexMask;
        return true;
    }
    /// The value taken by the last update() (the initial value before any).
    const T& front() const { return slots_[front_]; }

  private:
    static constexpr std::uint32_t kFresh = 4;
    static constexpr std::uint32_t kIndexMask = 3;

    std::array<T, 3> slots_{};
    std::uint32_t back_ = 0;                // writer's slot
    std::atomic<std::uint32_t> middle_{1};  // shared slot index | kFresh
    std::uint32_t front_ = 2;               // reader's slot
};

}  // namespace sandtin::haptics
