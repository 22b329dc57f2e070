#include "haptics/diagnostics/spin_probe.hpp"

#include <time.h>

#include <algorithm>
#include <stdexcept>
#include <thread>

#include "haptics/loop_observer.hpp"

namespace sandtin::haptics {

GapStats::GapStats(std::int64_t threshold_ns) : threshold_ns_(threshold_ns) {
    if (threshold_ns <= 0) throw std::invalid_argument("gap stats: threshold must be > 0");
}

void GapStats::begin(std::int64_t t_ns) {
    last_ = t_ns;
    in_burst_ = true;
}

void GapStats::read(std::int64_t t_ns) {
    if (!in_burst_) {
        begin(t_ns);
        return;
    }
    const std::int64_t gap = t_ns - last_;
    last_ = t_ns;
    observed_ns_ += gap;
    max_gap_ns_ = std::max(max_gap_ns_, gap);
    if (gap <= threshold_ns_) return;
    ++gaps_;
    stolen_ns_ += gap;
    std::size_t b = 0;
    while (b < kBucketEdgesNs.size() && gap >= kBucketEdgesNs[b])
        ++b;
    ++buckets_[b];
}

SpinProbeResult run_spin_probe(const SpinProbeOptions& o) {
    if (!(o.seconds > 0.0) || o.seconds > 3600.0)
        throw std::invalid_argument("spin probe: seconds must be in (0, 3600]");
    if (o.burst_ns <= 0 || o.sleep_ns < 0)
        throw std::invalid_argument("spin probe: burst must be > 0 and sleep >= 0");
    SpinProbeResult result;
    result.gaps = GapStats(o.threshold_ns);
    std::thread probe([&] {
        result.grant = make_this_thread_realtime(o.realtime);
        const std::vector<std::int64_t> steal_before = read_cpu_steal_ns();
        const ThreadCounters before = read_this_thread_counters();
        const std::int64_t end = monotonic_ns() + static_cast<std::int64_t>(o.seconds * 1e9);
        for (std::int64_t now = monotonic_ns(); now < end; now = monotonic_ns()) {
            result.gaps.begin(now);
            const std::int64_t burst_end = std::min(end, now + o.burst_ns);
            while (now < burst_end) {
                now = monotonic_ns();
                result.gaps.read(now);
            }
            if (o.sleep_ns > 0) {
                const timespec ts{static_cast<time_t>(o.sleep_ns / 1'000'000'000),
                                  static_cast<long>(o.sleep_ns % 1'000'000'000)};
                nanosleep(&ts, nullptr);
            }
        }
        result.during = difference(read_this_thread_counters(), before);
        const std::vector<std::int64_t> steal_after = read_cpu_steal_ns();
        for (std::size_t c = 0; c < std::min(steal_before.size(), steal_after.size()); ++c)
            result.steal_ns.push_back(steal_after[c] - steal_before[c]);
    });
    probe.join();
    return result;
}

}  // namespace sandtin::haptics
