// The relaxation's active set (engine/physics/active_set.hpp) against a plain model: an
// ordered list without repeats where activation appends, removal erases one id at a time and
// ageing drops ids that stayed still `quiet_limit` times. Random interleavings of the three,
// with batch removals that repeat ids and name ids that are not members, must leave the same
// list in the same order and the same membership answers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "physics/active_set.hpp"

namespace sandtin {
namespace {

struct ModelSet {
    std::vector<std::uint32_t> list;
    std::map<std::uint32_t, int> quiet;

    bool contains(std::uint32_t v) const {
        return std::find(list.begin(), list.end(), v) != list.end();
    }
    void activate(std::uint32_t v) {
        quiet[v] = 0;
        if (!contains(v)) list.push_back(v);
    }
    void remove_one(std::uint32_t v) { std::erase(list, v); }
    void age(const std::vector<std::uint8_t>& changed, int limit) {
        std::vector<std::uint32_t> kept;
        for (std::uint32_t v : list) {
            if (v < changed.size() && changed[v]) {
                quiet[v] = 0;
            } else if (++quiet[v] >= limit) {
                continue;
            }
            kept.push_back(v);
        }
        list = kept;
    }
};

TEST(ActiveSet, BatchRemovalKeepsTheOrderOfOneByOneErasure) {
    constexpr std::uint32_t kIds = 300;
    std::mt19937 rng(12);
    std::uniform_int_distribution<std::uint32_t> id(0, kIds - 1);
    std::uniform_int_distribution<int> op(0, 9);
    ActiveSet set;
    ModelSet model;
    for (int round = 0; round < 3000; ++round) {
        const int o = op(rng);
        if (o < 5) {
            const std::uint32_t v = id(rng);
            set.activate(v);
            model.activate(v);
        } else if (o < 8) {
            // A batch of dead ids: some members, some not, some twice.
            std::vector<std::uint32_t> batch;
            const int count = 1 + static_cast<int>(id(rng) % 12);
            for (int k = 0; k < count; ++k) {
                const std::uint32_t v = k % 3 == 0 && !model.list.empty()
                                            ? model.list[id(rng) % model.list.size()]
                                            : id(rng);
                batch.push_back(v);
                if (k % 4 == 1) batch.push_back(v);
            }
            set.remove(batch);
            for (std::uint32_t v : batch)
                model.remove_one(v);
        } else {
            std::vector<std::uint8_t> changed(kIds, 0);
            for (int k = 0; k < 20; ++k)
                changed[id(rng)] = 1;
            set.age(changed, 3);
            model.age(changed, 3);
        }
        ASSERT_EQ(set.list(), model.list) << "round " << round;
    }
    for (std::uint32_t v = 0; v < kIds + 70; ++v)
        EXPECT_EQ(set.contains(v), model.contains(v)) << v;
}

TEST(ActiveSet, RemovedIdsCanComeBackAtTheEnd) {
    ActiveSet set;
    for (std::uint32_t v : {5u, 70u, 3u, 200u})
        set.activate(v);
    const std::vector<std::uint32_t> dead = {70u, 3u, 999u};
    set.remove(dead);
    EXPECT_EQ(set.list(), (std::vector<std::uint32_t>{5u, 200u}));
    EXPECT_FALSE(set.contains(70u));
    EXPECT_FALSE(set.contains(999u));
    set.activate(70u);
    EXPECT_EQ(set.list(), (std::vector<std::uint32_t>{5u, 200u, 70u}));
    set.remove({});
    EXPECT_EQ(set.size(), 3u);
}

}  // namespace
}  // namespace sandtin
