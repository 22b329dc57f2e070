#include "progress_line.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>

namespace sandtin::cli {

namespace {

/// Redraws closer together than this only flicker, and cost the work time on a slow terminal.
constexpr std::chrono::milliseconds kRedrawInterval{100};

/// The terminal's width in columns; 80 when it does not say (a bare pseudo-terminal).
std::size_t terminal_columns() {
    winsize w{};
    if (ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
    return 80;
}

/// `text` cut to at most `bytes`, never inside a UTF-8 character.
std::string_view utf8_prefix(std::string_view text, std::size_t bytes) {
    if (text.size() <= bytes) return text;
    while (bytes > 0 && (static_cast<unsigned char>(text[bytes]) & 0xC0) == 0x80)
        --bytes;
    return text.substr(0, bytes);
}

/// Title and stage in at most `room` bytes. What the work does now matters most: the title is
/// shortened ("import dem...: refining"), then left out, and only then is the stage cut.
std::string fit_head(std::string_view title, std::string_view stage, std::size_t room) {
    constexpr std::string_view kCut = "...";
    constexpr std::size_t kShortestTitle = 8;
    const std::string sep = stage.empty() ? "" : ": ";
    if (title.size() + sep.size() + stage.size() <= room)
        return std::string(title) + sep + std::string(stage);
    if (stage.size() + sep.size() + kCut.size() + kShortestTitle <= room) {
        const std::size_t keep = room - stage.size() - sep.size() - kCut.size();
        return std::string(utf8_prefix(title, keep)) + std::string(kCut) + sep + std::string(stage);
    }
    const std::string_view head = stage.empty() ? title : stage;
    if (head.size() <= room) return std::string(head);
    return std::string(utf8_prefix(head, room > kCut.size() ? room - kCut.size() : 0)) +
           std::string(kCut);
}

}  // namespace

bool stderr_is_terminal() {
    return isatty(STDERR_FILENO) == 1;
}

std::string format_duration(double seconds) {
    char text[32];
    if (!(seconds >= 0.0)) seconds = 0.0;
    if (seconds < 60.0) {
        std::snprintf(text, sizeof text, "%.1f s", seconds);
    } else if (seconds < 3600.0) {
        const auto s = static_cast<long>(seconds);
        std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
    } else {
        const auto m = static_cast<long>(seconds / 60.0);
        std::snprintf(text, sizeof text, "%ld h %02ld min", m / 60, m % 60);
    }
    return text;
}

std::string progress_text(std::string_view title, std::string_view stage, double fraction,
                          double elapsed_seconds) {
    const double f = std::clamp(fraction, 0.0, 1.0);
    std::string text(title);
    if (!stage.empty()) {
        text += ": ";
        text += stage;
    }
    // Rounded down: 99.6 % of the work is not done.
    text += "  " + std::to_string(static_cast<int>(std::floor(f * 100.0))) + "%";
    text += "  elapsed " + format_duration(elapsed_seconds);
    if (f >= 1.0) return text;
    text += f > 0.0 ? "  left ~" + format_duration(elapsed_seconds * (1.0 - f) / f)
                    : std::string("  left: estimating");
    return text;
}

ProgressLine::ProgressLine(std::string title, bool enabled)
    : title_(std::move(title)), enabled_(enabled), start_(std::chrono::steady_clock::now()) {
    if (enabled_) draw();
}

ProgressLine::~ProgressLine() {
    stop();
}

void ProgressLine::report(const Progress& progress) {
    if (!enabled_ || ended_) return;
    // The engine promises non-decreasing fractions; a listener need not trust it to draw.
    fraction_ = std::max(fraction_, std::clamp(progress.fraction, 0.0, 1.0));
    stage_.assign(progress.stage);
    if (!drawn_ || std::chrono::steady_clock::now() - last_draw_ >= kRedrawInterval) draw();
}

ProgressCallback ProgressLine::callback() {
    if (!enabled_) return {};
    return [this](const Progress& p) { report(p); };
}

void ProgressLine::finish() {
    if (!enabled_ || ended_) return;
    // Always a last drawing that says done: the work's own last report may have drawn 100 %
    // with its stage ("operation 60 of 60"), and the line must end saying the work is done
    // (cli.progress_stress failed on a clean clone when that report fell due for a redraw).
    fraction_ = 1.0;
    stage_ = "done";
    draw();
    stop();
}

void ProgressLine::draw() {
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::string text = progress_text(title_, stage_, fraction_, elapsed);
    // A line wider than the terminal wraps, and '\r' then redraws only its last row: the
    // title gives way first, then the stage; the numbers stay.
    const std::size_t columns = terminal_columns() - 1;
    if (text.size() > columns) {
        const std::string numbers = progress_text("", "", fraction_, elapsed);
        const std::size_t room = columns > numbers.size() ? columns - numbers.size() : 0;
        text = fit_head(title_, stage_, room) + numbers;
    }
    const std::size_t width = text.size();
    // Blank what a longer previous line leaves on the right.
    if (width < width_) text.append(width_ - width, ' ');
    std::cerr << '\r' << text << std::flush;
    width_ = width;
    last_draw_ = now;
    drawn_ = true;
}

void ProgressLine::stop() {
    if (!enabled_ || ended_) return;
    ended_ = true;
    std::cerr << '\n' << std::flush;
}

}  // namespace sandtin::cli
