// The Erosion panel's state line says what is known: paused erosion claims no sliding.

#include <gtest/gtest.h>

#include "erosion_status.hpp"

namespace sandtin::editor {
namespace {

TEST(ErosionStatus, PausedErosionClaimsNothingAboutTheSand) {
    // The audit saw "sliding, 40800 active" on an untouched scene with the erosion paused.
    EXPECT_EQ(erosion_status_text(false, false, 40800), "paused");
    EXPECT_EQ(erosion_status_text(false, true, 0), "paused");
}

TEST(ErosionStatus, RunningErosionSaysAtRestOrHowManyVerticesSlide) {
    EXPECT_EQ(erosion_status_text(true, true, 0), "at rest");
    EXPECT_EQ(erosion_status_text(true, false, 263), "sliding, 263 active");
}

}  // namespace
}  // namespace sandtin::editor
