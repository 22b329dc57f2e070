// The recovery prompt's words for an autosave's age (editor/app/autosave_age.hpp).

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <optional>
#include <string>

#include "autosave_age.hpp"

namespace sandtin::editor {
namespace {

using namespace std::chrono;

/// 2026-12-05 14:02:30 in UTC, which the test sets as the local time zone.
system_clock::time_point at_1402() {
    return sys_days{year{2026} / 12 / 5} + hours{14} + minutes{2} + seconds{30};
}

class AutosaveAge : public ::testing::Test {
  protected:
    void SetUp() override {
        const char* tz = std::getenv("TZ");
        saved_tz_ = tz != nullptr ? std::optional<std::string>(tz) : std::nullopt;
        setenv("TZ", "UTC", 1);
        tzset();
    }
    void TearDown() override {
        if (saved_tz_)
            setenv("TZ", saved_tz_->c_str(), 1);
        else
            unsetenv("TZ");
        tzset();
    }
    std::optional<std::string> saved_tz_;
};

TEST_F(AutosaveAge, SaysHowLongAgoAndWhen) {
    const auto w = at_1402();
    EXPECT_EQ(autosave_age_text(w, w + seconds{20}), "autosave from less than a minute ago, 14:02");
    EXPECT_EQ(autosave_age_text(w, w + seconds{65}), "autosave from 1 minute ago, 14:02");
    EXPECT_EQ(autosave_age_text(w, w + minutes{3} + seconds{10}),
              "autosave from 3 minutes ago, 14:02");
    EXPECT_EQ(autosave_age_text(w, w + hours{1} + minutes{5}), "autosave from 1 hour ago, 14:02");
    // Another day: the date too.
    EXPECT_EQ(autosave_age_text(w, w + hours{30}), "autosave from 30 hours ago, 2026-12-05 14:02");
    EXPECT_EQ(autosave_age_text(w, w + days{9}), "autosave from 9 days ago, 2026-12-05 14:02");
    // A clock set back: no age it cannot know, only the time.
    EXPECT_EQ(autosave_age_text(w, w - hours{2}), "autosave from 14:02");
    EXPECT_EQ(autosave_age_text(w, w - seconds{30}), "autosave from less than a minute ago, 14:02");
}

}  // namespace
}  // namespace sandtin::editor
