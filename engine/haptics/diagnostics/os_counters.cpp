#include "haptics/diagnostics/os_counters.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <charconv>

namespace sandtin::haptics {

namespace {

std::string_view skip_spaces(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    return s;
}

// Reads one unsigned decimal field after optional blanks; advances `s` past it.
std::optional<std::int64_t> next_number(std::string_view& s) {
    s = skip_spaces(s);
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || v < 0) return std::nullopt;
    s.remove_prefix(static_cast<std::size_t>(end - s.data()));
    return v;
}

}  // namespace

std::optional<SchedStat> parse_schedstat(std::string_view text) {
    SchedStat s;
    const auto a = next_number(text);
    const auto b = next_number(text);
    const auto c = next_number(text);
    if (!a || !b || !c) return std::nullopt;
    s.cpu_ns = *a;
    s.run_delay_ns = *b;
    s.slices = *c;
    return s;
}

std::optional<std::vector<std::int64_t>> parse_cpu_steal_ns(std::string_view text,
                                                            long ticks_per_second) {
    if (ticks_per_second <= 0) return std::nullopt;
    std::vector<std::int64_t> steal;
    while (!text.empty()) {
        const auto eol = text.find('\n');
        std::string_view line = text.substr(0, eol);
        text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
        if (line.size() < 4 || line.substr(0, 3) != "cpu" || line[3] < '0' || line[3] > '9')
            continue;
        line.remove_prefix(3);
        const auto cpu = next_number(line);
        if (!cpu || *cpu > 65535) return std::nullopt;
        // user nice system idle iowait irq softirq steal
        std::optional<std::int64_t> field;
        for (int i = 0; i < 8; ++i) {
            field = next_number(line);
            if (!field) return std::nullopt;
        }
        const auto index = static_cast<std::size_t>(*cpu);
        if (steal.size() <= index) steal.resize(index + 1, 0);
        steal[index] = *field * (1'000'000'000 / ticks_per_second);
    }
    if (steal.empty()) return std::nullopt;
    return steal;
}

std::optional<std::string> read_small_file(const char* path) {
    const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return std::nullopt;
    std::string text;
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0) {
            ::close(fd);
            return std::nullopt;
        }
        if (n == 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fd);
    return text;
}

ThreadCounters read_this_thread_counters() {
    ThreadCounters c;
    // Faults first: reading the proc file below allocates, which may fault and must not be
    // counted against what came before the call.
    rusage u{};
    if (getrusage(RUSAGE_THREAD, &u) == 0) {
        c.voluntary_switches = u.ru_nvcsw;
        c.involuntary_switches = u.ru_nivcsw;
        c.minor_faults = u.ru_minflt;
        c.major_faults = u.ru_majflt;
    }
    if (const auto text = read_small_file("/proc/thread-self/schedstat")) {
        if (const auto s = parse_schedstat(*text)) c.sched = *s;
    }
    return c;
}

ThreadCounters difference(const ThreadCounters& after, const ThreadCounters& before) {
    const auto d = [](std::int64_t a, std::int64_t b) { return a < 0 || b < 0 ? -1 : a - b; };
    ThreadCounters r;
    r.sched.cpu_ns = d(after.sched.cpu_ns, before.sched.cpu_ns);
    r.sched.run_delay_ns = d(after.sched.run_delay_ns, before.sched.run_delay_ns);
    r.sched.slices = d(after.sched.slices, before.sched.slices);
    r.voluntary_switches = d(after.voluntary_switches, before.voluntary_switches);
    r.involuntary_switches = d(after.involuntary_switches, before.involuntary_switches);
    r.minor_faults = d(after.minor_faults, before.minor_faults);
    r.major_faults = d(after.major_faults, before.major_faults);
    return r;
}

std::vector<std::int64_t> read_cpu_steal_ns() {
    const auto text = read_small_file("/proc/stat");
    if (!text) return {};
    auto steal = parse_cpu_steal_ns(*text, sysconf(_SC_CLK_TCK));
    return steal ? std::move(*steal) : std::vector<std::int64_t>{};
}

}  // namespace sandtin::haptics
