// The staging ring (gpu/staging_ring.hpp): every byte queued reaches its destination, whatever
// the sizes, alignments and flushes. The case that once threw "no space although nothing is in
// flight" in the editor: the ring entirely free after a batch that ended unaligned near its
// end, then an upload larger than the room left before the wrap.

#include <cstdint>
#include <random>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/staging_ring.hpp"
#include "gpu_fixture.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;

constexpr VkDeviceSize kRing = 64 * 1024;
constexpr VkDeviceSize kTarget = 512 * 1024;

/// Bytes of a pattern that differs for every (seed, index).
std::vector<unsigned char> pattern(std::size_t n, std::uint32_t seed) {
    std::vector<unsigned char> out(n);
    for (std::size_t i = 0; i < n; ++i)
        out[i] = static_cast<unsigned char>((i * 2654435761u + seed * 40503u) >> 13);
    return out;
}

class StagingRingTest : public GpuTest {
  protected:
    Buffer target() {
        return Buffer(ctx(), kTarget,
                      VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                      MemoryUse::Device);
    }
};

TEST_F(StagingRingTest, AnUploadAfterAnUnalignedBatchNearTheEndOfAnIdleRingLands) {
    StagingRing ring(ctx(), kRing);
    Buffer dst = target();
    // A batch that ends 13 bytes past a 16-byte boundary, 1 997 bytes before the ring's end;
    // retired; then 5 000 bytes, more than the 1 984 left before the wrap.
    const std::vector<unsigned char> a = pattern(kRing - 1997, 1);
    ring.upload(dst.get(), 0, a.data(), a.size());
    ring.flush();
    ring.wait_idle();
    const std::vector<unsigned char> b = pattern(5000, 2);
    ring.upload(dst.get(), 100000, b.data(), b.size());
    ring.flush();
    ring.wait_idle();
    const std::vector<unsigned char> got = read_buffer(ctx(), dst.get(), 0, kTarget);
    for (std::size_t i = 0; i < a.size(); ++i)
        ASSERT_EQ(got[i], a[i]) << i;
    for (std::size_t i = 0; i < b.size(); ++i)
        ASSERT_EQ(got[100000 + i], b[i]) << i;
}

TEST_F(StagingRingTest, EveryByteLandsThroughRandomSizesFlushesAndWaits) {
    StagingRing ring(ctx(), kRing);
    Buffer dst = target();
    std::vector<unsigned char> expected(kTarget, 0);
    ring.upload(dst.get(), 0, expected.data(), expected.size());  // zeros, through the ring
    std::mt19937 rng(62);
    for (std::uint32_t k = 0; k < 300; ++k) {
        // Sizes from 1 byte to three rings, at any offset (4-byte aligned, as the mirror's).
        const std::size_t bytes = 1 + rng() % (k % 7 == 0 ? 3 * kRing : 6000);
        const std::size_t offset = 4 * (rng() % ((kTarget - bytes) / 4));
        const std::vector<unsigned char> data = pattern(bytes, k + 3);
        ring.upload(dst.get(), offset, data.data(), data.size());
        std::copy(data.begin(), data.end(), expected.begin() + static_cast<std::ptrdiff_t>(offset));
        if (rng() % 3 == 0) ring.flush();
        if (rng() % 5 == 0) ring.wait_idle();
    }
    ring.flush();
    ring.wait_idle();
    EXPECT_EQ(read_buffer(ctx(), dst.get(), 0, kTarget), expected);
}

}  // namespace
}  // namespace sandtin::gpu
