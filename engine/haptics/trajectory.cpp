#include "haptics/trajectory.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "haptics/haptic_device.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::haptics {

namespace {

std::string number(double v) {
    char buffer[40];
    const int n = std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return std::string(buffer, static_cast<std::size_t>(n));
}

class LineReader {
  public:
    LineReader(std::string_view text, const std::string& name) : text_(text), name_(name) {}

    /// Next non-empty, non-comment line split into fields; false at the end.
    bool next(std::vector<std::string_view>& fields) {
        while (pos_ < text_.size()) {
            const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
            std::string_view line = text_.substr(pos_, end - pos_);
            pos_ = end + 1;
            ++line_;
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            fields.clear();
            std::size_t i = 0;
            while (i < line.size()) {
                while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
                    ++i;
                std::size_t j = i;
                while (j < line.size() && line[j] != ' ' && line[j] != '\t')
                    ++j;
                if (j > i) fields.push_back(line.substr(i, j - i));
                i = j;
            }
            if (fields.empty() || fields[0].front() == '#') continue;
            return true;
        }
        return false;
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(name_ + ":" + std::to_string(line_) + ": " + what);
    }
    double real(std::string_view field, const char* what) const {
        double v = 0.0;
        const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
        if (ec != std::errc() || ptr != field.data() + field.size() || !std::isfinite(v))
            fail(std::string(what) + " is not a finite number: '" + std::string(field) + "'");
        return v;
    }
    std::uint64_t integer(std::string_view field, const char* what) const {
        std::uint64_t v = 0;
        const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
        if (ec != std::errc() || ptr != field.data() + field.size())
            fail(std::string(what) + " is not a non-negative integer: '" + std::string(field) +
                 "'");
        return v;
    }

  private:
    std::string_view text_;
    const std::string& name_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
};

}  // namespace

std::string format_trajectory(const Trajectory& t) {
    std::string out;
    out.reserve(64 + t.samples.size() * 64);
    out += std::string(kTrajectoryMagic) + " " + std::to_string(kTrajectoryVersion) + "\n";
    out += "rate_hz " + number(t.rate_hz) + "\n";
    out += "samples " + std::to_string(t.samples.size()) + "\n";
    out += "# x y z (m) buttons\n";
    for (const TrajectorySample& s : t.samples) {
        out += number(s.position.x) + " " + number(s.position.y) + " " + number(s.position.z) +
               " " + std::to_string(s.buttons) + "\n";
    }
    return out;
}

Trajectory parse_trajectory(std::string_view text, const std::string& name) {
    LineReader reader(text, name);
    std::vector<std::string_view> f;
    if (!reader.next(f) || f[0] != kTrajectoryMagic)
        reader.fail("not a trajectory file (expected '" + std::string(kTrajectoryMagic) + " 1')");
    if (f.size() != 2) reader.fail("header needs exactly a version number");
    const std::uint64_t version = reader.integer(f[1], "version");
    if (version != kTrajectoryVersion)
        reader.fail("unsupported trajectory version " + std::to_string(version));
    Trajectory t;
    if (!reader.next(f) || f.size() != 2 || f[0] != "rate_hz")
        reader.fail("expected 'rate_hz <Hz>'");
    t.rate_hz = reader.real(f[1], "rate_hz");
    if (!(t.rate_hz > 0.0) || t.rate_hz > 100000.0) reader.fail("rate_hz must be in (0, 1e5]");
    if (!reader.next(f) || f.size() != 2 || f[0] != "samples")
        reader.fail("expected 'samples <count>'");
    const std::uint64_t count = reader.integer(f[1], "samples");
    if (count > 100'000'000) reader.fail("sample count is implausibly large");
    t.samples.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(count, 1u << 20)));
    while (reader.next(f)) {
        if (f.size() != 4) reader.fail("a sample needs 4 fields: x y z buttons");
        if (t.samples.size() == count) reader.fail("more samples than the header's count");
        TrajectorySample s;
        s.position = {reader.real(f[0], "x"), reader.real(f[1], "y"), reader.real(f[2], "z")};
        const std::uint64_t b = reader.integer(f[3], "buttons");
        if (b > 0xFFFFFFFFu) reader.fail("buttons does not fit 32 bits");
        s.buttons = static_cast<std::uint32_t>(b);
        t.samples.push_back(s);
    }
    if (t.samples.size() != count) {
        throw std::runtime_error(name + ": truncated: " + std::to_string(t.samples.size()) +
                                 " samples, header says " + std::to_string(count));
    }
    return t;
}

