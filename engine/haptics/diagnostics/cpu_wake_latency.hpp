#pragma once
// Keeps the CPUs from sleeping deeply while a force loop runs, through the kernel's PM QoS
// interface: writing a maximum wake-up latency to /dev/cpu_dma_latency and keeping the file
// open (the request ends when it is closed). With 0, idle CPUs poll instead of halting.
//
// Why: on a virtual machine a halted virtual CPU is descheduled by the host, and the loop's
// timer then wakes it only when the host runs it again, which measured 1-6 ms late at times
// on the 2-core VM (bench haptics: late ticks all "wakeup", none in the run queue). A polling
// idle CPU takes its timer interrupt at once. On bare metal it avoids deep C-state exits. It is
// what cyclictest does. The cost: idle CPUs spin (power, and host CPU time on a VM), so only
// while the loop runs, and only when asked.
// Needs write access to the device (root on most systems); refusal is reported, not thrown.

#include <cstdint>
#include <string>

namespace sandtin::haptics {

class CpuWakeLatencyHold {
  public:
    /// Requests at most `max_latency_us` (>= 0) of wake-up latency until destroyed.
    /// `device` is for tests.
    explicit CpuWakeLatencyHold(std::int32_t max_latency_us,
                                const char* device = "/dev/cpu_dma_latency");
    ~CpuWakeLatencyHold();
    CpuWakeLatencyHold(const CpuWakeLatencyHold&) = delete;
    CpuWakeLatencyHold& operator=(const CpuWakeLatencyHold&) = delete;

    bool held() const { return fd_ >= 0; }
    /// Why the request could not be made (empty when held).
    const std::string& error() const { return error_; }

  private:
    int fd_ = -1;
    std::string error_;
};

}  // namespace sandtin::haptics
