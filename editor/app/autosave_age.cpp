#include "autosave_age.hpp"

#include <algorithm>
#include <ctime>

#include "io/autosave.hpp"

namespace sandtin::editor {

namespace {

std::tm local_time(std::chrono::system_clock::time_point t) {
    const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
    std::tm tm{};
    localtime_r(&seconds, &tm);
    return tm;
}

/// "less than a minute ago", "1 minute ago", "5 hours ago", "3 days ago".
std::string age_words(std::chrono::seconds age) {
    const auto count = [](long long n, const char* unit) {
        return std::to_string(n) + " " + unit + (n == 1 ? "" : "s") + " ago";
    };
    const long long s = age.count();
    if (s < 60) return "less than a minute ago";
    if (s < 3600) return count(s / 60, "minute");
    if (s < 48 * 3600) return count(s / 3600, "hour");
    return count(s / (24 * 3600), "day");
}

}  // namespace

std::string autosave_age_text(std::chrono::system_clock::time_point written,
                              std::chrono::system_clock::time_point now) {
    const std::tm w = local_time(written), n = local_time(now);
    const bool today = w.tm_year == n.tm_year && w.tm_yday == n.tm_yday;
    char when[64];
    std::strftime(when, sizeof(when), today ? "%H:%M" : "%Y-%m-%d %H:%M", &w);
    // A minute's grace: the file system's clock and this one may disagree by a little.
    const auto age = std::chrono::duration_cast<std::chrono::seconds>(now - written);
    if (age < -std::chrono::seconds(60)) return std::string("autosave from ") + when;
    return "autosave from " + age_words(std::max(age, std::chrono::seconds(0))) + ", " + when;
}

std::optional<std::chrono::system_clock::time_point> autosave_written_at(
    const std::filesystem::path& scene) {
    std::error_code ec;
    const auto written = std::filesystem::last_write_time(autosave_path(scene), ec);
    if (ec) return std::nullopt;
    return std::chrono::time_point_cast<std::chrono::system_clock::duration>(
        std::chrono::file_clock::to_sys(written));
}

}  // namespace sandtin::editor