Trajectory load_trajectory(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path.string() + ": cannot open trajectory file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse_trajectory(ss.str(), path.string());
}

void save_trajectory(const std::filesystem::path& path, const Trajectory& trajectory) {
    const std::string text = format_trajectory(trajectory);
    write_file_atomically(
        path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                            text.size()));
}

Trajectory make_stroke_trajectory(const StrokeTrajectorySpec& s) {
    if (!(s.rate_hz > 0.0) || !(s.speed > 0.0) || !(s.descend_speed > 0.0) || !(s.dwell >= 0.0))
        throw std::invalid_argument("stroke trajectory: rates, speeds and dwell must be positive");
    Trajectory t;
    t.rate_hz = s.rate_hz;
    const double dt = 1.0 / s.rate_hz;
    const Vec3 top{s.start_x, s.start_y, s.surface + s.hover};
    const Vec3 bottom{s.start_x, s.start_y, s.surface - s.depth};
    const Vec3 end_bottom{s.end_x, s.end_y, s.surface - s.depth};
    const Vec3 end_top{s.end_x, s.end_y, s.surface + s.hover};
    const auto segment = [&](Vec3 a, Vec3 b, double speed, std::uint32_t buttons) {
        const double len = length(b - a);
        const auto n = static_cast<std::size_t>(std::ceil(len / (speed * dt)));
        for (std::size_t i = 0; i < n; ++i) {
            const double u = static_cast<double>(i) / static_cast<double>(n);
            t.samples.push_back({a + (b - a) * u, buttons});
        }
    };
    const auto dwell = [&](Vec3 p, std::uint32_t buttons) {
        const auto n = static_cast<std::size_t>(std::round(s.dwell / dt));
        for (std::size_t i = 0; i < n; ++i)
            t.samples.push_back({p, buttons});
    };
    dwell(top, 0);
    segment(top, bottom, s.descend_speed, 0);
    dwell(bottom, 1);
    segment(bottom, end_bottom, s.speed, 1);
    dwell(end_bottom, 1);
    segment(end_bottom, end_top, s.descend_speed, 0);
    dwell(end_top, 0);
    return t;
}

Trajectory make_circle_trajectory(const CircleTrajectorySpec& s) {
    if (!(s.rate_hz > 0.0) || !(s.seconds > 0.0) || !(s.period_s > 0.0))
        throw std::invalid_argument("circle trajectory: rate, duration and period must be > 0");
    Trajectory t;
    t.rate_hz = s.rate_hz;
    const auto n = static_cast<std::size_t>(std::round(s.seconds * s.rate_hz));
    t.samples.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double time = static_cast<double>(i) / s.rate_hz;
        const double phase = std::fmod(time, s.period_s) / s.period_s;  // [0, 1)
        const double angle = 2.0 * std::numbers::pi * phase + 0.7 * std::floor(time / s.period_s);
        // Press during the middle 80 % of each circle, with smooth (cosine) dips in and out.
        double z = s.surface + s.hover;
        std::uint32_t buttons = 0;
        if (phase > 0.05 && phase < 0.95) {
            const double w = std::min(1.0, std::min(phase - 0.05, 0.95 - phase) / 0.1);
            const double blend = 0.5 - 0.5 * std::cos(std::numbers::pi * w);
            z = s.surface + s.hover - (s.hover + s.depth) * blend;
            buttons = w >= 1.0 ? kMainButton : 0;
        }
        t.samples.push_back(
            {{s.cx + s.radius * std::cos(angle), s.cy + s.radius * std::sin(angle), z}, buttons});
    }
    return t;
}

}  // namespace sandtin::haptics
