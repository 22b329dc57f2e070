// SessionKeeper: a copy of the terrain kept current from its journal is, whenever an autosave
// takes it, what Tin::snapshot() gives at that moment; byte for byte in the session file,
// which is what an autosave writes. While the writer still holds it, the frame's edits wait,
// and a second autosave copies the terrain whole instead.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "io/session_file.hpp"
#include "io/session_keeper.hpp"
#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

double dunes(Vec2 p) {
    return 0.5 + 0.1 * std::sin(2.0 * p.x) + 0.05 * std::cos(3.0 * p.y);
}

/// The session file of the terrain as it is now, as a whole snapshot gives it.
std::vector<std::uint8_t> file_now(const Tin& tin, Generation generation) {
    Session s;
    s.terrain = tin.snapshot();
    s.next_generation = generation;
    s.metadata_json = R"({"name":"dunes"})";
    return encode_session(s);
}

std::vector<std::uint8_t> file_of(const SessionSource& source) {
    return encode_session(source());
}

/// Random edits of every kind the journal reports: points in and out, constraints made and
/// released, and every per-vertex attribute.
class Edits {
  public:
    explicit Edits(std::uint64_t seed) : rng_(test::test_rng(seed)) {}
    void apply(Tin& tin, int count) {
        std::uniform_real_distribution<double> at(0.2, 9.8);
        std::uniform_int_distribution<int> kind(0, 8);
        for (int i = 0; i < count; ++i) {
            const std::vector<VertexId> live = test::live_ids(tin);
            const VertexId v =
                live[std::uniform_int_distribution<std::size_t>(0, live.size() - 1)(rng_)];
            switch (kind(rng_)) {
                case 0:
                    tin.insert_point({at(rng_), at(rng_)}, at(rng_) * 0.1);
                    break;
                case 1:
                    tin.insert_point_on_surface({at(rng_), at(rng_)});
                    break;
                case 2:
                    if (!tin.is_boundary(v) && !tin.is_on_constraint(v))
                        tin.remove_vertex(v, VolumePolicy::Report);
                    break;
                case 3: {
                    const VertexId a = tin.insert_point({at(rng_), at(rng_)}, 0.6);
                    const VertexId b = tin.insert_point({at(rng_), at(rng_)}, 0.4);
                    if (a != b) made_.push_back(tin.insert_constraint(a, b, ++generation_));
                    break;
                }
                case 4:
                    if (!made_.empty()) {
                        tin.release_constraint(made_.back());
                        made_.pop_back();
                    }
                    break;
                case 5:
                    tin.set_height(v, tin.height(v) + 0.01);
                    break;
                case 6:
                    tin.set_material(v, static_cast<std::uint16_t>(v.value % 4));
                    break;
                case 7:
                    tin.set_moisture(v, 0.25f);
                    break;
                default:
                    tin.set_slide(v, {0.125f, 0.75f});
                    tin.set_bedrock(v, tin.height(v) - 0.2);
                    break;
            }
        }
    }
    Generation generation() const { return generation_ + 1; }

  private:
    std::mt19937_64 rng_;
    std::vector<ConstraintId> made_;
    Generation generation_ = 0;
};

TEST(SessionKeeper, AKeptSessionIsTheWholeSnapshotAfterEveryKindOfEdit) {
    Tin tin = Tin::random_points(Rect::from_size(10.0, 10.0), 400, 9, dunes);
    tin.set_track_changes(false);
    SessionKeeper every_frame(tin);
    SessionKeeper only_when_asked(tin);  // never follows: takes everything at hand-out
    Edits edits(21);
    for (int frame = 1; frame <= 60; ++frame) {
        edits.apply(tin, 3);
        every_frame.follow();
        if (frame % 6 != 0) continue;
        SCOPED_TRACE("frame " + std::to_string(frame));
        const std::vector<std::uint8_t> expected = file_now(tin, edits.generation());
        EXPECT_EQ(file_of(every_frame.hand_out(edits.generation(), R"({"name":"dunes"})")),
                  expected);
        EXPECT_EQ(file_of(only_when_asked.hand_out(edits.generation(), R"({"name":"dunes"})")),
                  expected);
    }
    EXPECT_TRUE(tin.check_valid().ok());
    EXPECT_EQ(every_frame.whole_copies(), 0u);
    EXPECT_EQ(only_when_asked.whole_copies(), 0u);
}

TEST(SessionKeeper, WhileASourceIsOutTheEditsWaitAndASecondAutosaveCopiesWhole) {
    Tin tin = Tin::random_points(Rect::from_size(10.0, 10.0), 300, 4, dunes);
    tin.set_track_changes(false);
    SessionKeeper keeper(tin);
    Edits edits(5);
    edits.apply(tin, 10);
    const std::vector<std::uint8_t> before = file_now(tin, 7);
    std::optional<SessionSource> first = keeper.hand_out(7, R"({"name":"dunes"})");
    // Edited while the first source has not copied yet: it still gives the terrain it was
    // handed out for.
    edits.apply(tin, 10);
    keeper.follow();
    const std::vector<std::uint8_t> after = file_now(tin, 8);
    ASSERT_NE(before, after);
    EXPECT_EQ(file_of(keeper.hand_out(8, R"({"name":"dunes"})")), after);
    EXPECT_EQ(keeper.whole_copies(), 1u) << "the kept copy was out";
    EXPECT_EQ(file_of(*first), before);
    // Given back by its copy: the edits it waited for reach the kept copy.
    edits.apply(tin, 10);
    keeper.follow();
    EXPECT_EQ(file_of(keeper.hand_out(9, R"({"name":"dunes"})")), file_now(tin, 9));
    EXPECT_EQ(keeper.whole_copies(), 1u);

    // A source dropped uncalled (an autosave replaced in the writer's queue) gives it back too.
    first = keeper.hand_out(10, R"({"name":"dunes"})");
    first.reset();
    edits.apply(tin, 10);
    keeper.follow();
    EXPECT_EQ(file_of(keeper.hand_out(11, R"({"name":"dunes"})")), file_now(tin, 11));
    EXPECT_EQ(keeper.whole_copies(), 1u);
}

}  // namespace
}  // namespace sandtin
