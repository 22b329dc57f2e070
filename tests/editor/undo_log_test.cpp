// The editor's undo order over terrain levels and material edits: the artist's order both
// ways, a new level clears redo, material entries carry both tables, and the log is bounded.

#include <gtest/gtest.h>

#include "undo_log.hpp"

namespace sandtin::editor {
namespace {

MaterialTable with_dry_angle(double radians) {
    std::vector<Material> all = MaterialTable::presets().all();
    all[0].repose_dry = radians;
    return MaterialTable(all);
}

TEST(UndoLog, InterleavesTerrainLevelsAndMaterialEditsInOrder) {
    UndoLog log;
    EXPECT_FALSE(log.can_undo());
    EXPECT_FALSE(log.undo().has_value());
    log.push_terrain("stroke");
    log.push_materials(with_dry_angle(0.5), with_dry_angle(0.3));
    log.push_terrain("erosion");
    EXPECT_EQ(log.levels(), 3u);

    auto e = log.undo();
    ASSERT_TRUE(e && e->terrain);
    EXPECT_EQ(e->label, "erosion");
    e = log.undo();
    ASSERT_TRUE(e && !e->terrain);
    EXPECT_DOUBLE_EQ(e->before.at(0).repose_dry, 0.5);
    EXPECT_DOUBLE_EQ(e->after.at(0).repose_dry, 0.3);
    e = log.redo();
    ASSERT_TRUE(e && !e->terrain);
    EXPECT_DOUBLE_EQ(e->after.at(0).repose_dry, 0.3);
    e = log.undo();
    ASSERT_TRUE(e && !e->terrain);
    e = log.undo();
    ASSERT_TRUE(e && e->terrain);
    EXPECT_EQ(e->label, "stroke");
    EXPECT_FALSE(log.can_undo());
    EXPECT_TRUE(log.can_redo());

    // A new level after undoing clears the redo list.
    log.push_materials(with_dry_angle(0.5), with_dry_angle(0.4));
    EXPECT_FALSE(log.can_redo());
    EXPECT_FALSE(log.redo().has_value());
    EXPECT_EQ(log.levels(), 1u);
}

TEST(UndoLog, ForgetsTheOldestLevelsBeyondItsBound) {
    UndoLog log;
    for (std::size_t i = 0; i < UndoLog::kMaxLevels + 10; ++i)
        log.push_terrain("level " + std::to_string(i));
    EXPECT_EQ(log.levels(), UndoLog::kMaxLevels);
    EXPECT_EQ(log.undo()->label, "level " + std::to_string(UndoLog::kMaxLevels + 9));
}

TEST(UndoLog, TheReadoutCountsLevelsInGoodEnglish) {
    // It said "1 levels".
    EXPECT_EQ(undo_levels_text(0, 0), "0 levels, 0.0 MB");
    EXPECT_EQ(undo_levels_text(1, 104858), "1 level, 0.1 MB");
    EXPECT_EQ(undo_levels_text(3, 2621440), "3 levels, 2.5 MB");
}

}  // namespace
}  // namespace sandtin::editor
