// util/prepare_for_writing.hpp: a hint that must never change the bytes it is given, a reserve
// that keeps growth amortised, and zero-filled growth.

#include "util/prepare_for_writing.hpp"

#include <gtest/gtest.h>
#include <algorithm>

#include <cstdint>
#include <vector>

namespace sandtin {
namespace {

std::vector<std::uint64_t> pattern(std::size_t n) {
    std::vector<std::uint64_t> v(n);
    for (std::size_t i = 0; i < n; ++i)
        v[i] = (i + 1) * 0x9E3779B97F4A7C15ull;
    return v;
}

TEST(PrepareForWriting, KeepsTheBytesOfMemoryAlreadyWritten) {
    // 16 MB, past the 2 MiB threshold: the hints run. Memory the process has written must
    // read back the same (MADV_DONTNEED or MADV_FREE in their place would zero it).
    const std::size_t n = std::size_t{2} << 20;
    std::vector<std::uint64_t> v = pattern(n);
    const std::vector<std::uint64_t> expected = v;
    prepare_for_writing(v.data(), v.size() * sizeof(std::uint64_t));
    EXPECT_EQ(v, expected);
    // An unaligned part of it: only whole pages inside are hinted, the bytes around unchanged.
    auto* bytes = reinterpret_cast<unsigned char*>(v.data());
    prepare_for_writing(bytes + 3, v.size() * sizeof(std::uint64_t) - 7);
    EXPECT_EQ(v, expected);
}

TEST(PrepareForWriting, SmallOrEmptyRegionsAreLeftAlone) {
    std::vector<std::uint64_t> v = pattern(1000);
    const std::vector<std::uint64_t> expected = v;
    prepare_for_writing(v.data(), v.size() * sizeof(std::uint64_t));
    prepare_for_writing(nullptr, std::size_t{1} << 30);
    prepare_for_writing(v.data(), 0);
    EXPECT_EQ(v, expected);
}

TEST(ReserveForWriting, AnEmptyVectorGetsWhatWasAskedAndKeepsNothingElse) {
    std::vector<double> v;
    reserve_for_writing(v, 5'000'000);
    EXPECT_GE(v.capacity(), 5'000'000u);
    EXPECT_LT(v.capacity(), 5'000'000u + 5'000'000u / 4);  // not a doubling of nothing
    EXPECT_TRUE(v.empty());
}

TEST(ReserveForWriting, GrowingOneStepAtATimeReallocatesLogarithmically) {
    // Each call asks for one more element, as VertexArrays::resize does while a terrain grows
    // vertex by vertex: exact reserves would copy the array at every step (quadratic time).
    std::vector<std::uint32_t> v;
    int reallocations = 0;
    const std::uint32_t* data = nullptr;
    for (std::uint32_t i = 0; i < 200'000; ++i) {
        reserve_for_writing(v, v.size() + 1);
        v.push_back(i);
        if (v.data() != data) {
            ++reallocations;
            data = v.data();
        }
    }
    EXPECT_LE(reallocations, 20);  // log2(200 000) = 17.6
    for (std::uint32_t i = 0; i < v.size(); ++i)
        ASSERT_EQ(v[i], i);
}

TEST(GrowZeroFilled, GrowsToZerosKeepingWhatWasThereAndNeverShrinks) {
    // The walks' scratch arrays: a few marks set, then sized to a 3·10⁶-slot terrain at once
    // (12 MB, past the size where the storage is prepared), then asked for less.
    std::vector<std::uint32_t> marks(10);
    for (std::uint32_t i = 0; i < marks.size(); ++i)
        marks[i] = 7 * i + 1;
    grow_zero_filled(marks, 3'000'000);
    ASSERT_EQ(marks.size(), 3'000'000u);
    for (std::uint32_t i = 0; i < 10; ++i)
        EXPECT_EQ(marks[i], 7 * i + 1);
    EXPECT_EQ(std::count(marks.begin() + 10, marks.end(), 0u), 3'000'000 - 10);
    grow_zero_filled(marks, 5);
    EXPECT_EQ(marks.size(), 3'000'000u);
    EXPECT_EQ(marks[9], 64u);
    // Growing step by step reallocates logarithmically, as push_back does.
    std::vector<std::uint8_t> flags;
    int reallocations = 0;
    const std::uint8_t* data = nullptr;
    for (std::size_t n = 1; n <= 100'000; ++n) {
        grow_zero_filled(flags, n);
        flags[n - 1] = static_cast<std::uint8_t>(n & 0x7F);
        if (flags.data() != data) {
            ++reallocations;
            data = flags.data();
        }
    }
    EXPECT_LE(reallocations, 20);
    for (std::size_t n = 1; n <= flags.size(); ++n)
        ASSERT_EQ(flags[n - 1], static_cast<std::uint8_t>(n & 0x7F));
}

}  // namespace
}  // namespace sandtin
