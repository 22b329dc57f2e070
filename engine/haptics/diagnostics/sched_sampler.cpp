#include "haptics/diagnostics/sched_sampler.hpp"

#include <fcntl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>

#include "haptics/diagnostics/os_counters.hpp"
#include "haptics/loop_observer.hpp"

namespace sandtin::haptics {

WindowAttribution attribute_window(const std::vector<SchedSample>& samples, std::int64_t from_ns,
                                   std::int64_t to_ns, int cpu) {
    WindowAttribution a;
    const auto after_from =
        std::upper_bound(samples.begin(), samples.end(), from_ns,
                         [](std::int64_t t, const SchedSample& s) { return t < s.time_ns; });
    if (after_from == samples.begin()) return a;
    const SchedSample& before = *(after_from - 1);
    const auto end =
        std::lower_bound(samples.begin(), samples.end(), to_ns,
                         [](const SchedSample& s, std::int64_t t) { return s.read_start_ns < t; });
    if (end == samples.end()) return a;
    const SchedSample& after = *end;
    a.covered = true;
    a.span_ns = after.time_ns - before.time_ns;
    if (after.run_delay_ns >= 0 && before.run_delay_ns >= 0)
        a.run_delay_ns = after.run_delay_ns - before.run_delay_ns;
    for (std::size_t c = 0; c < kSampledCpus; ++c) {
        if (after.steal_ns[c] < 0 || before.steal_ns[c] < 0) continue;
        const std::int64_t d = after.steal_ns[c] - before.steal_ns[c];
        a.steal_all_cpus_ns += d;
        if (static_cast<int>(c) == cpu) a.steal_on_cpu_ns = d;
    }
    return a;
}

SchedSampler::SchedSampler(int tid, std::int64_t interval_ns, std::size_t capacity)
    : tid_(tid), interval_ns_(interval_ns) {
    if (tid <= 0) throw std::invalid_argument("sched sampler: no thread to observe");
    if (interval_ns <= 0) throw std::invalid_argument("sched sampler: interval must be > 0");
    samples_.reserve(capacity);
}

SchedSampler::~SchedSampler() {
    stop();
}

void SchedSampler::start() {
    if (thread_.joinable()) throw std::logic_error("sched sampler: already started");
    stop_.store(false);
    thread_ = std::thread([this] { run(); });
}

void SchedSampler::stop() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
}

namespace {

std::optional<std::string_view> pread_text(int fd, char* buffer, std::size_t size) {
    if (fd < 0) return std::nullopt;
    const ssize_t n = ::pread(fd, buffer, size, 0);
    if (n <= 0) return std::nullopt;
    return std::string_view(buffer, static_cast<std::size_t>(n));
}

}  // namespace

void SchedSampler::run() {
    const std::string sched_path = "/proc/self/task/" + std::to_string(tid_) + "/schedstat";
    const int sched_fd = ::open(sched_path.c_str(), O_RDONLY | O_CLOEXEC);
    const int stat_fd = ::open("/proc/stat", O_RDONLY | O_CLOEXEC);
    const long ticks_per_second = sysconf(_SC_CLK_TCK);
    available_ = sched_fd >= 0 && stat_fd >= 0;
    std::string stat_buffer(64 * 1024, '\0');
    char sched_buffer[256];
    std::int64_t next = monotonic_ns();
    while (!stop_.load(std::memory_order_relaxed) && samples_.size() < samples_.capacity()) {
        SchedSample s;
        s.steal_ns.fill(-1);
        s.read_start_ns = monotonic_ns();
        if (const auto text = pread_text(sched_fd, sched_buffer, sizeof sched_buffer)) {
            if (const auto st = parse_schedstat(*text)) s.run_delay_ns = st->run_delay_ns;
        }
        if (const auto text = pread_text(stat_fd, stat_buffer.data(), stat_buffer.size())) {
            if (const auto steal = parse_cpu_steal_ns(*text, ticks_per_second)) {
                for (std::size_t c = 0; c < std::min(steal->size(), kSampledCpus); ++c)
                    s.steal_ns[c] = (*steal)[c];
            }
        }
        s.time_ns = monotonic_ns();
        samples_.push_back(s);
        next += interval_ns_;
        const std::int64_t now = monotonic_ns();
        if (next < now) next = now;
        timespec ts{static_cast<time_t>(next / 1'000'000'000),
                    static_cast<long>(next % 1'000'000'000)};
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
    }
    if (sched_fd >= 0) ::close(sched_fd);
    if (stat_fd >= 0) ::close(stat_fd);
}

}  // namespace sandtin::haptics
