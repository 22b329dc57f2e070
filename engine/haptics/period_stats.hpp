#pragma once
// Statistics of loop periods: a fixed histogram (1 µs bins up to 20 ms, then one overflow bin)
// plus the exact maximum, so recording a period never allocates and percentiles cost one pass.

#include <cstdint>
#include <vector>

namespace sandtin::haptics {

struct PeriodSummary {
    std::uint64_t count = 0;
    double target_ms = 0.0;
    double mean_ms = 0.0;
    double p50_ms = 0.0;
    double p99_ms = 0.0;
    double max_ms = 0.0;
    /// Periods longer than 110 % of the target: the p99 target of the issue, so
    /// "p99 <= 1.1 ms" at 1 kHz holds exactly when overruns <= 1 % of the ticks.
    std::uint64_t overruns = 0;
};

class PeriodStats {
  public:
    /// `target_ns` > 0 is the nominal period.
    explicit PeriodStats(std::int64_t target_ns);

    void add(std::int64_t period_ns);
    /// Percentiles are bin upper edges (1 µs resolution); periods beyond 20 ms count as the max.
    PeriodSummary summary() const;
    void clear();

  private:
    static constexpr std::int64_t kBinNs = 1000;
    static constexpr std::size_t kBins = 20000;

    std::int64_t target_ns_;
    std::vector<std::uint32_t> bins_;  // kBins + 1 (overflow)
    std::uint64_t count_ = 0;
    std::uint64_t overruns_ = 0;
    std::int64_t max_ns_ = 0;
    double sum_ns_ = 0.0;
};

}  // namespace sandtin::haptics
