#include "haptics/period_stats.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sandtin::haptics {

PeriodStats::PeriodStats(std::int64_t target_ns) : target_ns_(target_ns), bins_(kBins + 1, 0) {
    if (target_ns <= 0) throw std::invalid_argument("period stats: target period must be > 0");
}

void PeriodStats::clear() {
    std::fill(bins_.begin(), bins_.end(), 0u);
    count_ = 0;
    overruns_ = 0;
    max_ns_ = 0;
    sum_ns_ = 0.0;
}

void PeriodStats::add(std::int64_t period_ns) {
    period_ns = std::max<std::int64_t>(period_ns, 0);
    const auto bin = static_cast<std::size_t>(period_ns / kBinNs);
    ++bins_[std::min(bin, kBins)];
    ++count_;
    sum_ns_ += static_cast<double>(period_ns);
    max_ns_ = std::max(max_ns_, period_ns);
    if (period_ns * 10 > target_ns_ * 11) ++overruns_;
}

PeriodSummary PeriodStats::summary() const {
    PeriodSummary s;
    s.count = count_;
    s.target_ms = static_cast<double>(target_ns_) * 1e-6;
    s.overruns = overruns_;
    s.max_ms = static_cast<double>(max_ns_) * 1e-6;
    if (count_ == 0) return s;
    s.mean_ms = sum_ns_ / static_cast<double>(count_) * 1e-6;
    const auto percentile = [&](double q) {
        // Nearest rank: the smallest bin edge with ceil(q n) samples at or below it.
        const auto need = std::max<std::uint64_t>(
            1, static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_))));
        std::uint64_t seen = 0;
        for (std::size_t b = 0; b < kBins; ++b) {
            seen += bins_[b];
            if (seen >= need) {
                const double edge_ms = static_cast<double>((b + 1) * kBinNs) * 1e-6;
                return std::min(edge_ms, s.max_ms);
            }
        }
        return s.max_ms;
    };
    s.p50_ms = percentile(0.50);
    s.p99_ms = percentile(0.99);
    return s;
}

}  // namespace sandtin::haptics
